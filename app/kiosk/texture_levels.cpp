// Stroke levels and texture gain calibration (see texture_levels.h).
#include "kiosk/texture_levels.h"

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>
#include <vector>

#include "kiosk/gesture.h"
#include "kiosk/render_command.h"
#include "surface/loudness.h"
#include "synth/output_stage.h"

namespace sas::kiosk {
namespace {

constexpr int kMaxCalibrationRenders = 6;
constexpr double kCalibrationToleranceDb = 0.05;

double Round2(double db) {
  return std::round(db * 100.0) / 100.0;
}

}  // namespace

StrokeLevels MeasureStrokeLevels(const std::string& texture_toml,
                                 const surface::TextureGains& gains,
                                 const LevelMeasurement& measurement) {
  const auto gesture = FindBuiltinGesture(measurement.gesture);
  if (!gesture) throw RenderError("no built-in gesture \"" + measurement.gesture + "\"");
  double down_s = -1.0;
  double up_s = -1.0;
  for (const auto& row : gesture->samples) {
    if (row.pressure <= 0.0) continue;
    if (down_s < 0.0) down_s = row.t_s;
    up_s = row.t_s;
  }
  if (!(up_s > down_s)) throw RenderError("gesture \"" + measurement.gesture + "\" never strokes");

  RenderOptions options;
  options.profile = texture_toml;
  options.gesture = measurement.gesture;
  options.sample_rate_hz = measurement.sample_rate_hz;
  options.tail_s = 0.0;
  options.sound_gain_db = gains.sound_gain_db + measurement.global_sound_gain_db;
  options.haptic_gain_db = gains.haptic_gain_db + measurement.global_haptic_gain_db;
  std::vector<float> audio;
  RenderToMemory(options, audio);

  const double fs = measurement.sample_rate_hz;
  const auto from = static_cast<std::size_t>(std::llround(down_s * fs));
  const auto to = static_cast<std::size_t>(std::llround(up_s * fs));
  const std::span<const float> all(audio);
  StrokeLevels levels;
  levels.sound_lufs = surface::KWeightedLoudnessDb(all, fs, from, to, 2);
  levels.haptic_rms_db = surface::RmsDb(all.subspan(1), from, to, 2);
  for (std::size_t i = from; i < to && 2 * i + 1 < audio.size(); ++i) {
    levels.sound_peak = std::max(levels.sound_peak, static_cast<double>(std::fabs(audio[2 * i])));
    levels.haptic_peak =
        std::max(levels.haptic_peak, static_cast<double>(std::fabs(audio[2 * i + 1])));
  }
  return levels;
}

surface::TextureGains CalibrateTextureGains(const std::string& texture_toml,
                                            double target_sound_lufs, double target_haptic_rms_db,
                                            const LevelMeasurement& measurement) {
  surface::TextureGains gains;
  for (int render = 0; render < kMaxCalibrationRenders; ++render) {
    const StrokeLevels levels = MeasureStrokeLevels(texture_toml, gains, measurement);
    if (levels.sound_lufs <= surface::kSilenceDb || levels.haptic_rms_db <= surface::kSilenceDb) {
      throw RenderError(texture_toml + ": the calibration stroke is silent");
    }
    const double sound_error = target_sound_lufs - levels.sound_lufs;
    const double haptic_error = target_haptic_rms_db - levels.haptic_rms_db;
    if (std::fabs(sound_error) < kCalibrationToleranceDb &&
        std::fabs(haptic_error) < kCalibrationToleranceDb) {
      break;
    }
    gains.sound_gain_db += sound_error;
    gains.haptic_gain_db += haptic_error;
    // Below the knee the output stage is linear in the gain: the correction is exact.
    const auto scaled = [](double peak, double db) { return peak * std::pow(10.0, db / 20.0); };
    if (scaled(levels.sound_peak, sound_error) < synth::OutputStage::kKnee &&
        scaled(levels.haptic_peak, haptic_error) < synth::OutputStage::kKnee) {
      break;
    }
  }
  return {Round2(gains.sound_gain_db), Round2(gains.haptic_gain_db)};
}

}  // namespace sas::kiosk
