// Stroke levels through the kiosk engine and texture gain calibration (see texture_levels.h).
#include "calibration/texture_levels.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <numbers>
#include <random>
#include <span>
#include <stdexcept>

#include "kiosk/kiosk_engine.h"
#include "surface/image_surface.h"
#include "surface/loudness.h"
#include "synth/output_stage.h"
#include "tools/render_command.h"

namespace sas::kiosk {
namespace {

constexpr int kMaxCalibrationRenders = 4;
constexpr double kCalibrationToleranceDb = 0.05;
// Each stroke is short (kStrokeS, 0.4 s) and measured from kSettleS after touch-down: a
// visitor's strokes last longer (the headless visit's 1.2 s), and over the whole of a short stroke
// the landing click outweighs the sliding (wood: over 0.3 s strokes its level hardly grew with
// speed, over 1.2 s it was 10 dB below the others), so the sustained sound is what is matched. The
// landing gets the stroke's correction too (stroke_gain.h). Between strokes the pen is up; the
// ring of one stroke still under the next is part of the (deterministic) sequence.
constexpr double kGapS = kGapAfterLiftS;
// After the idle reset between visits: its switch to the default texture and the fade (well within
// this) settle before the next visitor's stroke.
constexpr double kVisitResetS = 0.5;

double Round2(double db) {
  return std::round(db * 100.0) / 100.0;
}

bool OnScreen(const VisitorStroke& stroke) {
  const double back = stroke.pen.hover_s / stroke.pen.duration_s;  // where the hover starts
  const double hx = stroke.pen.x0 - (stroke.pen.x1 - stroke.pen.x0) * back;
  const double hy = stroke.pen.y0 - (stroke.pen.y1 - stroke.pen.y0) * back;
  for (const double f : {hx, hy, stroke.pen.x0, stroke.pen.x1, stroke.pen.y0, stroke.pen.y1}) {
    if (!(f > 0.0 && f < 1.0)) return false;
  }
  return true;
}

}  // namespace

VisitorStroke MakeStroke(const char* name, double x0, double y0, double angle_deg,
                         double speed_mm_s, double pressure, double tilt_deg) {
  const double pitch_mm = surface::DisplayGeometry{}.pixel_pitch_mm();
  const double length_mm = speed_mm_s * kStrokeS;
  const double angle = angle_deg * std::numbers::pi / 180.0;
  VisitorStroke stroke;
  stroke.name = name;
  stroke.pen.x0 = x0;
  stroke.pen.y0 = y0;
  stroke.pen.x1 = x0 + length_mm * std::cos(angle) / (pitch_mm * kScreenWidthPx);
  stroke.pen.y1 = y0 + length_mm * std::sin(angle) / (pitch_mm * kScreenHeightPx);
  stroke.pen.duration_s = kStrokeS;
  stroke.pen.pressure = pressure;
  stroke.pen.tilt_deg = tilt_deg;
  stroke.pen.hover_s = kHoverS;
  return stroke;
}

std::vector<VisitorStroke> VisitorPopulation(int count, std::uint32_t seed, double duration_scale) {
  // Our own draws from std::mt19937 (its sequence is fixed by the standard; the standard
  // distributions are not, so they are not used).
  std::mt19937 rng(seed);
  const auto uniform = [&](double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(rng()) / 4294967296.0);
  };
  const GestureMapping mapping;
  const double rub_tilt = TiltFromWidthDeg(mapping.rub_width_mm, mapping);
  const double pitch_mm = surface::DisplayGeometry{}.pixel_pitch_mm();
  const double width_mm = pitch_mm * kScreenWidthPx, height_mm = pitch_mm * kScreenHeightPx;
  std::vector<VisitorStroke> strokes;
  for (int i = 0; i < count; ++i) {
    VisitorStroke stroke;
    const int style = static_cast<int>(rng() % 3);
    const double speed = std::exp(uniform(std::log(20.0), std::log(400.0)));
    const double pressure = uniform(0.1, 0.9);
    double duration = uniform(0.3, 1.5) * duration_scale;
    double tilt = 0.0;
    if (style == 0) {
      stroke.name = "scrape";
      tilt = uniform(0.0, rub_tilt * 0.999);
    } else if (style == 1) {
      stroke.name = "rub";
      tilt = uniform(rub_tilt, 60.0);
    } else {
      stroke.name = "roll";
      tilt = uniform(0.0, 60.0);
      stroke.pen.style = synth::ProbeStyle::kRoll;
    }
    // Direction and start: the stroke must stay on the screen's middle 90 %; too long, it is
    // shortened (a visitor's hand reaches the edge and lifts).
    const double angle = uniform(0.0, 2.0 * std::numbers::pi);
    const double dx = std::cos(angle), dy = std::sin(angle);
    const double room_x = 0.9 * width_mm, room_y = 0.9 * height_mm;
    double length = speed * duration;
    const double fit = std::min(std::fabs(dx) > 1e-9 ? room_x / std::fabs(dx) : 1e300,
                                std::fabs(dy) > 1e-9 ? room_y / std::fabs(dy) : 1e300);
    if (length > fit) {
      length = fit;
      duration = length / speed;
    }
    const double span_x = room_x - length * std::fabs(dx), span_y = room_y - length * std::fabs(dy);
    const double x0_mm = 0.05 * width_mm + uniform(0.0, span_x) + (dx < 0 ? length * -dx : 0.0);
    const double y0_mm = 0.05 * height_mm + uniform(0.0, span_y) + (dy < 0 ? length * -dy : 0.0);
    stroke.pen.x0 = x0_mm / width_mm;
    stroke.pen.y0 = y0_mm / height_mm;
    stroke.pen.x1 = (x0_mm + length * dx) / width_mm;
    stroke.pen.y1 = (y0_mm + length * dy) / height_mm;
    stroke.pen.duration_s = duration;
    stroke.pen.pressure = pressure;
    stroke.pen.tilt_deg = tilt;
    stroke.pen.hover_s = kHoverS;
    strokes.push_back(stroke);
  }
  return strokes;
}

