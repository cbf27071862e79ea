// One stroke, played as the kiosk plays it and measured (gesture_response.h).
#include "calibration/gesture_response.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <opencv2/core.hpp>
#include <span>
#include <stdexcept>

#include "calibration/character.h"
#include "calibration/felt.h"
#include "calibration/sharpness.h"
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

// A scene for `surface` with the pen resting on it at (x0, y0) mm, held as `stroke` says (a rub
// tilted, scrape and roll upright), facing (dx, dy): it has landed at kLandingMps and settled for
// kRestS. Returns the resting pen's command, for the motion to follow.
synth::ProbeCommand LandPen(synth::Scene& scene, const ResponseSurface& surface,
                            const HandStroke& stroke, double x0_mm, double y0_mm, double dx,
                            double dy, double fs_hz) {
  const GestureMapping mapping;
  scene.Init(fs_hz);
  scene.Prepare(surface.material, synth::OutputParams{}, surface.field->View());
  synth::ProbeCommand pen;
  pen.tip_down = true;
  pen.x_m = x0_mm * 1e-3;
  pen.y_m = y0_mm * 1e-3;
  ApplyPenPressure(stroke.pressure, surface::ReliefM(*surface.field), mapping, pen);
  ApplyPenTilt(stroke.style == synth::ProbeStyle::kRub ? kTiltRubDeg : 0.0, ProbeShape{},
               stroke.style, mapping, pen);
  pen.direction_x = dx;
  pen.direction_y = dy;
  pen.landing_speed_mps = kLandingMps;
  pen.velocity_mps = 0.0;
  const auto rest = static_cast<int>(std::lround(kRestS * fs_hz));
  std::vector<float> buffer(2 * static_cast<std::size_t>(rest));
  scene.Process(&pen, 1, buffer.data(), rest);
  return pen;
}

