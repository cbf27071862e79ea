// One stroke, played as the kiosk plays it and measured (gesture_response.h).
#include "calibration/gesture_response.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <opencv2/core.hpp>
#include <span>
#include <stdexcept>

#include "calibration/character.h"
#include "kiosk/gesture.h"
#include "kiosk/kiosk_engine.h"
#include "kiosk/pen_mapping.h"
#include "kiosk/synthetic_voice.h"
#include "surface/image_surface.h"
#include "surface/sound_image.h"
#include "surface/texture_set.h"
#include "synth/scene.h"
#include "tools/builtin_profiles.h"
#include "tools/render_command.h"

namespace sas::kiosk {
namespace {

constexpr double kTiltRubDeg = 40.0;
constexpr double kLandingMps = 0.005;

double PowerDb(double mean_square) {
  return 10.0 * std::log10(std::max(mean_square, 1e-30));
}

// Third-octave band edges: centre · 2^(±1/6), centres 100 · 10^(k/10) (ISO 266 base-10 series).
double BandCentreHz(int band) {
  return 100.0 * std::pow(10.0, band / 10.0);
}

struct Span {
  std::vector<float> sound;
  std::vector<float> haptic;
};

// Renders one stroke along (x0, y0) + s (dx, dy), s in [0, kPathMm], and returns the motion span.
Span PlayStroke(const ResponseSurface& surface, const HandStroke& stroke, double x0_mm,
                double y0_mm, double dx, double dy, double fs_hz) {
  const GestureMapping mapping;
  synth::Scene scene;
  scene.Init(fs_hz);
  scene.Prepare(surface.material, synth::OutputParams{}, surface.field->View());
  synth::ProbeCommand pen;
  pen.tip_down = true;
  pen.x_m = x0_mm * 1e-3;
  pen.y_m = y0_mm * 1e-3;
  // A rub is held tilted, scrape and roll upright; the style is the stroke's.
  ApplyPenPressure(stroke.pressure, surface::ReliefM(*surface.field), mapping, pen);
  ApplyPenTilt(stroke.style == synth::ProbeStyle::kRub ? kTiltRubDeg : 0.0, ProbeShape{},
               stroke.style, mapping, pen);
  pen.direction_x = dx;
  pen.direction_y = dy;
  pen.landing_speed_mps = kLandingMps;
  pen.velocity_mps = 0.0;

  const auto rest = static_cast<int>(std::lround(kRestS * fs_hz));
  const auto motion = static_cast<int>(std::lround(kPathMm / stroke.speed_mm_s * fs_hz));
  std::vector<float> buffer(2 * static_cast<std::size_t>(std::max(rest, motion)));
  scene.Process(&pen, 1, buffer.data(), rest);
  synth::ProbeCommand move = pen;
  move.velocity_mps = stroke.speed_mm_s * 1e-3;
  scene.Process(&move, 1, buffer.data(), motion);
  Span span;
  span.sound.resize(static_cast<std::size_t>(motion));
  span.haptic.resize(static_cast<std::size_t>(motion));
  for (int i = 0; i < motion; ++i) {
    span.sound[static_cast<std::size_t>(i)] = buffer[2 * static_cast<std::size_t>(i)];
    span.haptic[static_cast<std::size_t>(i)] = buffer[2 * static_cast<std::size_t>(i) + 1];
  }
  return span;
}

double MeanSquare(const std::vector<float>& x) {
  double sum = 0.0;
  for (const float v : x) sum += static_cast<double>(v) * v;
  return x.empty() ? 0.0 : sum / static_cast<double>(x.size());
}

// Hann-windowed power spectrum (OpenCV's DFT) -> centroid and third-octave band shape.
void Spectrum(const std::vector<float>& x, double fs_hz, StrokeResponse* out) {
  const int n = cv::getOptimalDFTSize(static_cast<int>(x.size()));
  cv::Mat in = cv::Mat::zeros(1, n, CV_64F);
  const auto count = x.size();
  for (std::size_t i = 0; i < count; ++i) {
    const double w = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * (static_cast<double>(i) + 0.5) /
                                          static_cast<double>(count));
    in.at<double>(0, static_cast<int>(i)) = w * x[i];
  }
  cv::Mat spectrum;
  cv::dft(in, spectrum, cv::DFT_COMPLEX_OUTPUT);
  // Band b holds the bins from its lower edge up to the next band's: edges at centre · 2^(-1/6).
  std::array<double, kThirdOctaveBands + 1> edge_hz{};
  for (int b = 0; b <= kThirdOctaveBands; ++b) {
    edge_hz[static_cast<std::size_t>(b)] = BandCentreHz(b) * std::pow(2.0, -1.0 / 6.0);
  }
  std::array<double, kThirdOctaveBands> band{};
  double weighted = 0.0, total = 0.0, in_bands = 0.0;
  const double bin_hz = fs_hz / n;
  std::size_t at = 0;  // the band bin k falls in (bins rise, so it only moves up)
  for (int k = 1; k <= n / 2; ++k) {
    const cv::Vec2d c = spectrum.at<cv::Vec2d>(0, k);
    const double p = c[0] * c[0] + c[1] * c[1];
    const double f = k * bin_hz;
    if (f >= 20.0 && f <= 20000.0) {
      weighted += f * p;
      total += p;
    }
    while (at < band.size() && f >= edge_hz[at + 1]) ++at;
    if (at < band.size() && f >= edge_hz[at]) {
      band[at] += p;
      in_bands += p;
    }
  }
  out->centroid_hz = total > 0.0 ? weighted / total : 0.0;
  for (int b = 0; b < kThirdOctaveBands; ++b) {
    const auto i = static_cast<std::size_t>(b);
    out->band_db[i] = PowerDb(band[i]) - PowerDb(in_bands);
  }
}

}  // namespace

