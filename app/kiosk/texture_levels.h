#pragma once
// Loudness and vibration-strength matching of the kiosk textures (issue 7, "noisy room"): the
// same stroke on any of the four textures must sound equally loud and vibrate equally strongly
// (within 1 dB), so that switching tokens never jumps in level. A texture's [gains] in its
// texture.toml are the correction; this file measures them and computes them.
//
// Measurement: the offline render path (render_command.h: the texture's material and true height
// map, the built-in gesture mapped as the renderer maps it, the same synth::Scene the kiosk plays)
// renders the stroke with the texture's gains plus `global` gains (the kiosk configuration's
// gains.sound_gain_db / haptic_gain_db, default 0); then, over the part of the gesture where the
// pen is down (first to last row with pressure > 0):
//   sound   channel 1, BS.1770 K-weighted loudness (LUFS, ungated) — surface/loudness.h says why
//   haptic  channel 2, RMS in dBFS — the output stage has already band-limited it to 40–800 Hz
//
// Calibration: gains = target − measured. The output stage applies the gain to the pickup signal
// before its soft limiter, so the level is exactly linear in the gain while the stroke's peaks stay
// below the limiter's knee: then one render at 0 dB gives the answer. When a peak would reach the
// knee, the calibration renders again at the new gains until it converges (within 0.05 dB).
// Offline only.

#include <string>

#include "surface/texture_file.h"

namespace sas::kiosk {

struct StrokeLevels {
  double sound_lufs = 0.0;
  double haptic_rms_db = 0.0;
  double sound_peak = 0.0;  // largest |sample| over the stroke (linear, full scale = 1)
  double haptic_peak = 0.0;
};

struct LevelMeasurement {
  std::string gesture = "slow stroke";  // a built-in gesture (gesture.h)
  double global_sound_gain_db = 0.0;    // on top of the texture's gains
  double global_haptic_gain_db = 0.0;
  int sample_rate_hz = 48000;
};

// The calibration targets for a stroke at the texture gains only (global gains 0 dB). The strokes'
// peaks lie up to ~24 dB above their loudness (wood's clicks on the grain) and ~26 dB above their
// RMS on the transducer (glass), so with the kiosk's default +12 dB / +6 dB only the sharpest
// clicks reach the soft limiters' knee (-6 dBFS) while the average level is room-filling.
inline constexpr double kTargetSoundLufs = -36.0;
inline constexpr double kTargetHapticRmsDb = -36.0;

// Renders `measurement.gesture` on the texture file `texture_toml` with texture gains `gains`
// (not the ones in the file: the caller chooses) and returns the levels. Throws on any problem.
StrokeLevels MeasureStrokeLevels(const std::string& texture_toml,
                                 const surface::TextureGains& gains,
                                 const LevelMeasurement& measurement = {});

// The texture gains that bring the stroke to the targets (within 0.05 dB), rounded to 0.01 dB.
surface::TextureGains CalibrateTextureGains(const std::string& texture_toml,
                                            double target_sound_lufs = kTargetSoundLufs,
                                            double target_haptic_rms_db = kTargetHapticRmsDb,
                                            const LevelMeasurement& measurement = {});

}  // namespace sas::kiosk