VisitorStroke PlacedStroke(const char* name, int place, double speed_mm_s, double pressure,
                           double tilt_deg) {
  // Place k: start on a low-discrepancy sequence over the middle 70 % of the screen (the R2
  // sequence's two irrationals), direction turned by the golden angle each place; a stroke that
  // would leave the screen turns by 30° steps until it fits, and starts from the centre, then from
  // the left or right edge, if none does (a long fast stroke only fits across the screen).
  const double k = place;
  const auto frac = [](double v) { return v - std::floor(v); };
  const double x0 = 0.15 + 0.7 * frac(0.5 + k * 0.7548776662466927);
  const double y0 = 0.15 + 0.7 * frac(0.5 + k * 0.5698402909980532);
  const double angle = std::fmod(k * 137.50776405003785, 360.0);
  for (const auto& [x, y] :
       {std::pair{x0, y0}, std::pair{0.5, 0.5}, std::pair{0.08, y0}, std::pair{0.92, y0}}) {
    for (int turn = 0; turn < 12; ++turn) {
      VisitorStroke stroke =
          MakeStroke(name, x, y, angle + 30.0 * turn, speed_mm_s, pressure, tilt_deg);
      if (OnScreen(stroke)) return stroke;
    }
  }
  throw RenderError(std::string(name) + ": no place on the screen for this stroke");
}

std::vector<VisitorStroke> CalibrationStrokes(const CalibrationGrid& grid) {
  const GestureMapping mapping;  // the kiosk engine's
  std::vector<VisitorStroke> strokes;
  int place = 0;
  const char* names[] = {"scrape", "rub", "roll"};
  for (int style = 0; style < 3; ++style) {
    const std::vector<double>& widths = style == 0   ? grid.scrape_widths_mm
                                        : style == 1 ? grid.rub_widths_mm
                                                     : grid.roll_widths_mm;
    for (const double width : widths) {
      for (const double speed : grid.speeds_mm_s) {
        for (const double pressure : grid.pressures) {
          char name[64];
          std::snprintf(name, sizeof name, "%s %.1f mm %.0f mm/s p%.2f", names[style], width, speed,
                        pressure);
          for (int i = 0; i < grid.places; ++i) {
            VisitorStroke stroke =
                PlacedStroke(name, place++, speed, pressure, TiltFromWidthDeg(width, mapping));
            if (style == 2) stroke.pen.style = synth::ProbeStyle::kRoll;
            strokes.push_back(std::move(stroke));
          }
        }
      }
    }
  }
  return strokes;
}

