// Ambient-adaptive sound gain: room estimate, bounded target, slew-limited gain (ambient_gain.h).
#include "kiosk/ambient_gain.h"

#include <algorithm>
#include <cmath>

namespace sas::kiosk {

AmbientGainConfig AmbientGainConfigFrom(const KioskConfig& config) {
  return {.enabled = config.ambient_adaptive,
          .min_db = config.ambient_min_db,
          .max_db = config.ambient_max_db,
          .per_db = config.ambient_per_db,
          .quiet_dbfs = config.ambient_quiet_dbfs,
          .rate_db_per_s = config.ambient_rate_db_per_s};
}

AmbientGain::AmbientGain(const AmbientGainConfig& config) : config_(config) {
  if (config_.max_db < config_.min_db) std::swap(config_.min_db, config_.max_db);
  Reset();
}

void AmbientGain::Reset() {
  has_room_ = false;
  room_dbfs_ = -120.0;
  target_db_ = gain_db_ = config_.enabled ? config_.min_db : 0.0;
}

void AmbientGain::Update(double mic_rms_dbfs, double dt_s, bool idle) {
  if (!config_.enabled || !idle) return;
  if (!std::isfinite(mic_rms_dbfs) || !std::isfinite(dt_s) || dt_s <= 0.0) return;
  const double level = std::clamp(mic_rms_dbfs, -120.0, 0.0);
  const double dt = std::min(dt_s, config_.max_step_s);
  if (!has_room_) {
    room_dbfs_ = level;  // the first measurement is the best estimate there is
    has_room_ = true;
  } else {
    const double alpha = 1.0 - std::exp(-dt / std::max(config_.averaging_s, 1e-3));
    room_dbfs_ += alpha * (level - room_dbfs_);
  }
  target_db_ = std::clamp(config_.min_db + config_.per_db * (room_dbfs_ - config_.quiet_dbfs),
                          config_.min_db, config_.max_db);
  const double max_step = config_.rate_db_per_s * dt;
  gain_db_ += std::clamp(target_db_ - gain_db_, -max_step, max_step);
}

}  // namespace sas::kiosk
