#pragma once
// The per-sample contact kernel: probe (point mass, vertical) + contact (Hunt–Crossley and
// friction, contact.h) + modal resonator (exact maps, modal_resonator.h) advanced by one output
// sample. Scene::Process and SimulateRigidWallImpact both run exactly this function, so the
// calibration command measures the code that makes the sound (never write the
// maths twice: a second copy could drift from the one that is heard).
//
// Geometry (vertical, up = positive): the surface under the probe sits at s(t) + Σ q_i (felt
// profile plus the resonator's contact displacement); the probe at y. Compression
// x = s + Σ q - y > 0 means contact. The probe is pushed down by the pen's force f_N and up by the
// contact force F; the resonator receives -F (normal) + f (friction, along the stroke, acting on
// the same modal coordinates: one pickup shared by both interactions, as in the SDT).
// While the contact is active (or about to start within the sample) the sample is split into
// equal sub-steps with the modes advanced by their exact sub-step maps; otherwise one exact
// full-sample step of free motion is taken. With adaptive oversampling (the automatic choice) the
// number of sub-steps is chosen per sample from the contact's impact speed (ChooseSubstepLevel):
// a hard landing or a bump gets what its restitution accuracy needs, a pen resting or sliding on
// the surface gets one, and a pressed pen over a vibrating surface at most
// kSustainedContactSubsteps.

#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "synth/contact.h"
#include "synth/modal_resonator.h"

namespace sas::synth {

// The elasto-plastic model's viscous term σ2 v does not depend on the load, so when the contact
// opens under a sliding tip it vanishes in one sample: lifting a pen sliding at 300 mm/s over
// bubble wrap (σ2 = 1 N s/m: 0.3 N, more than a light press) popped louder than the stroke. The
// viscous part of friction acts over the real contact area, which goes to zero with the load
// (Hertz: area ∝ f_N^(2/3), Johnson, "Contact Mechanics", §4.2): below kFullViscousLoadN it is
// scaled by that area, above it is the material's σ2 (every stroke the kiosk plays presses
// harder: its lightest, 0.2 N, is 0.1 N of friction load on a tilted rub).
inline constexpr double kFullViscousLoadN = 0.1;

// Whether ViscousAtLoad scales σ2 for this friction load (below).
inline bool ViscousScaled(const FrictionModel& friction, double friction_load_n) {
  return friction_load_n < kFullViscousLoadN && friction.sigma2 > 0.0;
}
// `friction`, or its copy made in `light` with σ2 scaled for a friction load under
// kFullViscousLoadN (only then is a copy made: the audio path's usual case costs nothing).
inline const FrictionModel& ViscousAtLoad(const FrictionModel& friction, double friction_load_n,
                                          std::optional<FrictionModel>& light) {
  if (!ViscousScaled(friction, friction_load_n)) return friction;
  light.emplace(friction);
  light->sigma2 *= std::cbrt(std::pow(std::max(friction_load_n, 0.0) / kFullViscousLoadN, 2.0));
  return *light;
}

struct ContactKernelConfig {
  ImpactModel impact;
  FrictionModel friction;
  // The scheme that runs; the sub-step solve dispatches on it (contact.h describes each).
  ContactScheme scheme = kDefaultContactScheme;
  double probe_mass_kg = 0.01;
  double period_s = 1.0 / 48000.0;
  double sub_step_s = 1.0 / 48000.0;
  int substeps = 1;  // the finest level (the material's count)
  // Adaptive oversampling: level L of the ModalState (level_substeps[L] sub-steps) serves impact
  // speeds up to sqrt(level_speed_sq[L]) (ContactSubstepsForSpeed); the finest level, any speed.
  bool adaptive = false;
  std::array<double, kMaxSubstepLevels> level_speed_sq{};
  // The finest level a sustained contact may use (SustainedContactSubsteps sub-steps at most),
  // and the coarsest it may use while friction acts (ImpactParams::pressed_floor; else level 0).
  int sustained_level = kMaxSubstepLevels - 1;
  int pressed_floor_level = 0;

  double rate_hz = 48000.0;       // 1 / period_s
  double inv_probe_mass = 100.0;  // 1 / probe_mass_kg