const std::vector<VisitorStroke>& CalibrationStrokes() {
  static const std::vector<VisitorStroke> strokes = CalibrationStrokes(CalibrationGrid{});
  return strokes;
}

std::vector<StrokeLevels> MeanOverPlaces(const std::vector<StrokeLevels>& levels, int places) {
  std::vector<StrokeLevels> means;
  const auto n = static_cast<std::size_t>(std::max(places, 1));
  for (std::size_t i = 0; i + n <= levels.size(); i += n) {
    StrokeLevels mean;
    for (std::size_t j = i; j < i + n; ++j) {
      mean.sound_lufs += levels[j].sound_lufs / static_cast<double>(n);
      mean.haptic_rms_db += levels[j].haptic_rms_db / static_cast<double>(n);
      mean.sound_peak = std::max(mean.sound_peak, levels[j].sound_peak);
      mean.haptic_peak = std::max(mean.haptic_peak, levels[j].haptic_peak);
    }
    means.push_back(mean);
  }
  return means;
}

std::vector<StrokeLevels> MeasureStrokeLevels(const std::string& texture_toml,
                                              const surface::TextureGains& gains,
                                              const LevelMeasurement& measurement) {
  if (measurement.strokes.empty()) throw RenderError("no strokes to measure");
  // The engine adds the configuration's gains to the file's: asking for `gains` instead of the
  // file's is a configuration gain of the difference.
  const surface::TextureFile file = surface::LoadTextureFile(texture_toml);
  KioskEngineOptions options;
  options.texture_paths = {texture_toml};
  options.texture_paths.insert(options.texture_paths.end(), measurement.other_textures.begin(),
                               measurement.other_textures.end());
  options.config.default_texture =
      std::filesystem::path(texture_toml).parent_path().filename().string();
  options.screen_width_px = kScreenWidthPx;
  options.screen_height_px = kScreenHeightPx;
  options.virtual_clock = true;
  options.spoken_cues = false;
  options.config.sound_gain_db = measurement.global_sound_gain_db + gains.sound_gain_db +
                                 gains.sound_trim_db - file.gains.sound_gain_db -
                                 file.gains.sound_trim_db;
  options.config.haptic_gain_db = measurement.global_haptic_gain_db + gains.haptic_gain_db +
                                  gains.haptic_trim_db - file.gains.haptic_gain_db -
                                  file.gains.haptic_trim_db;
  options.config.stroke_cap_lu = measurement.stroke_cap_lu;
  if (measurement.strokes_per_visit > 0) options.config.idle_timeout_s = kVisitIdleTimeoutS;
  KioskEngine engine(options);
  if (!engine.texture_failures().empty()) throw RenderError(engine.texture_failures().front());
  VirtualVisit visit(engine);

  const double fs = visit.sample_rate_hz();
  // The engine plays a pen event one buffer after it happened (player/player.h).
  const double delay_s = visit.block_frames() / fs;
  std::vector<surface::FrameWindow> windows;
  for (const auto& stroke : measurement.strokes) {
    const auto played = static_cast<int>(windows.size());
    if (measurement.strokes_per_visit > 0 && played > 0 &&
        played % measurement.strokes_per_visit == 0) {
      // The visitor leaves: the idle reset, then its fade to the default texture.
      visit.Advance(kVisitIdleTimeoutS + kVisitResetS);
    }
    const double t_hover = visit.now_s();
    visit.Advance(stroke.pen.hover_s + stroke.pen.duration_s + kGapS,
                  StraightStroke(stroke.pen, t_hover, kScreenWidthPx, kScreenHeightPx));
    const double t0 = t_hover + stroke.pen.hover_s;  // tip down
    const double begin = measurement.whole_strokes ? t0 : t0 + kSettleS;
    const double end = t0 + stroke.pen.duration_s + (measurement.whole_strokes ? kGapS : 0.0);
    windows.push_back({static_cast<std::size_t>(std::llround((begin + delay_s) * fs)),
                       static_cast<std::size_t>(std::llround((end + delay_s) * fs))});
  }
  // Every stroke's 400 ms windows, 100 ms apart, measured in one pass with the strokes' own.
  const auto window = static_cast<std::size_t>(std::llround(kMomentaryWindowS * fs));
  const auto hop = static_cast<std::size_t>(std::llround(kMomentaryHopS * fs));
  std::vector<surface::FrameWindow> all_windows = windows;
  std::vector<std::pair<std::size_t, std::size_t>> momentary_range;  // per stroke: [first, last)
  for (const auto& w : windows) {
    const std::size_t first = all_windows.size();
    for (std::size_t start = w.from; start == w.from || start + window <= w.to; start += hop) {
      all_windows.push_back({start, start + window});
    }
    momentary_range.emplace_back(first, all_windows.size());
  }

  const std::span<const float> all(visit.output());
  const std::vector<double> loudness = surface::KWeightedLoudnessDb(all, fs, all_windows, 2);
  // Channel 2 skin-weighted once, from the visit's start (no filter start-up inside a stroke).
  const std::vector<float> skin = SkinWeighted(all.subspan(1), fs, 2);
  const double ceiling = std::pow(10.0, options.config.haptic_ceiling_db / 20.0);
  std::vector<StrokeLevels> result;
  for (std::size_t w = 0; w < windows.size(); ++w) {
    const auto [from, to] = windows[w];
    StrokeLevels levels;
    levels.sound_lufs = loudness[w];
    levels.sound_momentary_max_lufs = surface::kSilenceDb;
    for (std::size_t m = momentary_range[w].first; m < momentary_range[w].second; ++m) {
      levels.sound_momentary_max_lufs = std::max(levels.sound_momentary_max_lufs, loudness[m]);
    }
    levels.haptic_rms_db = surface::RmsDb(skin, from, to, 1);
    if (measurement.felt_figures) {
      std::vector<float> ch2;
      for (std::size_t i = from; i < to && 2 * i + 1 < all.size(); ++i) ch2.push_back(all[2 * i + 1]);
      levels.felt = MeasureFelt(ch2, fs, ceiling);
    }
    for (std::size_t i = from; i < to && 2 * i + 1 < all.size(); ++i) {
      levels.sound_peak = std::max(levels.sound_peak, static_cast<double>(std::fabs(all[2 * i])));
      levels.haptic_peak =
          std::max(levels.haptic_peak, static_cast<double>(std::fabs(all[2 * i + 1])));
    }
    result.push_back(levels);
  }
  return result;
}

