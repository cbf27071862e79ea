#pragma once
// The synth's output settings for the texture under the pen (for a noisy room): the kiosk
// configuration's gains (deliberately high for a loud room), plus the texture's calibrated
// loudness-matching gains (texture.toml [gains], calibration/texture_levels.h), plus the
// ambient-adaptive sound gain (ambient_gain.h; 0 dB when off), all in dB; the transducer's peak
// ceiling and the low-vibration attenuation from the configuration. The soft limiters of
// synth/output_stage.h keep whatever comes out within full scale (sound) and the ceiling
// (transducer). Control side only (Prepare-time); switching low-vibration mode while playing is
// synth::Scene::SetLowVibration().

#include "files/kiosk_config.h"
#include "surface/texture_file.h"
#include "synth/material_params.h"

namespace sas::kiosk {

// The level the textures are calibrated to at their own [gains] (calibration/texture_levels.h): the
// mean loudness of the calibration strokes, LUFS. The stroke leveller's cap sits
// KioskConfig::stroke_cap_lu above it plus the configured and ambient gains (the leveller
// K-weights the sound as the loudness measure does).
inline constexpr double kCalibratedSoundLufs = -36.0;

synth::OutputParams KioskOutputParams(const KioskConfig& config,
                                      const surface::TextureGains& texture,
                                      double ambient_gain_db = 0.0, bool low_vibration = false);

}  // namespace sas::kiosk
