#pragma once
// Contact between the probe (stylus tip, a point mass) and the resonator: Hunt–Crossley impact in
// the normal direction and elasto-plastic bristle friction in the tangential one, solved together
// for one (sub-)step. Sources: Hunt & Crossley 1975; Avanzini & Rocchesso, DAFx 2001 (impact);
// Dupont et al., IEEE TAC 47(5) 2002 and Avanzini, Serafin & Rocchesso, IEEE TSAP 13(5) 2005
// (friction); ../shared/reference/hunt-crossley.md and friction.md.
//
// Scheme (ContactScheme::kDiscreteGradient). Over a step h every force is held constant (zero-order
// hold). The modes and the probe are then advanced EXACTLY for that constant force, so the work
// each receives is exactly force × displacement. The forces are chosen so that this work equals
// the change of the stored contact energy plus a non-negative loss:
//   normal:   F = G·P,  G = [V(x1) - V(x0)] / (x1 - x0)  (discrete gradient of V = k
//   x₊^(α+1)/(α+1))
//             P = max(1 + μ (x1 - x0)/h, 0)              (Hunt–Crossley loss; clamped = no pull)
//             ⇒ work = ΔV + G μ Δx²/h (or ΔV - G Δx with Δx < 0 when clamped) ≥ ΔV.
//   friction: f = σ0 <z> + σ1' Δz/h + σ2 Δu/h + σ3 w,  <z> = slip-weighted mean bristle deflection
//             over the step, the bristle advanced along the slip Δu by exact exponential
//             relaxation (piecewise, frozen velocity), σ1' = σ1 unless Δz opposes Δu (then 0,
//             Dupont's passivity condition) ⇒ work = Δ(σ0 z²/2) + non-negative loss (+ noise
//             input).
// Δx and Δu are affine in (F, f) through the exact mode/probe maps, so each force is the root of a
// scalar monotone (normal) or continuous (friction) equation, found by a bracketed, safeguarded
// Newton/secant iteration; the two are coupled through the shared resonator and iterated
// (block Gauss–Seidel, contracting because the coupling is a shared compliance).
// Energy is therefore never created by the numerics (tested), for any k, α, mass or step; accuracy
// is second order in h, so the contact is sub-stepped ("oversampled") while it is active.

#include <cmath>
#include <cstdint>

#include "synth/material_params.h"

namespace sas::synth {

// True for the schemes implemented so far. The others run kDiscreteGradient until issue 4 adds
// them (Scene and SimulateRigidWallImpact substitute it).
bool IsContactSchemeImplemented(ContactScheme scheme);

struct ImpactModel {
  bool enabled = false;
  double k = 0.0;      // N/m^α
  double mu = 0.0;     // s/m (λ = μ k)
  double alpha = 1.5;  // shape

  void Set(const ImpactParams& params);
  double Potential(double x) const;  // k x₊^(α+1)/(α+1), J
  double Force(double x) const;      // k x₊^α (elastic part), N
  // x^α for x > 0, with sqrt/multiply fast paths for α = 1, 1.5, 2 (the common shapes).
  double PowAlpha(double x) const {
    switch (shape_) {
      case Shape::kOne:
        return x;
      case Shape::kThreeHalves:
        return x * std::sqrt(x);
      case Shape::kTwo:
        return x * x;
      default:
        return std::pow(x, alpha);
    }
  }

 private:
  enum class Shape : std::uint8_t { kOne, kThreeHalves, kTwo, kOther };
  Shape shape_ = Shape::kThreeHalves;
};

struct FrictionModel {
  bool enabled = false;
  double sigma0 = 0.0, sigma1 = 0.0, sigma2 = 0.0, sigma3 = 0.0;
  double mu_s = 0.0, mu_d = 0.0, v_s = 0.1, c_ba = 0.1;

  void Set(const FrictionParams& params);
  // Steady-state bristle deflection magnitude |z_ss(v)| for normal force fn (Stribeck curve).
  double SteadyDeflection(double v_mps, double fn) const;
  // Steady sliding force magnitude σ0 |z_ss(v)| + σ2 |v| (the plastic regime).
  double SteadySlidingForce(double v_mps, double fn) const;
};

// Result of advancing the bristle along a slip du over a step h at normal force fn.
struct BristleStep {
  double z1 = 0.0;      // deflection at the end of the step
  double mean_z = 0.0;  // slip-weighted mean deflection over the step (z0 if du = 0)
};
BristleStep AdvanceBristle(const FrictionModel& model, double z0, double du, double h, double fn);

// Friction force over the step for slip du (see the header comment); `noise_n` is σ3 w.
double FrictionStepForce(const FrictionModel& model, double z0, const BristleStep& step, double du,
                         double h, double noise_n);

// One contact step. Affine model of the step (forces constant over it):
//   Δx = free_dx - normal_compliance·F + coupling·f     (compression change)
//   Δu = free_du - coupling·f + coupling·F               (tangential slip change)
// with F the normal force on the probe (up) and f the friction force on the resonator.
struct ContactStepInput {
  double h = 0.0;
  double x0 = 0.0;
  double free_dx = 0.0;
  double normal_compliance = 0.0;  // coupling + h²/(2 m_probe) > 0
  double coupling = 0.0;           // resonator compliance Σ b1 (0 for a rigid body)
  double free_du = 0.0;
  double z0 = 0.0;
  double friction_normal_n = 0.0;  // f_N seen by the friction (≥ 0)
  double noise_n = 0.0;            // σ3 w for this step
  double friction_guess_n = 0.0;   // friction force of the previous step (Gauss–Seidel start)
  bool impact_on = false;
  bool friction_on = false;
};

struct ContactStepOutput {
  double normal_n = 0.0;    // F
  double friction_n = 0.0;  // f
  double dx = 0.0;
  double du = 0.0;
  double z1 = 0.0;
};

ContactStepOutput SolveContactStep(const ImpactModel& impact, const FrictionModel& friction,
                                   const ContactStepInput& in);

// Contact sub-steps per sample so that an impact at v_ref = 1 m/s of the probe mass against a
// rigid body lasts at least kTargetContactSamples sub-steps (capped at kMaxOversample).
inline constexpr double kTargetContactSamples = 128.0;
inline constexpr int kMaxOversample = 64;
double RigidWallContactTime(double mass_kg, double k, double alpha, double v_in);  // λ = 0
int ChooseContactOversample(const ImpactParams& impact, double probe_mass_kg,
                            double sample_rate_hz);

// One probe impact against a rigid, immovable body, run through the scene's own per-sample
// kernel (the same code path as Scene::Process). The probe starts in free flight and first
// touches the body `onset_phase` (0..1) of a sample after a sample instant.
struct ImpactRunResult {
  double exit_velocity_mps = 0.0;    // |v| after separation
  double max_compression_m = 0.0;    // peak of the scheme's own (piecewise parabolic) trajectory
  double contact_time_s = 0.0;       // first touch to separation (crossings interpolated)
  double samples_per_contact = 0.0;  // contact_time_s · fs
  int oversample = 1;                // sub-steps per sample used
  ContactScheme scheme_used = ContactScheme::kDiscreteGradient;  // see IsContactSchemeImplemented
  bool separated = false;  // false if the probe had not left after 10 s
};
ImpactRunResult SimulateRigidWallImpact(double mass_kg, double k, double mu, double alpha,
                                        double v_in, double sample_rate_hz, ContactScheme scheme,
                                        int oversample, double onset_phase);

}  // namespace sas::synth
