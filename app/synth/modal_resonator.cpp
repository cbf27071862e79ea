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
  // Every slot past the modes stays zero: the SIMD pass reads up to three slots beyond the count.
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
  for (int level = 0; level < level_count; ++level) {
    const auto l = static_cast<std::size_t>(level);
    level_inverse[l] = 1.0 / static_cast<double>(level_substeps[l]);
  }
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
  padded_count = (count + 3) / 4 * 4;
  sub_compliance = level_compliance[static_cast<std::size_t>(level_count - 1)];
  Reset();
}

namespace {
// Four doubles per vector through the compiler's vector extension: one AVX2 register, or two SSE2
// registers in the baseline build (same lanes, same operations, same results). Loads and stores
// go through memcpy (no aliasing assumptions); everything stays inside the functions below, so no
// vector crosses a call (no ABI difference between the clones).
using Double4 = double __attribute__((vector_size(32)));
}  // namespace

// The AVX2 clone is x86-64's alone (GCC rejects the target elsewhere); an arm64 build (the
// Raspberry Pi) compiles the one version, with Double4 in two NEON registers.
#if defined(__x86_64__)
#define SAS_AVX2_CLONE __attribute__((target_clones("default", "avx2")))
#else
#define SAS_AVX2_CLONE
#endif

#define SAS_LOAD4(dst, src) __builtin_memcpy(&(dst), (src), sizeof(Double4))

SAS_AVX2_CLONE double AdvanceModesPass(ModalState& s, const ModeMaps& steps, double force_n,
                                       const ModeMaps& next) {
  Double4 q_sum{0.0, 0.0, 0.0, 0.0}, v_sum = q_sum, pickup = q_sum, free_next = q_sum;
  const Double4 force{force_n, force_n, force_n, force_n};
  const Double4 one{1.0, 1.0, 1.0, 1.0};
  // Locals: the byte-wise stores below may alias anything, so nothing is re-read from `s`.
  const int count = s.padded_count;
  double* const q = s.q.data();
  double* const v = s.v.data();
  const double* const gains = s.gain.data();
  for (int i = 0; i < count; i += 4) {
    const auto k = static_cast<std::size_t>(i);
    Double4 q0, v0, a11, a12, a21, a22, b1, b2, gain, n11, n12;
    SAS_LOAD4(q0, q + k);
    SAS_LOAD4(v0, v + k);
    SAS_LOAD4(a11, &steps.a11[k]);
    SAS_LOAD4(a12, &steps.a12[k]);
    SAS_LOAD4(a21, &steps.a21[k]);
    SAS_LOAD4(a22, &steps.a22[k]);
    SAS_LOAD4(b1, &steps.b1[k]);
    SAS_LOAD4(b2, &steps.b2[k]);
    SAS_LOAD4(gain, gains + k);
    SAS_LOAD4(n11, &next.a11[k]);
    SAS_LOAD4(n12, &next.a12[k]);
    const Double4 q1 = a11 * q0 + a12 * v0 + b1 * force;
    const Double4 v1 = a21 * q0 + a22 * v0 + b2 * force;
    __builtin_memcpy(q + k, &q1, sizeof q1);
    __builtin_memcpy(v + k, &v1, sizeof v1);
    q_sum += q1;
    v_sum += v1;
    pickup += gain * v1;
    free_next += (n11 - one) * q1 + n12 * v1;
  }
  const double q_total = (q_sum[0] + q_sum[1]) + (q_sum[2] + q_sum[3]);
  const double change = q_total - s.contact_displacement;
  s.contact_displacement = q_total;
  s.contact_velocity = (v_sum[0] + v_sum[1]) + (v_sum[2] + v_sum[3]);
  s.pickup_velocity = (pickup[0] + pickup[1]) + (pickup[2] + pickup[3]);
  s.free_motion = (free_next[0] + free_next[1]) + (free_next[2] + free_next[3]);
  s.free_motion_map = MapId(s, next);
  return change;
}

SAS_AVX2_CLONE double FreeMotionPass(const ModalState& s, const ModeMaps& steps) {
  Double4 sum{0.0, 0.0, 0.0, 0.0};
  const Double4 one{1.0, 1.0, 1.0, 1.0};
  for (int i = 0; i < s.padded_count; i += 4) {
    const auto k = static_cast<std::size_t>(i);
    Double4 q, v, a11, a12;
    SAS_LOAD4(q, &s.q[k]);
    SAS_LOAD4(v, &s.v[k]);
    SAS_LOAD4(a11, &steps.a11[k]);
    SAS_LOAD4(a12, &steps.a12[k]);
    sum += (a11 - one) * q + a12 * v;
  }
  return (sum[0] + sum[1]) + (sum[2] + sum[3]);
}

#undef SAS_LOAD4
#undef SAS_AVX2_CLONE

}  // namespace sas::synth