std::vector<ResponseSurface> LoadResponseSurfaces(const std::string& textures_dir) {
  const std::vector<std::string> dirs = MaterialSearchDirs("");
  std::vector<ResponseSurface> out;
  for (const std::string& key : KioskTextureNames()) {
    const std::string path = (std::filesystem::path(textures_dir) / key / "texture.toml").string();
    surface::LoadedTexture loaded = surface::LoadTexture(path);
    ResponseSurface s;
    s.name = loaded.file.name;
    s.field = loaded.field;
    s.material = FindMaterial(loaded.file.material, dirs).params;
    out.push_back(std::move(s));
  }
  // The kiosk's voice path (kiosk_engine.h) on a 2.4 s take at 120 Hz, as the headless visit
  // records it.
  constexpr double kFs = 48000.0;
  const std::vector<float> voice = SynthesiseVoice(kFs, 2.4, 120.0);
  ResponseSurface v;
  v.name = "voice";
  v.field = std::make_shared<const surface::HeightField>(surface::SoundToHeightField(
      std::span<const float>(voice),
      VoiceImageOptions(kFs, KioskConfig{}.record_max_duration_s, voice.size()), kVoiceReliefMm,
      surface::DisplayGeometry{}.pixel_pitch_mm(), std::pmr::get_default_resource()));
  v.material = FindMaterial(kVoiceMaterial, dirs).params;
  out.push_back(std::move(v));
  return out;
}

StrokeResponse MeasureStroke(const ResponseSurface& surface, const HandStroke& stroke, int places,
                             double fs_hz) {
  const double width_mm = surface.field->width() * surface.field->pitch_m() * 1e3;
  const double height_mm = surface.field->height() * surface.field->pitch_m() * 1e3;
  // The relief alone: no friction (nor its noise), no micro-roughness, no crumbling.
  ResponseSurface relief = surface;
  relief.material.friction.enabled = false;
  relief.material.roughness.enabled = false;
  relief.material.crumble.enabled = false;
  StrokeResponse mean;
  mean.sound_db = mean.haptic_db = mean.relief_db = 0.0;
  places = std::max(places, 1);
  for (int p = 0; p < places; ++p) {
    // Places spread over the middle of the surface, directions turning by 70° from one to the
    // next (never along the voice image's rows only, never the same crack twice).
    const double angle = (15.0 + 70.0 * p) * std::numbers::pi / 180.0;
    const double dx = std::cos(angle), dy = std::sin(angle);
    const double cx = width_mm * (0.3 + 0.4 * (p + 0.5) / places);
    const double cy = height_mm * (0.35 + 0.3 * ((p * 7) % places + 0.5) / places);
    const Span span = PlayStroke(surface, stroke, cx - 0.5 * kPathMm * dx, cy - 0.5 * kPathMm * dy,
                                 dx, dy, fs_hz);
    StrokeResponse one;
    Spectrum(span.sound, fs_hz, &one);
    mean.sound_db += PowerDb(MeanSquare(span.sound)) / places;
    mean.haptic_db += PowerDb(MeanSquare(span.haptic)) / places;
    const Span relief_span =
        PlayStroke(relief, stroke, cx - 0.5 * kPathMm * dx, cy - 0.5 * kPathMm * dy, dx, dy, fs_hz);
    mean.relief_db += PowerDb(MeanSquare(relief_span.sound)) / places;
    StrokeResponse relief_one;
    Spectrum(relief_span.sound, fs_hz, &relief_one);
    mean.relief_centroid_hz += relief_one.centroid_hz / places;
    mean.centroid_hz += one.centroid_hz / places;
    mean.flatness += SpectralFlatness(span.sound, fs_hz) / places;
    mean.crest_db += CrestFactorDb(span.sound) / places;
    mean.onsets_per_s += OnsetRatePerS(span.sound, fs_hz) / places;
    for (std::size_t b = 0; b < mean.band_db.size(); ++b)
      mean.band_db[b] += one.band_db[b] / places;
  }
  return mean;
}

