// Exact (zero-order-hold) discretisation of the modal resonator; see modal_resonator.h.
#include "synth/modal_resonator.h"

#include <numbers>

namespace sas::synth {

ModeStep ComputeModeStep(double frequency_hz, double decay_s, double mass_kg, double step_s) {
  const double omega_d = 2.0 * std::numbers::pi * frequency_hz;
  const double sigma = decay_s > 0.0 ? 1.0 / decay_s : 0.0;
  const double omega0_sq = omega_d * omega_d + sigma * sigma;
  const double decay = std::exp(-sigma * step_s);
  const double theta = omega_d * step_s;
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  const double half_sin = std::sin(0.5 * theta);
  ModeStep m;
  m.a11 = decay * (c + sigma / omega_d * s);
  m.a12 = decay * s / omega_d;
  m.a21 = -decay * omega0_sq / omega_d * s;
  m.a22 = decay * (c - sigma / omega_d * s);
  // 1 - a11 written so that it keeps its digits for tiny steps (contact sub-steps): 1 - e c =
  // (1 - e) + 2 e sin²(θ/2). A wrong b1 would break the exact work identity Q·Δq, i.e. passivity.
  const double one_minus_a11 = -std::expm1(-sigma * step_s) + 2.0 * decay * half_sin * half_sin -
                               decay * sigma / omega_d * s;
  m.b1 = one_minus_a11 / (mass_kg * omega0_sq);
  m.b2 = decay * s / (mass_kg * omega_d);
  return m;
}

void ModalState::Prepare(const ResonatorParams& params, double sample_rate_hz, int substeps,
                         bool keep_inaudible, bool adaptive) {
  count = 0;
  sub_compliance = 0.0;
  full_compliance = 0.0;
  // Every slot past the modes stays zero: the paired passes read one slot beyond an odd count.
  full = ModeMaps{};
  sub = ModeMaps{};
  level_maps.fill(ModeMaps{});
  gain.fill(0.0);
  const int finest = substeps < 1 ? 1 : substeps;
  level_count = 0;
  if (adaptive) {
    for (int n = 1; n < finest && level_count < kMaxSubstepLevels - 1; n *= 2) {
      level_substeps[static_cast<std::size_t>(level_count++)] = n;
    }
  }
  level_substeps[static_cast<std::size_t>(level_count++)] = finest;
  level_compliance.fill(0.0);
  const double step_s = 1.0 / sample_rate_hz;
  const int n = params.mode_count < kMaxModes ? params.mode_count : kMaxModes;
  for (int i = 0; i < n; ++i) {
    const ModeParams& mode = params.modes[static_cast<std::size_t>(i)];
    if (!(mode.frequency_hz > 0.0) || !std::isfinite(mode.frequency_hz) || !(mode.mass_kg > 0.0) ||
        !(mode.decay_s > 0.0) || !std::isfinite(mode.gain))
      continue;
    const bool audible = mode.frequency_hz < kMaxModeFrequencyRatio * sample_rate_hz &&
                         std::fabs(mode.gain) >= kNegligibleGain;
    if (!audible && !keep_inaudible) continue;
    const auto k = static_cast<std::size_t>(count);
    const double omega_d = 2.0 * std::numbers::pi * mode.frequency_hz;
    const ModeStep full_map =
        ComputeModeStep(mode.frequency_hz, mode.decay_s, mode.mass_kg, step_s);
    full.Set(k, full_map);
    ModeStep finest_map = full_map;
    for (int level = 0; level < level_count; ++level) {
      const auto l = static_cast<std::size_t>(level);
      const int steps = level_substeps[l];
      const ModeStep map = steps == 1
                               ? full_map
                               : ComputeModeStep(mode.frequency_hz, mode.decay_s, mode.mass_kg,
                                                 step_s / static_cast<double>(steps));
      level_maps[l].Set(k, map);
      level_compliance[l] += map.b1;
      finest_map = map;
    }
    sub.Set(k, finest_map);
    mass[k] = mode.mass_kg;
    omega0_sq[k] = omega_d * omega_d + 1.0 / (mode.decay_s * mode.decay_s);
    gain[k] = mode.gain;
    full_compliance += full_map.b1;
    ++count;
  }
  padded_count = (count + 1) / 2 * 2;
  sub_compliance = level_compliance[static_cast<std::size_t>(level_count - 1)];
  Reset();
}

void ModalState::Refresh() {
  double q_sum = 0.0, v_sum = 0.0, pickup = 0.0, free_next = 0.0;
  for (int i = 0; i < count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    q_sum += q[k];
    v_sum += v[k];
    pickup += gain[k] * v[k];
    free_next += (full.a11[k] - 1.0) * q[k] + full.a12[k] * v[k];
  }
  contact_displacement = q_sum;
  contact_velocity = v_sum;
  pickup_velocity = pickup;
  free_motion = free_next;
  free_motion_map = -1;
}

}  // namespace sas::synth
