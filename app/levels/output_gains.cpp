// Configuration + texture + ambient gains -> synth::OutputParams (see output_gains.h).
#include "levels/output_gains.h"

#include <cmath>

namespace sas::kiosk {
namespace {

// BS.1770's -0.691 dB between a K-weighted mean square and LUFS.
constexpr double kLufsOffsetDb = 0.691;

double FromDb(double db) {
  return std::pow(10.0, db / 20.0);
}

}  // namespace

synth::OutputParams KioskOutputParams(const KioskConfig& config,
                                      const surface::TextureGains& texture, double ambient_gain_db,
                                      bool low_vibration) {
  synth::OutputParams p;
  p.sound_gain = FromDb(config.sound_gain_db + texture.sound_gain_db + texture.sound_trim_db +
                        ambient_gain_db);
  p.haptic_gain = FromDb(config.haptic_gain_db + texture.haptic_gain_db + texture.haptic_trim_db);
  p.haptic_ceiling = FromDb(config.haptic_ceiling_db);
  p.low_vibration_gain = FromDb(-config.low_vibration_db);
  p.low_vibration = low_vibration;
  if (config.stroke_cap_lu > 0.0) {
    // The leveller's cap is a K-weighted RMS: LUFS = -0.691 + 10 log10(mean square) (BS.1770).
    p.sound_level_cap = FromDb(kCalibratedSoundLufs + config.sound_gain_db + ambient_gain_db +
                               config.stroke_cap_lu + kLufsOffsetDb);
  }
  return p;
}

}  // namespace sas::kiosk