double SpectralDistanceDb(const StrokeResponse& a, const StrokeResponse& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.band_db.size(); ++i) sum += std::fabs(a.band_db[i] - b.band_db[i]);
  return sum / static_cast<double>(a.band_db.size());
}

std::vector<ResponseCell> MeasureResponseGrid(const ResponseSurface& surface, int places) {
  std::vector<ResponseCell> grid;
  for (const synth::ProbeStyle style : kResponseStyles) {
    for (const double speed : kResponseSpeedsMmS) {
      for (const double pressure : kResponsePressures) {
        ResponseCell cell;
        cell.stroke = {style, speed, pressure};
        cell.response = MeasureStroke(surface, cell.stroke, places);
        grid.push_back(cell);
      }
    }
  }
  return grid;
}

std::string LevelText(double db) {
  char text[32];
  if (db < kPrintFloorDb) {
    std::snprintf(text, sizeof text, "< %.0f", kPrintFloorDb);
  } else {
    std::snprintf(text, sizeof text, "%.1f", db);
  }
  return text;
}

int ResponseRelationCount() {
  const int styles = static_cast<int>(kResponseStyles.size());
  const int speeds = static_cast<int>(kResponseSpeedsMmS.size());
  const int pressures = static_cast<int>(kResponsePressures.size());
  return styles * pressures * 3 + styles * speeds + speeds * pressures * styles * (styles - 1) / 2;
}