StrokeSetLevels Summarise(const std::vector<StrokeLevels>& strokes) {
  StrokeSetLevels set;
  for (const auto& levels : strokes) {
    set.silent = set.silent || levels.sound_lufs <= surface::kSilenceDb ||
                 levels.haptic_rms_db <= surface::kSilenceDb;
    set.sound_mean_lufs += levels.sound_lufs / static_cast<double>(strokes.size());
    set.haptic_mean_rms_db += levels.haptic_rms_db / static_cast<double>(strokes.size());
    set.sound_peak = std::max(set.sound_peak, levels.sound_peak);
    set.haptic_peak = std::max(set.haptic_peak, levels.haptic_peak);
  }
  return set;
}

TextureCalibration CalibrateTexture(const std::string& texture_toml, double target_sound_lufs,
                                    double target_haptic_rms_db, const CalibrationGrid& grid) {
  if (surface::LoadTextureFile(texture_toml).levels) {
    throw RenderError(texture_toml + ": calibrate a texture file without its [levels] table");
  }
  LevelMeasurement measurement;
  measurement.strokes = CalibrationStrokes(grid);
  surface::TextureGains gains;
  std::vector<StrokeLevels> strokes;
  double sound_applied = 0.0, haptic_applied = 0.0;  // gain change since the strokes were played
  for (int render = 0; render < kMaxCalibrationRenders; ++render) {
    strokes = MeasureStrokeLevels(texture_toml, gains, measurement);
    sound_applied = haptic_applied = 0.0;
    // The gains from the sliding strokes only (scrape and rub come first; see CalibrationGrid).
    const std::size_t sliding = static_cast<std::size_t>(grid.places) * grid.speeds_mm_s.size() *
                                grid.pressures.size() *
                                (grid.scrape_widths_mm.size() + grid.rub_widths_mm.size());
    const StrokeSetLevels set = Summarise(std::vector<StrokeLevels>(
        strokes.begin(), strokes.begin() + static_cast<std::ptrdiff_t>(sliding)));
    if (set.silent) throw RenderError(texture_toml + ": a calibration stroke is silent");
    const double sound_error = target_sound_lufs - set.sound_mean_lufs;
    const double haptic_error = std::min(target_haptic_rms_db - set.haptic_mean_rms_db,
                                         kMaxHapticGainDb - gains.haptic_gain_db);
    if (std::fabs(sound_error) < kCalibrationToleranceDb &&
        std::fabs(haptic_error) < kCalibrationToleranceDb) {
      break;
    }
    gains.sound_gain_db += sound_error;
    gains.haptic_gain_db += haptic_error;
    sound_applied = sound_error;
    haptic_applied = haptic_error;
    // Below the knee the output stage is linear in the gain: the correction is exact.
    const auto scaled = [](double peak, double db) { return peak * std::pow(10.0, db / 20.0); };
    if (scaled(set.sound_peak, sound_error) < synth::OutputStage::kKnee &&
        scaled(set.haptic_peak, haptic_error) < synth::OutputStage::kKnee) {
      break;
    }
  }
  TextureCalibration result;
  result.gains = {Round2(gains.sound_gain_db), Round2(gains.haptic_gain_db)};
  // The levels at the written (rounded) gains: the last pass's plus what changed since (linear:
  // below the knee, or within the 0.05 dB the loop converged to).
  sound_applied += result.gains.sound_gain_db - gains.sound_gain_db;
  haptic_applied += result.gains.haptic_gain_db - gains.haptic_gain_db;
  result.levels.scrape_widths_mm = grid.scrape_widths_mm;
  result.levels.rub_widths_mm = grid.rub_widths_mm;
  result.levels.roll_widths_mm = grid.roll_widths_mm;
  result.levels.speeds_mm_s = grid.speeds_mm_s;
  result.levels.pressures = grid.pressures;
  for (const auto& levels : MeanOverPlaces(strokes, grid.places)) {
    result.levels.sound_lufs.push_back(Round2(levels.sound_lufs + sound_applied));
    result.levels.haptic_rms_db.push_back(Round2(levels.haptic_rms_db + haptic_applied));
  }
  return result;
}

double Percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double pos = p * static_cast<double>(v.size() - 1);
  const auto i = static_cast<std::size_t>(pos);
  const double f = pos - static_cast<double>(i);
  return i + 1 < v.size() ? v[i] * (1.0 - f) + v[i + 1] * f : v[i];
}

std::string LevelTableToml(const surface::StrokeLevelTable& levels) {
  const auto list = [](const std::vector<double>& values, std::size_t from, std::size_t count,
                       std::size_t per_row) {
    std::string out = "[";
    char number[32];
    for (std::size_t i = 0; i < count; ++i) {
      if (i > 0) out += i % per_row == 0 ? ",\n  " : ", ";
      std::snprintf(number, sizeof number, "%.2f", values[from + i] + 0.0);
      out += number;
    }
    return out + "]\n";
  };
  const std::size_t widths = levels.scrape_widths_mm.size();
  const std::size_t speeds = levels.speeds_mm_s.size(), pressures = levels.pressures.size();
  std::string out =
      "\n[levels]\n# This texture's stroke levels at the gains above, measured on the grid below "
      "(levels/stroke_gain.h):\n# per style, per probe width one block of rows, one row per speed, "
      "one value per pressure.\n# The kiosk corrects each stroke towards the median of the loaded "
      "textures' levels for it.\n";
  out += "scrape_widths_mm = " + list(levels.scrape_widths_mm, 0, widths, widths);
  out += "rub_widths_mm = " + list(levels.rub_widths_mm, 0, widths, widths);
  const std::size_t rolls = levels.roll_widths_mm.size();
  if (levels.styles() > 2)
    out += "roll_widths_mm = " + list(levels.roll_widths_mm, 0, rolls, rolls);
  out += "speeds_mm_s = " + list(levels.speeds_mm_s, 0, speeds, speeds);
  out += "pressures = " + list(levels.pressures, 0, pressures, pressures);
  const char* names[] = {"scrape", "rub", "roll"};
  for (int style = 0; style < levels.styles(); ++style) {
    const std::size_t from = levels.Index(style, 0, 0, 0);
    const std::size_t per_style = levels.widths_mm(style).size() * speeds * pressures;
    out += std::string(names[style]) +
           "_sound_lufs = " + list(levels.sound_lufs, from, per_style, pressures);
    out += std::string(names[style]) +
           "_haptic_rms_db = " + list(levels.haptic_rms_db, from, per_style, pressures);
  }
  return out;
}

}  // namespace sas::kiosk