// Renders one stroke along (x0, y0) + s (dx, dy), s in [0, kPathMm], and returns the motion span.
Span PlayStroke(const ResponseSurface& surface, const HandStroke& stroke, double x0_mm,
                double y0_mm, double dx, double dy, double fs_hz) {
  synth::Scene scene;
  synth::ProbeCommand move = LandPen(scene, surface, stroke, x0_mm, y0_mm, dx, dy, fs_hz);
  const auto motion = static_cast<int>(std::lround(kPathMm / stroke.speed_mm_s * fs_hz));
  std::vector<float> buffer(2 * static_cast<std::size_t>(motion));
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

// Renders one stroke from (x0, y0) along (dx, dy) whose speed rises from stroke.speed_mm_s by
// accel_mm_s2 over kRampS, the pen set at every millisecond on its exact path; returns channel 1
// of the motion.
std::vector<float> PlayRamp(const ResponseSurface& surface, const HandStroke& stroke, double x0_mm,
                            double y0_mm, double dx, double dy, double accel_mm_s2, double fs_hz) {
  synth::Scene scene;
  const synth::ProbeCommand pen = LandPen(scene, surface, stroke, x0_mm, y0_mm, dx, dy, fs_hz);
  const auto motion = static_cast<int>(std::lround(kRampS * fs_hz));
  const int block = static_cast<int>(std::lround(fs_hz / 1000.0));
  std::vector<float> buffer(2 * static_cast<std::size_t>(block));
  std::vector<float> sound;
  sound.reserve(static_cast<std::size_t>(motion));
  for (int at = 0; at < motion; at += block) {
    const int n = std::min(block, motion - at);
    const double t = at / fs_hz;
    const double s_mm = stroke.speed_mm_s * t + 0.5 * accel_mm_s2 * t * t;
    synth::ProbeCommand move = pen;
    move.x_m = (x0_mm + s_mm * dx) * 1e-3;
    move.y_m = (y0_mm + s_mm * dy) * 1e-3;
    // The speed at the block's middle, so the scene's step along the path matches the hand's.
    move.velocity_mps = (stroke.speed_mm_s + accel_mm_s2 * (t + 0.5 * n / fs_hz)) * 1e-3;
    scene.Process(&move, 1, buffer.data(), n);
    for (int i = 0; i < n; ++i) sound.push_back(buffer[2 * static_cast<std::size_t>(i)]);
  }
  return sound;
}

double MeanSquare(std::span<const float> x) {
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

StrokePlace ResponsePlace(int index, double width_mm, double height_mm) {
  // splitmix64 of (seed, index): the same places on every machine and run, independent of the
  // standard library's distributions. The seed is arbitrary; changing it moves every place.
  std::uint64_t z =
      0x5A5C0FFEE2026ULL + 0x9E3779B97F4A7C15ULL * static_cast<std::uint64_t>(index + 1);
  const auto next = [&z] {
    z += 0x9E3779B97F4A7C15ULL;
    std::uint64_t x = z;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    x ^= x >> 31;
    return static_cast<double>(x >> 11) * 0x1.0p-53;  // uniform in [0, 1)
  };
  StrokePlace place;
  // The middle 60 % of the picture, any direction: a 20 mm path stays well inside it.
  place.cx_mm = width_mm * (0.2 + 0.6 * next());
  place.cy_mm = height_mm * (0.2 + 0.6 * next());
  const double angle = std::numbers::pi * next();
  place.dx = std::cos(angle);
  place.dy = std::sin(angle);
  return place;
}

namespace {

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Sharpness heard at kListeningDbSpl (gesture_response.h); 0 for a silent span.
double HeardSharpness(std::span<const float> x, double fs_hz) {
  const double mean_square = MeanSquare(x);
  if (!(mean_square > 1e-24)) return 0.0;
  return Sharpness(x, fs_hz, kListeningDbSpl - PowerDb(mean_square));
}

}  // namespace

StrokeResponse MeasureStroke(const ResponseSurface& surface, const HandStroke& stroke, int places,
                             double fs_hz) {
  const double width_mm = surface.field->width() * surface.field->pitch_m() * 1e3;
  const double height_mm = surface.field->height() * surface.field->pitch_m() * 1e3;
  // The relief alone: no friction (nor its noise), no micro-roughness, no crumbling.
  ResponseSurface relief = surface;
  relief.material.friction.enabled = false;
  relief.material.roughness.enabled = false;
  relief.material.crumble.enabled = false;
  places = std::max(places, 1);
  std::vector<StrokeResponse> each;
  for (int p = 0; p < places; ++p) {
    const StrokePlace at = ResponsePlace(p, width_mm, height_mm);
    const double x0 = at.cx_mm - 0.5 * kPathMm * at.dx, y0 = at.cy_mm - 0.5 * kPathMm * at.dy;
    const Span span = PlayStroke(surface, stroke, x0, y0, at.dx, at.dy, fs_hz);
    StrokeResponse one;
    Spectrum(span.sound, fs_hz, &one);
    one.sound_db = PowerDb(MeanSquare(span.sound));
    const FeltFigures felt = MeasureFelt(span.haptic, fs_hz, 1.0);
    one.haptic_db = felt.skin_db;
    one.haptic_detail_db = felt.features[10];
    one.sharpness_acum = HeardSharpness(span.sound, fs_hz);
    one.flatness = SpectralFlatness(span.sound, fs_hz);
    one.crest_db = CrestFactorDb(span.sound);
    one.onsets_per_s = OnsetRatePerS(span.sound, fs_hz);
    const Span relief_span = PlayStroke(relief, stroke, x0, y0, at.dx, at.dy, fs_hz);
    StrokeResponse relief_one;
    Spectrum(relief_span.sound, fs_hz, &relief_one);
    one.relief_db = PowerDb(MeanSquare(relief_span.sound));
    one.relief_centroid_hz = relief_one.centroid_hz;
    each.push_back(one);
  }
  const auto median = [&](auto field) {
    std::vector<double> v;
    for (const StrokeResponse& r : each) v.push_back(field(r));
    return Median(std::move(v));
  };
  StrokeResponse m;
  m.sound_db = median([](const StrokeResponse& r) { return r.sound_db; });
  m.haptic_db = median([](const StrokeResponse& r) { return r.haptic_db; });
  m.haptic_detail_db = median([](const StrokeResponse& r) { return r.haptic_detail_db; });
  m.centroid_hz = median([](const StrokeResponse& r) { return r.centroid_hz; });
  m.relief_db = median([](const StrokeResponse& r) { return r.relief_db; });
  m.relief_centroid_hz = median([](const StrokeResponse& r) { return r.relief_centroid_hz; });
  m.flatness = median([](const StrokeResponse& r) { return r.flatness; });
  m.crest_db = median([](const StrokeResponse& r) { return r.crest_db; });
  m.onsets_per_s = median([](const StrokeResponse& r) { return r.onsets_per_s; });
  m.sharpness_acum = median([](const StrokeResponse& r) { return r.sharpness_acum; });
  for (std::size_t b = 0; b < m.band_db.size(); ++b) {
    m.band_db[b] = median([b](const StrokeResponse& r) { return r.band_db[b]; });
  }
  return m;
}

double SpearmanRho(std::span<const double> a, std::span<const double> b) {
  const std::size_t n = std::min(a.size(), b.size());
  if (n < 2) return 0.0;
  const auto ranks = [n](std::span<const double> x) {
    std::vector<std::size_t> order(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](std::size_t i, std::size_t j) { return x[i] < x[j]; });
    std::vector<double> r(n);
    for (std::size_t i = 0; i < n;) {
      std::size_t j = i;
      while (j + 1 < n && x[order[j + 1]] == x[order[i]]) ++j;
      const double mean_rank = 0.5 * static_cast<double>(i + j);  // ties share their mean rank
      for (std::size_t k = i; k <= j; ++k) r[order[k]] = mean_rank;
      i = j + 1;
    }
    return r;
  };
  const std::vector<double> ra = ranks(a), rb = ranks(b);
  // Pearson's correlation of the ranks (exact with ties).
  double ma = 0.0, mb = 0.0;
  for (std::size_t i = 0; i < n; ++i) ma += ra[i] / static_cast<double>(n);
  for (std::size_t i = 0; i < n; ++i) mb += rb[i] / static_cast<double>(n);
  double sab = 0.0, saa = 0.0, sbb = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sab += (ra[i] - ma) * (rb[i] - mb);
    saa += (ra[i] - ma) * (ra[i] - ma);
    sbb += (rb[i] - mb) * (rb[i] - mb);
  }
  return saa > 0.0 && sbb > 0.0 ? sab / std::sqrt(saa * sbb) : 0.0;
}