ResponseCheck CheckResponseGrid(const std::string& surface_name,
                                const std::vector<ResponseCell>& grid,
                                const ResponseLimits& limits) {
  const auto at = [&](synth::ProbeStyle style, double speed,
                      double pressure) -> const StrokeResponse* {
    for (const ResponseCell& c : grid) {
      if (c.stroke.style == style && c.stroke.speed_mm_s == speed &&
          c.stroke.pressure == pressure) {
        return &c.response;
      }
    }
    return nullptr;
  };
  const auto name = [](synth::ProbeStyle style) { return synth::ProbeStyleName(style).data(); };
  ResponseCheck check;
  char text[400];
  char key[160];
  const auto fail = [&](const char* relation, const char* style, const char* condition) {
    std::snprintf(key, sizeof key, "%s/%s/%s/%s", surface_name.c_str(), relation, style, condition);
    check.failures.push_back({key, text});
  };
  // How far the relief alone is under the stroke, "more than N" where it is silent.
  const auto Under = [](const StrokeResponse& r) {
    char figure[32];
    if (r.relief_db < kPrintFloorDb) {
      std::snprintf(figure, sizeof figure, "over %.0f", r.sound_db - kPrintFloorDb);
    } else {
      std::snprintf(figure, sizeof figure, "%.0f", r.sound_db - r.relief_db);
    }
    return std::string(figure);
  };
  char condition[32];
  const double slow = kResponseSpeedsMmS.front(), fast = kResponseSpeedsMmS.back();
  const double light = kResponsePressures.front(), firm = kResponsePressures.back();
  for (const synth::ProbeStyle style : kResponseStyles) {
    for (const double pressure : kResponsePressures) {
      const StrokeResponse* a = at(style, slow, pressure);
      const StrokeResponse* b = at(style, fast, pressure);
      if (a == nullptr || b == nullptr) continue;
      if (b->sound_db - a->sound_db < limits.speed_sound_db) {
        std::snprintf(text, sizeof text,
                      "%s, %s, p %.1f: speed %.0f -> %.0f mm/s raises the sound by %.1f dB, "
                      "needs %.1f",
                      surface_name.c_str(), name(style), pressure, slow, fast,
                      b->sound_db - a->sound_db, limits.speed_sound_db);
        std::snprintf(condition, sizeof condition, "p%.1f", pressure);
        fail("speed-sound", name(style), condition);
      }
      if (!(b->centroid_hz >= limits.speed_centroid_ratio * a->centroid_hz)) {
        std::snprintf(text, sizeof text,
                      "%s, %s, p %.1f: speed %.0f -> %.0f mm/s moves the centroid %.0f -> %.0f "
                      "Hz (x%.2f), needs x%.2f (the relief alone: %.0f -> %.0f Hz, x%.2f)",
                      surface_name.c_str(), name(style), pressure, slow, fast, a->centroid_hz,
                      b->centroid_hz, b->centroid_hz / std::max(a->centroid_hz, 1e-9),
                      limits.speed_centroid_ratio, a->relief_centroid_hz, b->relief_centroid_hz,
                      b->relief_centroid_hz / std::max(a->relief_centroid_hz, 1e-9));
        std::snprintf(condition, sizeof condition, "p%.1f", pressure);
        fail("speed-centroid", name(style), condition);
      }
      if (!(b->haptic_db - a->haptic_db > limits.speed_haptic_db)) {
        std::snprintf(text, sizeof text,
                      "%s, %s, p %.1f: speed %.0f -> %.0f mm/s changes the vibration by %.1f dB",
                      surface_name.c_str(), name(style), pressure, slow, fast,
                      b->haptic_db - a->haptic_db);
        std::snprintf(condition, sizeof condition, "p%.1f", pressure);
        fail("speed-haptic", name(style), condition);
      }
    }
    for (const double speed : kResponseSpeedsMmS) {
      const StrokeResponse* a = at(style, speed, light);
      const StrokeResponse* b = at(style, speed, firm);
      if (a == nullptr || b == nullptr) continue;
      const double rise = b->sound_db - a->sound_db;
      if (rise < limits.pressure_sound_db) {
        std::snprintf(condition, sizeof condition, "%.0fmm/s", speed);
        const bool sliding_noise = a->relief_db <= a->sound_db - limits.sliding_noise_margin_db &&
                                   b->relief_db <= b->sound_db - limits.sliding_noise_margin_db &&
                                   rise >= limits.sliding_noise_min_rise_db;
        if (sliding_noise) {
          std::snprintf(text, sizeof text,
                        "%s, %s, %.0f mm/s: pressure %.1f -> %.1f raises the sound by %.1f dB "
                        "(%.1f -> %.1f dB); the relief alone plays %s / %s dB, %s / %s dB "
                        "under the stroke: sliding noise, whose level the load hardly sets",
                        surface_name.c_str(), name(style), speed, light, firm, rise, a->sound_db,
                        b->sound_db, LevelText(a->relief_db).c_str(),
                        LevelText(b->relief_db).c_str(), Under(*a).c_str(), Under(*b).c_str());
          std::snprintf(key, sizeof key, "%s/pressure-sound/%s/%s", surface_name.c_str(),
                        name(style), condition);
          check.exemptions.push_back({key, text});
        } else {
          std::snprintf(text, sizeof text,
                        "%s, %s, %.0f mm/s: pressure %.1f -> %.1f raises the sound by %.1f dB, "
                        "needs %.1f (the relief alone: %s / %s dB)",
                        surface_name.c_str(), name(style), speed, light, firm, rise,
                        limits.pressure_sound_db, LevelText(a->relief_db).c_str(),
                        LevelText(b->relief_db).c_str());
          fail("pressure-sound", name(style), condition);
        }
      }
    }
  }
  for (const double speed : kResponseSpeedsMmS) {
    for (const double pressure : kResponsePressures) {
      for (std::size_t i = 0; i < kResponseStyles.size(); ++i) {
        for (std::size_t j = i + 1; j < kResponseStyles.size(); ++j) {
          const StrokeResponse* a = at(kResponseStyles[i], speed, pressure);
          const StrokeResponse* b = at(kResponseStyles[j], speed, pressure);
          if (a == nullptr || b == nullptr) continue;
          const double d = SpectralDistanceDb(*a, *b);
          if (!(d >= limits.style_distance_db)) {
            std::snprintf(text, sizeof text,
                          "%s, %.0f mm/s, p %.1f: %s and %s spectra differ by %.1f dB, needs %.1f",
                          surface_name.c_str(), speed, pressure, name(kResponseStyles[i]),
                          name(kResponseStyles[j]), d, limits.style_distance_db);
            std::snprintf(condition, sizeof condition, "%.0fmm/s,p%.1f", speed, pressure);
            const std::string pair =
                std::string(name(kResponseStyles[i])) + "-" + name(kResponseStyles[j]);
            fail("style-spectra", pair.c_str(), condition);
          }
        }
      }
    }
  }
  return check;
}

}  // namespace sas::kiosk
