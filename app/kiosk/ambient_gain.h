#pragma once
// Ambient-adaptive sound gain (for a noisy room; optional, gains.ambient_adaptive): while the
// kiosk is idle nobody is scratching or speaking, so the microphone hears the room. Its level
// moves an extra speaker gain so the exhibit stays audible over a busy gallery and does not blare
// into an empty one:
//   mic RMS (dBFS, one value per measurement period dt)
//     -> room estimate: exponential average in dB with time constant averaging_s (a cough or a
//        door slam moves it little; in dB, not power, so short loud events do not dominate)
//     -> target = clamp(min_db + per_db · (room - quiet_dbfs), min_db, max_db)
//     -> gain slews towards the target at most rate_db_per_s (never jumps, even after a pause).
// While not idle both the room estimate and the gain hold: the visitor's own stroke or voice is
// not room noise. Disabled, the gain is 0 dB. Pure logic, no devices: fed by the wiring with the
// microphone meter's level, called on the control thread.

#include "files/kiosk_config.h"

namespace sas::kiosk {

struct AmbientGainConfig {
  bool enabled = false;
  double min_db = 0.0;
  double max_db = 12.0;
  double per_db = 0.5;         // dB of gain per dB of room level above quiet_dbfs
  double quiet_dbfs = -60.0;   // a quiet room's microphone RMS: gain min_db at or below it
  double rate_db_per_s = 1.0;  // largest change of the gain per second
  double averaging_s = 5.0;    // room estimate's time constant
  double max_step_s = 0.5;     // a longer gap between measurements counts as this long
};

AmbientGainConfig AmbientGainConfigFrom(const KioskConfig& config);

class AmbientGain {
 public:
  explicit AmbientGain(const AmbientGainConfig& config);

  // One microphone measurement: RMS in dBFS over the last `dt_s` seconds. Non-finite levels and
  // non-positive dt are ignored; levels are clamped to [-120, 0] dBFS.
  void Update(double mic_rms_dbfs, double dt_s, bool idle);
  // Back to the start: no room estimate, gain at its lower bound (0 dB when disabled).
  void Reset();

  double gain_db() const { return gain_db_; }
  double target_db() const { return target_db_; }
  bool has_room_estimate() const { return has_room_; }
  double room_dbfs() const { return room_dbfs_; }

 private:
  AmbientGainConfig config_;
  bool has_room_ = false;
  double room_dbfs_ = -120.0;
  double target_db_ = 0.0;
  double gain_db_ = 0.0;
};

}  // namespace sas::kiosk