  // Sets the timing (and the reciprocals the kernel multiplies by): call after probe_mass_kg.
  void SetTiming(double sample_rate_hz, int contact_substeps) {
    substeps = contact_substeps < 1 ? 1 : contact_substeps;
    rate_hz = sample_rate_hz;
    inv_probe_mass = 1.0 / probe_mass_kg;
    period_s = 1.0 / sample_rate_hz;
    sub_step_s = period_s / static_cast<double>(substeps);
  }
  // Fills level_speed_sq for the levels of `modes` (adaptive only). Not real-time.
  void SetLevels(const ImpactParams& params, const ModalState& modes, double sample_rate_hz) {
    level_speed_sq.fill(0.0);
    for (int level = 0; level < modes.level_count; ++level) {
      const auto l = static_cast<std::size_t>(level);
      level_speed_sq[l] =
          level + 1 == modes.level_count
              ? std::numeric_limits<double>::infinity()
              : MaxSpeedForSubsteps(params, probe_mass_kg, sample_rate_hz, modes.level_substeps[l]);
      level_speed_sq[l] *= level_speed_sq[l];
    }
    sustained_level = 0;
    for (int level = 0; level < modes.level_count; ++level) {
      if (modes.level_substeps[static_cast<std::size_t>(level)] <=
          SustainedContactSubsteps(params)) {
        sustained_level = level;
      }
    }
    pressed_floor_level = params.pressed_floor ? sustained_level : 0;
  }
};

struct ProbeDynamics {
  bool active = false;            // false: parked (tip up), nothing computed
  double height_m = 0.0;          // y
  double velocity_mps = 0.0;      // dy/dt
  double bristle_m = 0.0;         // z
  double normal_n = 0.0;          // last F (up, on the probe)
  double friction_n = 0.0;        // last f (on the resonator)
  double compression_m = 0.0;     // x at the end of the last step
  double contact_aux = 0.0;       // the scheme's contact state (ContactStepInput::aux0)
  double slip_slope = 0.0;        // the coupled solve's last slip-residual slope (next start)
  double contact_energy_j = 0.0;  // energy the scheme holds in the contact (V(x), E or ψ²/2)
  int substeps_used = 0;
  bool touched = false;  // a contact force acted during the last sample
  // Adaptive oversampling: the level held over the current compression (re-chosen when a new
  // compression starts), whether the contact was closing at the last sample, and the push whose
  // equilibrium energy min_x [V(x) - f_N x] is cached.
  int held_level = 0;
  bool closing = false;
  double equilibrium_push_n = 0.0;
  double equilibrium_energy_j = 0.0;
};

// What the control side imposes over one sample.
struct SampleDrive {
  double surface_begin_m = 0.0;     // felt profile height at the start of the sample
  double surface_end_m = 0.0;       // ... and at its end (linear in between)
  double slide_velocity_mps = 0.0;  // tangential velocity of the probe (driven by the hand)
  double push_n = 0.0;              // f_N pressing the probe down
  double friction_share = 1.0;      // style weight of the friction (roll = 0)
  double noise_n = 0.0;             // σ3 w for this sample
};

// One contact sub-step with the configured scheme (contact.h describes each).
[[gnu::always_inline]] inline ContactStepOutput SolveContactStepWith(
    const ContactKernelConfig& config, const FrictionModel& friction, const ContactStepInput& in) {
  switch (config.scheme) {
    case ContactScheme::kExplicitPassive:
      return SolveContactStepExplicit(config.impact, friction, in);
    case ContactScheme::kTrapezoidNewton:
      return SolveContactStepTrapezoid(config.impact, friction, in);
    case ContactScheme::kEnergyQuadratised:
      return SolveContactStepQuadratised(config.impact, friction, in);
    case ContactScheme::kDiscreteGradient:
    default:
      return SolveContactStep(config.impact, friction, in);
  }
}

struct NoObserver {
  void operator()(double, double, double, double, double) const {}
};

// Advances probe + contact + modes by one sample. `observe(h, x0, x1, v0, v1)` is called once per
// (sub-)step with the step length, compression and probe velocity before/after (tests,
// calibration).
template <class Observer = NoObserver>
inline void StepContactSample(const ContactKernelConfig& config, ModalState& modes,
                              ProbeDynamics& probe, const SampleDrive& drive,
                              Observer&& observe = Observer{}) {
  const bool touched_before = probe.touched;
  probe.touched = false;
  if (!probe.active) {
    AdvanceModes(modes, modes.full, 0.0);
    probe.substeps_used = 0;
    return;
  }
  const double inv_mass = config.inv_probe_mass;
  const double rate = config.rate_hz;
  const bool impact_on = config.impact.enabled;
  const bool friction_on = config.friction.enabled && drive.friction_share > 0.0;
  const double period = config.period_s;
  double contact_displacement = modes.ContactDisplacement();
  const double x_start = drive.surface_begin_m + contact_displacement - probe.height_m;

  bool contact = false;
  if (impact_on) {
    const double x_end_free = drive.surface_end_m + contact_displacement +
                              FreeContactMotion(modes, modes.full) -
                              (probe.height_m + probe.velocity_mps * period -
                               0.5 * drive.push_n * inv_mass * period * period);
    contact = x_start > 0.0 || x_end_free > 0.0;
  } else {
    contact = friction_on && drive.push_n > 0.0;
  }

  if (!contact) {
    // Free flight: exact parabola for the probe, exact free ring of the modes, bristle relaxed.
    const double v0 = probe.velocity_mps;
    AdvanceModes(modes, modes.full, 0.0);
    probe.height_m += v0 * period - 0.5 * drive.push_n * inv_mass * period * period;
    probe.velocity_mps = v0 - drive.push_n * inv_mass * period;
    probe.bristle_m = 0.0;
    probe.normal_n = 0.0;
    probe.friction_n = 0.0;
    probe.contact_aux = 0.0;
    probe.contact_energy_j = 0.0;
    probe.held_level = 0;
    probe.closing = false;
    probe.compression_m = drive.surface_end_m + modes.ContactDisplacement() - probe.height_m;
    probe.substeps_used = 1;
    observe(period, x_start, probe.compression_m, v0, probe.velocity_mps);
    return;
  }

  int level = modes.level_count - 1;
  if (config.adaptive) {
    // Impact speed: the closing speed the contact would reach at its equilibrium under the push,
    // v² = ẋ² + 2 [V(x) - f_N x - min(V - f_N x)] / m (energy of the probe's motion relative to
    // the surface, measured from the static equilibrium; = ẋ² in free flight without push).
    const double xdot = (drive.surface_end_m - drive.surface_begin_m) * rate +
                        modes.ContactVelocity() - probe.velocity_mps;
    if (drive.push_n != probe.equilibrium_push_n) {
      probe.equilibrium_push_n = drive.push_n;
      probe.equilibrium_energy_j = EquilibriumEnergy(config.impact, drive.push_n);
    }
    const double excess =
        config.impact.Potential(x_start) - drive.push_n * x_start - probe.equilibrium_energy_j;
    const double speed_sq = xdot * xdot + 2.0 * std::max(excess, 0.0) * inv_mass;
    int needed = 0;
    while (needed + 1 < modes.level_count &&
           speed_sq > config.level_speed_sq[static_cast<std::size_t>(needed)]) {
      ++needed;
    }
    // A sustained contact (pressed at the start of the sample, a force acting in the last one) is
    // not an impact: kSustainedContactSubsteps in contact.h.
    if (touched_before && x_start > 0.0) {
      needed = std::min(needed, config.sustained_level);
      if (friction_on) needed = std::max(needed, config.pressed_floor_level);
    }
    // Hold the level over one compression: re-chosen when the contact starts closing again.
    const bool closing = xdot > 0.0;
    if (closing && !probe.closing) probe.held_level = needed;
    probe.closing = closing;
    probe.held_level = std::max(probe.held_level, needed);
    level = probe.held_level;
  }
  const auto level_index = static_cast<std::size_t>(level);
  const auto& sub_maps = modes.level_maps[level_index];
  const int n = modes.level_substeps[level_index];
  const double inv_n = n == 1 ? 1.0 : modes.level_inverse[level_index];
  const double h = n == config.substeps ? config.sub_step_s : period * inv_n;
  const double sub_compliance = modes.level_compliance[level_index];
  const bool needs_rate = impact_on && SchemeNeedsCompressionRate(config.scheme);
  const double surface_rate = (drive.surface_end_m - drive.surface_begin_m) * rate;
  double surface = drive.surface_begin_m;
  for (int j = 0; j < n; ++j) {
    const double surface_next =
        j + 1 == n ? drive.surface_end_m
                   : drive.surface_begin_m + (drive.surface_end_m - drive.surface_begin_m) *
                                                 static_cast<double>(j + 1) * inv_n;
    const double x0 = surface + contact_displacement - probe.height_m;
    const ModeMaps& step_maps = n == 1 ? modes.full : sub_maps;
    const double free_resonator = FreeContactMotion(modes, step_maps);
    const double v0 = probe.velocity_mps;
    // Every field is given (designated initialisers in declaration order): a default-constructed
    // input followed by assignments made GCC clear the struct with `rep stos` first on every
    // sub-step; without it the kiosk scene runs ~18 % faster (contact_bench, A/B).
    const double half_h_sq_over_m = 0.5 * h * h * inv_mass;
    ContactStepInput in{
        .h = h,
        .inv_h = rate * static_cast<double>(n),
        .x0 = x0,
        // Impact off: no compression to track.
        .free_dx = impact_on ? (surface_next - surface) + free_resonator -
                                   (v0 * h - half_h_sq_over_m * drive.push_n)
                             : 0.0,
        .normal_compliance = impact_on ? sub_compliance + half_h_sq_over_m : 0.0,
        .coupling = sub_compliance,
        .free_du = drive.slide_velocity_mps * h - free_resonator,
        .z0 = probe.bristle_m,
        // With the impact on, whether friction acts (and the general solve's load) follows the
        // normal force of the previous sub-step; a closed, sliding step loads it with its own
        // normal force (friction_load_share). Either way the friction step stays passive: it is
        // for any f_N >= 0.
        .friction_normal_n =
            drive.friction_share *
            (impact_on ? (probe.normal_n > 0.0 ? probe.normal_n : 0.0) : drive.push_n),
        .friction_load_share = impact_on ? drive.friction_share : 0.0,
        .noise_n = drive.noise_n,
        .friction_guess_n = probe.friction_n,
        .slip_slope_guess = probe.slip_slope,
        .normal_guess_n = probe.normal_n,
        // ẋ = s' + Σ q' - y' (only the explicit and trapezoid schemes read it: one pass over the
        // modes).
        .xdot0 = needs_rate ? surface_rate + modes.ContactVelocity() - v0 : 0.0,
        .aux0 = probe.contact_aux,
        .impact_on = impact_on,
        .friction_on = friction_on,
    };
    // ViscousAtLoad's copy only in the branch that needs it: an optional declared for every
    // sub-step was cleared (112 bytes, `rep stos`) on each, a pressed stroke's usual case too.
    ContactStepOutput out;
    if (!ViscousScaled(config.friction, in.friction_normal_n)) {
      out = SolveContactStepWith(config, config.friction, in);
    } else {
      std::optional<FrictionModel> light_load;
      out = SolveContactStepWith(
          config, ViscousAtLoad(config.friction, in.friction_normal_n, light_load), in);
    }

    // The free motion of the next sub-step (or of the next full sample) comes out of this pass.
    AdvanceModes(modes, step_maps, out.friction_n - out.normal_n,
                 j + 1 < n ? &step_maps : &modes.full);
    contact_displacement = modes.ContactDisplacement();
    if (impact_on) {
      const double acc = (out.normal_n - drive.push_n) * inv_mass;
      probe.height_m += v0 * h + 0.5 * acc * h * h;
      probe.velocity_mps = v0 + acc * h;
    }
    probe.bristle_m = in.friction_normal_n > 0.0 && friction_on ? out.z1 : 0.0;
    probe.normal_n = out.normal_n;
    probe.friction_n = out.friction_n;
    probe.contact_aux = out.aux1;
    probe.slip_slope = out.slip_slope;
    probe.contact_energy_j = out.contact_energy_j;
    if (out.normal_n != 0.0 || out.friction_n != 0.0) probe.touched = true;
    surface = surface_next;
    const double x1 = surface + contact_displacement - probe.height_m;
    observe(h, x0, x1, v0, probe.velocity_mps);
    probe.compression_m = x1;
  }
  probe.substeps_used = n;
}

}  // namespace sas::synth
