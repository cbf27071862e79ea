#pragma once
// Modal resonator: the vibrating material as a sum of independent damped oscillators, each seen
// at the contact point with its modal mass and heard at the pickup with its gain (paper §4; the
// Sound Design Toolkit's modal resonator). Mode i obeys
//     m_i (q_i'' + 2 σ_i q_i' + ω0_i² q_i) = Q(t),     σ_i = 1 / decay_s,  ω0_i² = ω_i² + σ_i²,
// where ω_i = 2π frequency_hz is the ringing (damped) frequency and decay_s the 1/e time of the
// amplitude envelope. Q is the force on the resonator at the contact, held constant over each
// step (zero-order hold), and the state is advanced by the EXACT solution of that ODE (the matrix
// exponential): no frequency warping, no decay error, and the work done on a mode over a step is
// exactly Q·Δq minus the (non-negative) damping loss, which keeps the coupled scheme passive.
// Modes at or above 0.45 fs, or with |gain| below kNegligibleGain, are not computed.

#include <array>
#include <cmath>

#include "synth/material_params.h"

namespace sas::synth {

inline constexpr double kNegligibleGain = 1e-9;
inline constexpr double kMaxModeFrequencyRatio = 0.45;  // of the sample rate

// Exact one-step map of a damped oscillator driven by a constant force Q over a step of length h:
//   [q']   [a11 a12] [q]   [b1]
//   [v'] = [a21 a22] [v] + [b2] Q
struct ModeStep {
  double a11 = 1.0, a12 = 0.0, a21 = 0.0, a22 = 1.0, b1 = 0.0, b2 = 0.0;
};

// Computes the exact step for frequency_hz (damped), decay_s (1/e), mass_kg and step h_s.
ModeStep ComputeModeStep(double frequency_hz, double decay_s, double mass_kg, double step_s);

// The computed modes, packed (only the active ones), with their exact maps for a full sample and
// for one contact sub-step. Plain data so the per-sample kernel can keep it in registers/cache.
struct ModalState {
  int count = 0;
  std::array<double, kMaxModes> q{};  // displacement at the contact point, m
  std::array<double, kMaxModes> v{};  // velocity, m/s
  std::array<ModeStep, kMaxModes> full{};
  std::array<ModeStep, kMaxModes> sub{};
  std::array<double, kMaxModes> mass{};
  std::array<double, kMaxModes> omega0_sq{};
  std::array<double, kMaxModes> gain{};
  double sub_compliance = 0.0;   // Σ b1 over the sub-step: Δ(contact displacement) per newton
  double full_compliance = 0.0;  // Σ b1 over a full sample

  // Fills the packed arrays from `params` (fs in Hz, `substeps` contact sub-steps per sample)
  // and zeroes the state. `keep_inaudible` computes the modes at or above 0.45 fs and those with
  // negligible gain too (tests comparing against the skip).
  void Prepare(const ResonatorParams& params, double sample_rate_hz, int substeps,
               bool keep_inaudible = false);
  void Reset() {
    q.fill(0.0);
    v.fill(0.0);
  }

  double ContactDisplacement() const {
    double sum = 0.0;
    for (int i = 0; i < count; ++i) sum += q[static_cast<std::size_t>(i)];
    return sum;
  }
  double ContactVelocity() const {  // Σ q', the surface's velocity at the contact point
    double sum = 0.0;
    for (int i = 0; i < count; ++i) sum += v[static_cast<std::size_t>(i)];
    return sum;
  }
  double PickupVelocity() const {
    double sum = 0.0;
    for (int i = 0; i < count; ++i) {
      const auto k = static_cast<std::size_t>(i);
      sum += gain[k] * v[k];
    }
    return sum;
  }
  double Energy() const {
    double sum = 0.0;
    for (int i = 0; i < count; ++i) {
      const auto k = static_cast<std::size_t>(i);
      sum += 0.5 * mass[k] * (v[k] * v[k] + omega0_sq[k] * q[k] * q[k]);
    }
    return sum;
  }
  // Upper bound of the pickup amplitude Σ |g| · (velocity amplitude of each mode).
  double PickupAmplitudeBound() const {
    double sum = 0.0;
    for (int i = 0; i < count; ++i) {
      const auto k = static_cast<std::size_t>(i);
      sum += std::fabs(gain[k]) * std::sqrt(v[k] * v[k] + omega0_sq[k] * q[k] * q[k]);
    }
    return sum;
  }
};

// Advances every mode by one step of map `steps` under constant contact force `force_n`.
// Returns the change of the contact displacement Σ Δq.
inline double AdvanceModes(ModalState& s, const std::array<ModeStep, kMaxModes>& steps,
                           double force_n) {
  double dq_sum = 0.0;
  for (int i = 0; i < s.count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const ModeStep& m = steps[k];
    const double q0 = s.q[k], v0 = s.v[k];
    const double q1 = m.a11 * q0 + m.a12 * v0 + m.b1 * force_n;
    s.v[k] = m.a21 * q0 + m.a22 * v0 + m.b2 * force_n;
    s.q[k] = q1;
    dq_sum += q1 - q0;
  }
  return dq_sum;
}

// Change of the contact displacement over one step of `steps` if no force acted.
inline double FreeContactMotion(const ModalState& s, const std::array<ModeStep, kMaxModes>& steps) {
  double dq_sum = 0.0;
  for (int i = 0; i < s.count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const ModeStep& m = steps[k];
    dq_sum += (m.a11 - 1.0) * s.q[k] + m.a12 * s.v[k];
  }
  return dq_sum;
}

}  // namespace sas::synth