RampResponse MeasureRamp(const ResponseSurface& surface, synth::ProbeStyle style, double pressure,
                         int places, double fs_hz) {
  const double width_mm = surface.field->width() * surface.field->pitch_m() * 1e3;
  const double height_mm = surface.field->height() * surface.field->pitch_m() * 1e3;
  const double accel = (kRampToMmS - kRampFromMmS) / kRampS;  // mm/s²
  const double path_mm = 0.5 * (kRampFromMmS + kRampToMmS) * kRampS;
  const auto motion = static_cast<int>(std::lround(kRampS * fs_hz));
  const int window = motion / kRampWindows;
  RampResponse out;
  out.style = style;
  out.pressure = pressure;
  places = std::max(places, 1);
  std::array<std::vector<double>, kRampWindows> level, sharp;
  for (int p = 0; p < places; ++p) {
    // Across the middle of the picture, at most 20° off the horizontal (the path is 168 mm, the
    // picture 166 mm high), from a seeded place.
    const StrokePlace at = ResponsePlace(1000 + p, width_mm, height_mm);
    const double angle = (at.dy * 2.0 - 1.0) * 20.0 * std::numbers::pi / 180.0;
    const double sign = at.dx >= 0.0 ? 1.0 : -1.0;
    const double dx = sign * std::cos(angle), dy = std::sin(angle);
    const double cx = width_mm * (0.45 + 0.1 * (at.cx_mm / width_mm));
    const double cy = height_mm * (0.4 + 0.2 * (at.cy_mm / height_mm));
    const double x0 = cx - 0.5 * path_mm * dx, y0 = cy - 0.5 * path_mm * dy;
    const HandStroke stroke{style, kRampFromMmS, pressure};
    const std::vector<float> sound = PlayRamp(surface, stroke, x0, y0, dx, dy, accel, fs_hz);
    for (int w = 0; w < kRampWindows; ++w) {
      const std::span<const float> part(sound.data() + static_cast<std::size_t>(w) * window,
                                        static_cast<std::size_t>(window));
      level[static_cast<std::size_t>(w)].push_back(PowerDb(MeanSquare(part)));
      sharp[static_cast<std::size_t>(w)].push_back(HeardSharpness(part, fs_hz));
    }
  }
  for (int w = 0; w < kRampWindows; ++w) {
    const auto i = static_cast<std::size_t>(w);
    const double t_mid = (w + 0.5) * window / fs_hz;
    out.speed_mm_s[i] = kRampFromMmS + accel * t_mid;
    out.sound_db[i] = Median(level[i]);
    out.sharpness_acum[i] = Median(sharp[i]);
  }
  out.sound_rho = SpearmanRho(out.speed_mm_s, out.sound_db);
  out.sharpness_rho = SpearmanRho(out.speed_mm_s, out.sharpness_acum);
  return out;
}

