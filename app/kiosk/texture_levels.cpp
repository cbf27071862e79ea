// Stroke levels through the kiosk engine and texture gain calibration (see texture_levels.h).
#include "kiosk/texture_levels.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <stdexcept>

#include "kiosk/kiosk_engine.h"
#include "kiosk/render_command.h"
#include "surface/image_surface.h"
#include "surface/loudness.h"
#include "synth/output_stage.h"

namespace sas::kiosk {
namespace {

constexpr int kMaxCalibrationRenders = 4;
constexpr double kCalibrationToleranceDb = 0.05;
constexpr int kScreenWidthPx = 1920;  // the kiosk's screen (KioskEngineOptions default)
constexpr int kScreenHeightPx = 1080;
// Each stroke is short: a visitor's strokes last longer, but 0.3 s already crosses many ridges at
// these speeds and keeps the regeneration tests quick. Shorter strokes make the slow ones' levels
// noisy (at 0.25 s glass's gains moved by 1.6 dB sound and 3.3 dB vibration). Between strokes the
// pen is up; the ring of one stroke still under the next is part of the (deterministic) sequence.
constexpr double kStrokeS = 0.3;
constexpr double kGapS = 0.15;

double Round2(double db) {
  return std::round(db * 100.0) / 100.0;
}

// A stroke from (x0, y0) (screen fractions) at `angle_deg` (0 = rightwards, positive = down the
// screen) and `speed_mm_s` for kStrokeS, on the kiosk's screen at the display's pixel pitch.
VisitorStroke Make(const char* name, double x0, double y0, double angle_deg, double speed_mm_s,
                   double pressure, double tilt_deg) {
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
  return stroke;
}

}  // namespace

const std::vector<VisitorStroke>& CalibrationStrokes() {
  // Upright pen (tilt < 18°: narrower than the 2 mm rub width) scrapes; tilted 45–55° (4.6–5.5 mm)
  // rubs. Speeds: 40 mm/s (slow, firm), 150 mm/s (medium), 350 mm/s (fast, light).
  static const std::vector<VisitorStroke> strokes = {
      Make("scrape medium", 0.12, 0.30, 10.0, 150.0, 0.5, 0.0),
      Make("scrape slow firm", 0.60, 0.20, 80.0, 40.0, 0.6, 5.0),
      Make("scrape fast light", 0.25, 0.80, -35.0, 350.0, 0.3, 10.0),
      Make("rub medium", 0.15, 0.55, -10.0, 150.0, 0.5, 50.0),
      Make("rub slow firm", 0.35, 0.15, 100.0, 40.0, 0.6, 45.0),
      Make("rub fast light", 0.55, 0.75, -30.0, 350.0, 0.3, 55.0),
  };
  return strokes;
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
  options.screen_width_px = kScreenWidthPx;
  options.screen_height_px = kScreenHeightPx;
  options.virtual_clock = true;
  options.spoken_cues = false;
  options.config.sound_gain_db =
      measurement.global_sound_gain_db + gains.sound_gain_db - file.gains.sound_gain_db;
  options.config.haptic_gain_db =
      measurement.global_haptic_gain_db + gains.haptic_gain_db - file.gains.haptic_gain_db;
  KioskEngine engine(options);
  if (!engine.texture_failures().empty()) throw RenderError(engine.texture_failures().front());
  VirtualVisit visit(engine);

  const double fs = visit.sample_rate_hz();
  // The engine plays a pen event one buffer after it happened (kiosk_engine.h).
  const double delay_s = visit.block_frames() / fs;
  struct Window {
    std::size_t from, to;
  };
  std::vector<Window> windows;
  for (const auto& stroke : measurement.strokes) {
    const double t0 = visit.now_s();
    visit.Advance(stroke.pen.duration_s + kGapS,
                  StraightStroke(stroke.pen, t0, kScreenWidthPx, kScreenHeightPx));
    windows.push_back(
        {static_cast<std::size_t>(std::llround((t0 + delay_s) * fs)),
         static_cast<std::size_t>(std::llround((t0 + stroke.pen.duration_s + delay_s) * fs))});
  }

  const std::span<const float> all(visit.output());
  std::vector<StrokeLevels> result;
  for (const auto& [from, to] : windows) {
    StrokeLevels levels;
    levels.sound_lufs = surface::KWeightedLoudnessDb(all, fs, from, to, 2);
    levels.haptic_rms_db = surface::RmsDb(all.subspan(1), from, to, 2);
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

surface::TextureGains CalibrateTextureGains(const std::string& texture_toml,
                                            double target_sound_lufs, double target_haptic_rms_db,
                                            const LevelMeasurement& measurement) {
  surface::TextureGains gains;
  for (int render = 0; render < kMaxCalibrationRenders; ++render) {
    const auto strokes = MeasureStrokeLevels(texture_toml, gains, measurement);
    const StrokeSetLevels set = Summarise(strokes);
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
    // Below the knee the output stage is linear in the gain: the correction is exact.
    const auto scaled = [](double peak, double db) { return peak * std::pow(10.0, db / 20.0); };
    if (scaled(set.sound_peak, sound_error) < synth::OutputStage::kKnee &&
        scaled(set.haptic_peak, haptic_error) < synth::OutputStage::kKnee) {
      break;
    }
  }
  return {Round2(gains.sound_gain_db), Round2(gains.haptic_gain_db)};
}

}  // namespace sas::kiosk
