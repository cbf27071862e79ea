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

// The maps of all modes for one step length, one array per coefficient (structure of arrays), so
// the per-sample pass runs two modes per SIMD register. Slots past the mode count are zero.
struct ModeMaps {
  alignas(32) std::array<double, kMaxModes> a11{};
  alignas(32) std::array<double, kMaxModes> a12{};
  alignas(32) std::array<double, kMaxModes> a21{};
  alignas(32) std::array<double, kMaxModes> a22{};
  alignas(32) std::array<double, kMaxModes> b1{};
  alignas(32) std::array<double, kMaxModes> b2{};
  void Set(std::size_t k, const ModeStep& m) {
    a11[k] = m.a11;
    a12[k] = m.a12;
    a21[k] = m.a21;
    a22[k] = m.a22;
    b1[k] = m.b1;
    b2[k] = m.b2;
  }
};

// Sub-step levels a ModalState keeps maps for: the contact may run 1, 2, 4, ... sub-steps per
// sample (adaptive oversampling, contact_kernel.h) up to the material's count.
inline constexpr int kMaxSubstepLevels = 9;

// The computed modes, packed (only the active ones), with their exact maps for a full sample and
// for one contact sub-step at each level. Plain data so the per-sample kernel can keep it in
// cache. The sums the kernel needs every sample (contact displacement and velocity, pickup
// velocity, the free motion over the next full sample) are accumulated in the same pass that
// advances the modes (AdvanceModes), so a sample costs one or two passes over the modes.
struct ModalState {
  int count = 0;
  int padded_count = 0;                           // count rounded up to even (SIMD pairs)
  alignas(32) std::array<double, kMaxModes> q{};  // displacement at the contact point, m
  alignas(32) std::array<double, kMaxModes> v{};  // velocity, m/s
  ModeMaps full{};
  ModeMaps sub{};  // the finest level: `substeps` sub-steps per sample
  std::array<double, kMaxModes> mass{};
  std::array<double, kMaxModes> omega0_sq{};
  alignas(32) std::array<double, kMaxModes> gain{};
  double sub_compliance = 0.0;   // Σ b1 over the finest sub-step: Δ(contact displacement) per N
  double full_compliance = 0.0;  // Σ b1 over a full sample
  // Levels, coarsest first: level_substeps[0] = 1 when adaptive (its map is `full`), and the last
  // level is always `substeps` (its map is `sub`).
  int level_count = 1;
  std::array<int, kMaxSubstepLevels> level_substeps{1};
  std::array<double, kMaxSubstepLevels> level_inverse{1.0};  // 1 / level_substeps
  std::array<double, kMaxSubstepLevels> level_compliance{};
  std::array<ModeMaps, kMaxSubstepLevels> level_maps{};
  // Cached sums of the current state (kept by AdvanceModes and Reset).
  double contact_displacement = 0.0;  // Σ q
  double contact_velocity = 0.0;      // Σ v
  double pickup_velocity = 0.0;       // Σ g v
  double free_motion = 0.0;           // Σ Δq over one step of map free_motion_map with no force
  int free_motion_map = -1;           // which map: -1 full, L level_maps[L] (MapId; an index, not a
                                      // pointer, so that a copied state stays valid)

  // Fills the packed arrays from `params` (fs in Hz, `substeps` contact sub-steps per sample)
  // and zeroes the state. `keep_inaudible` computes the modes at or above 0.45 fs and those with
  // negligible gain too (tests comparing against the skip). `adaptive` keeps maps for 1, 2, 4, ...
  // sub-steps below `substeps` as well.
  void Prepare(const ResonatorParams& params, double sample_rate_hz, int substeps,
               bool keep_inaudible = false, bool adaptive = false);
  void Reset() {
    q.fill(0.0);
    v.fill(0.0);
    contact_displacement = contact_velocity = pickup_velocity = free_motion = 0.0;
    free_motion_map = -1;  // at rest the free motion is 0 for every map
  }

  // An impulse (N s, up = positive) on the resonator at the contact point, too brief for a
  // step to resolve: every mode's velocity jumps by impulse / mass. Keeps the cached sums.
  void Kick(double impulse_n_s) {
    // The sums in locals: updated in place, each mode's store to v might alias them as far as the
    // compiler knows, and every mode paid a store and a reload on both chains (a rolling ball
    // kicks every sample). Same additions in the same order: the same sums, bit for bit.
    double contact = contact_velocity, pickup = pickup_velocity;
    for (int i = 0; i < count; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const double dv = impulse_n_s / mass[k];
      v[k] += dv;
      contact += dv;
      pickup += gain[k] * dv;
    }
    contact_velocity = contact;
    pickup_velocity = pickup;
    free_motion_map = -2;  // the cached free motion was for the old velocities
  }

  double ContactDisplacement() const { return contact_displacement; }
  double ContactVelocity() const {  // Σ q', the surface's velocity at the contact point
    return contact_velocity;
  }
  double PickupVelocity() const { return pickup_velocity; }
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

// Identifies one of `s`'s own maps: -1 full, L for level_maps[L], -2 any other (not cached).
inline int MapId(const ModalState& s, const ModeMaps& maps) {
  if (&maps == &s.full) return -1;
  for (int level = 0; level < s.level_count; ++level) {
    if (&maps == &s.level_maps[static_cast<std::size_t>(level)]) return level;
  }
  return -2;
}

// The per-sample pass (AdvanceModes / FreeContactMotion below), out of line: on x86-64 it is built
// twice, for the baseline and for AVX2 (picked at load time; the arithmetic and the order of the
// sums are the same in both, so the output does not depend on the machine); arm64 builds it once.
double AdvanceModesPass(ModalState& s, const ModeMaps& steps, double force_n, const ModeMaps& next);
double FreeMotionPass(const ModalState& s, const ModeMaps& steps);

// Advances every mode by one step of map `steps` under constant contact force `force_n`, and
// refreshes the cached sums in the same pass, including the free motion over the NEXT step, taken
// with `next` (nullptr: a full sample). Returns the change of the contact displacement.
inline double AdvanceModes(ModalState& s, const ModeMaps& steps, double force_n,
                           const ModeMaps* next = nullptr) {
  return AdvanceModesPass(s, steps, force_n, next != nullptr ? *next : s.full);
}

// Change of the contact displacement over one step of `steps` if no force acted.
inline double FreeContactMotion(const ModalState& s, const ModeMaps& steps) {
  if (const int id = MapId(s, steps); id != -2 && id == s.free_motion_map) return s.free_motion;
  return FreeMotionPass(s, steps);
}

}  // namespace sas::synth