std::vector<RampResponse> MeasureRamps(const ResponseSurface& surface, int places) {
  std::vector<RampResponse> out;
  for (const synth::ProbeStyle style : kResponseStyles) {
    for (const double pressure : kResponsePressures) {
      out.push_back(MeasureRamp(surface, style, pressure, places));
    }
  }
  return out;
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

int RampRelationCount() {
  return 2 * static_cast<int>(kResponseStyles.size() * kResponsePressures.size());
}

std::vector<ResponseFailure> CheckRamps(const std::string& surface_name,
                                        const std::vector<RampResponse>& ramps,
                                        const ResponseLimits& limits) {
  std::vector<ResponseFailure> out;
  char text[400];
  char key[160];
  for (const RampResponse& r : ramps) {
    const char* style = synth::ProbeStyleName(r.style).data();
    const auto check = [&](const char* what, const char* relation, double rho,
                           const std::array<double, kRampWindows>& series, const char* format) {
      if (rho >= limits.ramp_rho) return;
      std::string figures;
      for (const double v : series) {
        char one[24];
        std::snprintf(one, sizeof one, format, v);
        figures += (figures.empty() ? "" : " ") + std::string(one);
      }
      std::snprintf(text, sizeof text,
                    "%s, %s, p %.1f: speeding up %.0f -> %.0f mm/s, the %s follows the speed "
                    "with rho %.2f, needs %.2f (%s)",
                    surface_name.c_str(), style, r.pressure, kRampFromMmS, kRampToMmS, what, rho,
                    limits.ramp_rho, figures.c_str());
      std::snprintf(key, sizeof key, "%s/%s/%s/p%.1f", surface_name.c_str(), relation, style,
                    r.pressure);
      out.push_back({key, text});
    };
    check("level", "ramp-sound", r.sound_rho, r.sound_db, "%.1f");
    check("sharpness", "ramp-sharpness", r.sharpness_rho, r.sharpness_acum, "%.2f");
  }
  return out;
}

double SharpnessAtSpeed(const std::vector<ResponseCell>& grid, double speed_mm_s) {
  std::vector<double> v;
  for (const ResponseCell& c : grid) {
    if (c.stroke.speed_mm_s == speed_mm_s) v.push_back(c.response.sharpness_acum);
  }
  return Median(std::move(v));
}

std::vector<ResponseFailure> CheckSharpestTexture(
    const std::vector<std::string>& names, const std::vector<std::vector<ResponseCell>>& grids) {
  constexpr const char* kGlass = "broken glass";
  std::vector<ResponseFailure> out;
  const auto glass = std::find(names.begin(), names.end(), kGlass);
  for (const double speed : kResponseSpeedsMmS) {
    char key[96];
    std::snprintf(key, sizeof key, "character/glass-sharpest/%.0fmm/s", speed);
    if (glass == names.end()) {
      out.push_back({key, "no broken glass among the surfaces"});
      continue;
    }
    const double glass_acum =
        SharpnessAtSpeed(grids[static_cast<std::size_t>(glass - names.begin())], speed);
    std::string sharper;
    for (std::size_t i = 0; i < names.size() && i < grids.size(); ++i) {
      if (names[i] == kGlass || names[i] == "voice") continue;
      const double acum = SharpnessAtSpeed(grids[i], speed);
      if (!(glass_acum > acum)) {
        char one[96];
        std::snprintf(one, sizeof one, "%s%s %.2f", sharper.empty() ? "" : ", ", names[i].c_str(),
                      acum);
        sharper += one;
      }
    }
    if (!sharper.empty()) {
      char text[400];
      std::snprintf(text, sizeof text,
                    "at %.0f mm/s broken glass (%.2f acum, the median of its styles and pressures) "
                    "is not the sharpest texture: %s",
                    speed, glass_acum, sharper.c_str());
      out.push_back({key, text});
    }
  }
  return out;
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
      if (!(b->sharpness_acum >= limits.speed_sharpness_ratio * a->sharpness_acum)) {
        std::snprintf(text, sizeof text,
                      "%s, %s, p %.1f: speed %.0f -> %.0f mm/s moves the sharpness %.2f -> %.2f "
                      "acum (x%.2f), needs x%.2f (centroid %.0f -> %.0f Hz; the relief alone's "
                      "%.0f -> %.0f Hz)",
                      surface_name.c_str(), name(style), pressure, slow, fast, a->sharpness_acum,
                      b->sharpness_acum, b->sharpness_acum / std::max(a->sharpness_acum, 1e-9),
                      limits.speed_sharpness_ratio, a->centroid_hz, b->centroid_hz,
                      a->relief_centroid_hz, b->relief_centroid_hz);
        std::snprintf(condition, sizeof condition, "p%.1f", pressure);
        fail("speed-sharpness", name(style), condition);
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
