// The four contact schemes (synth/contact.h) through the engine's own kernel
// (SimulateRigidWallImpact runs StepContactSample, the code Scene::Process runs), each against the
// Hunt–Crossley closed forms (HuntCrossleyImpact): accuracy at its
// automatic oversampling, its order of convergence, and passivity over the whole parameter range
// (k <= 1e12, 1 <= α <= 4, probe 0.1 g .. 1 kg, v <= 10 m/s).
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "synth/contact.h"
#include "synth/hunt_crossley_closed_form.h"

using namespace sas::synth;

namespace {

constexpr double kFs = 48000.0;
constexpr double kMass = 0.01, kAlpha = 1.5;
#if defined(__SANITIZE_ADDRESS__)
constexpr int kPhaseStride = 4;  // ~10x slower under the sanitizer: every 4th of the 32 phases
#else
constexpr int kPhaseStride = 1;
#endif

struct SchemeCase {
  ContactScheme scheme;
  const char* name;
  double accuracy;  // worst relative restitution error at automatic oversampling (k 1e6, 1e8)
};

// The accuracy each scheme reaches at its automatic oversampling (TargetContactSamples): 1e-4 for
// the second-order schemes; the first-order explicit one at the kMaxOversample cap reaches ~1e-3.
constexpr SchemeCase kSchemes[] = {
    {ContactScheme::kExplicitPassive, "explicit passive", 2e-3},
    {ContactScheme::kTrapezoidNewton, "trapezoid Newton", 1e-4},
    {ContactScheme::kDiscreteGradient, "discrete gradient", 1e-4},
    {ContactScheme::kEnergyQuadratised, "energy quadratised", 1e-4},
};

// Worst relative exit-velocity error over the onset phases.
double WorstError(ContactScheme scheme, double mass, double k, double mu_v, double alpha,
                  double v_in, int oversample, int phase_stride = kPhaseStride) {
  const double mu = mu_v / v_in;
  const auto exact = HuntCrossleyImpact(mass, k, mu, alpha, v_in);
  double worst = 0.0;
  for (int p = 0; p < 32; p += phase_stride) {
    const auto run = SimulateRigidWallImpact(mass, k, mu, alpha, v_in, kFs, scheme, oversample,
                                             (p + 0.5) / 32.0);
    if (!run.separated) return 1.0;
    worst = std::max(worst, std::fabs(run.exit_velocity_mps / exact.exit_speed_mps - 1.0));
  }
  return worst;
}

}  // namespace

TEST_CASE("every named contact scheme is implemented and runs as itself", "[dsp]") {
  for (const auto& c : kSchemes) {
    INFO(c.name);
    CHECK(IsContactSchemeImplemented(c.scheme));
    const auto run = SimulateRigidWallImpact(kMass, 1e8, 0.5, kAlpha, 1.0, kFs, c.scheme, 4, 0.3);
    CHECK(run.scheme_used == c.scheme);
    CHECK(run.oversample == 4);
  }
  // The schemes are distinct methods: the same under-resolved impact gives four different
  // restitutions.
  double exits[4];
  for (int i = 0; i < 4; ++i) {
    exits[i] =
        SimulateRigidWallImpact(kMass, 1e8, 1.0, kAlpha, 1.0, kFs, kSchemes[i].scheme, 1, 0.3)
            .exit_velocity_mps;
  }
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < 4; ++j) CHECK(exits[i] != exits[j]);
  }
}

TEST_CASE(
    "every scheme's exit velocity matches the Lambert-W closed form at its accuracy level at "
    "every one of 32 onset phases (48 kHz, 10 g, alpha 1.5, k 1e6 and 1e8, mu*v_in 0.1 and 1, "
    "automatic oversampling)",
    "[dsp]") {
  for (const auto& c : kSchemes) {
    for (const double k : {1e6, 1e8}) {
      for (const double mu_v : {0.1, 1.0}) {
        const double worst = WorstError(c.scheme, kMass, k, mu_v, kAlpha, 1.0, 0);
        INFO(c.name << " k " << k << " mu*v " << mu_v << " worst error " << worst);
        CHECK(worst <= c.accuracy);
      }
    }
  }
}

TEST_CASE(
    "doubling the oversampling divides the restitution error by 4 for the second-order "
    "schemes, by 2 for the explicit one and by at least 8 for the corrected discrete gradient",
    "[dsp]") {
  // k = 1e8, 10 g: 16.7 samples per contact; 4x the oversampling must cut the worst error by
  // 16 (second order) or 4 (first order), within the spread of the onset phases. The discrete
  // gradient's loss carries the step's covariance correction (contact.cpp, NormalForce), which
  // removes its leading error term: from x1 to x4 its error falls by more than 64 (third order or
  // better), until it reaches the rounding level.
  for (const auto& c : kSchemes) {
    const bool first_order = c.scheme == ContactScheme::kExplicitPassive;
    const bool corrected = c.scheme == ContactScheme::kDiscreteGradient;
    const int coarse = first_order ? 16 : corrected ? 1 : 4;
    const double e_coarse = WorstError(c.scheme, kMass, 1e8, 1.0, kAlpha, 1.0, coarse, 1);
    const double e_fine = WorstError(c.scheme, kMass, 1e8, 1.0, kAlpha, 1.0, 4 * coarse, 1);
    const double ratio = e_coarse / e_fine;
    INFO(c.name << " error at x" << coarse << " " << e_coarse << ", at x" << 4 * coarse << " "
                << e_fine);
    if (first_order) {
      CHECK(ratio > 3.5);
      CHECK(ratio < 4.5);
    } else if (corrected) {
      CHECK(ratio > 64.0);
    } else {
      CHECK(ratio > 13.0);
      CHECK(ratio < 19.0);
    }
  }
}

TEST_CASE(
    "no scheme ever returns more energy than it received: without dissipation the exit speed "
    "is at most the entry speed for k up to 1e12, alpha 1 to 4, probe 0.1 g to 1 kg, v up to "
    "10 m/s, one step per sample or automatic oversampling",
    "[dsp]") {
  for (const auto& c : kSchemes) {
    double worst_gain = -1.0;
    for (const double k : {1e6, 1e9, 1e12}) {
      for (const double alpha : {1.0, 1.5, 2.5, 4.0}) {
        for (const double mass : {1e-4, 1e-2, 1.0}) {
          for (const double v_in : {0.01, 1.0, 10.0}) {
            for (const int oversample : {1, 0}) {
              // Long, well-resolved contacts are covered at one step per sample; with the
              // oversampling (the explicit scheme always runs at the cap) they would only cost.
              ImpactParams params;
              params.scheme = c.scheme;
              params.stiffness = k;
              params.shape_alpha = alpha;
              params.oversample = oversample;
              const double sub_steps = RigidWallContactTime(mass, k, alpha, v_in) * kFs *
                                       ChooseContactOversample(params, mass, kFs);
              if (oversample == 0 && sub_steps > 2e4) continue;
              for (int p = 0; p < 32; p += 8 * kPhaseStride) {
                const auto run = SimulateRigidWallImpact(mass, k, 0.0, alpha, v_in, kFs, c.scheme,
                                                         oversample, (p + 0.5) / 32.0);
                INFO(c.name << " k " << k << " alpha " << alpha << " mass " << mass << " v " << v_in
                            << " oversample " << oversample << " phase " << p);
                REQUIRE(run.separated);
                // Passivity: e <= e_exact (1 + 1e-6); the discrete gradient's solve leaves
                // ~1e-9 of rounding in the most under-resolved cases.
                CHECK(run.exit_velocity_mps <= v_in * (1.0 + 1e-6));
                worst_gain = std::max(worst_gain, run.exit_velocity_mps / v_in - 1.0);
              }
            }
          }
        }
      }
    }
    UNSCOPED_INFO(c.name << ": largest exit/entry - 1 = " << worst_gain);
  }
}

TEST_CASE(
    "no scheme ever gains energy in a lossy impact: the exit speed never exceeds the entry "
    "speed for mu*v_in up to 10, k up to 1e12, alpha 1 to 4, probe 0.1 g to 1 kg, v up to "
    "10 m/s",
    "[dsp]") {
  for (const auto& c : kSchemes) {
    for (const double k : {1e6, 1e12}) {
      for (const double alpha : {1.0, 4.0}) {
        for (const double mass : {1e-4, 1.0}) {
          for (const double v_in : {0.1, 10.0}) {
            for (const double mu_v : {0.1, 1.0, 10.0}) {
              const int oversample = c.scheme == ContactScheme::kExplicitPassive ? 1 : 0;
              for (int p = 0; p < 32; p += 8 * kPhaseStride) {
                const auto run = SimulateRigidWallImpact(mass, k, mu_v / v_in, alpha, v_in, kFs,
                                                         c.scheme, oversample, (p + 0.5) / 32.0);
                INFO(c.name << " k " << k << " alpha " << alpha << " mass " << mass << " v " << v_in
                            << " mu*v " << mu_v << " phase " << p);
                REQUIRE(run.separated);
                // At most: an unresolved contact under the passivity guard can bounce without
                // loss (it never got to store energy), but never gains.
                CHECK(run.exit_velocity_mps <= v_in * (1.0 + 1e-6));
              }
            }
          }
        }
      }
    }
  }
}

TEST_CASE(
    "the discrete gradient and energy-quadratised schemes conserve energy without "
    "dissipation at one step per sample: exit speed within 1e-6 of the entry speed for a "
    "resolved contact",
    "[dsp]") {
  // k = 1e6, 10 g: ~100 samples per contact. The discrete gradient conserves V exactly; the
  // quadratised scheme conserves ψ²/2 exactly and only loses what ψ holds when the contact opens
  // (its drift from √(2V), second order).
  for (int p = 0; p < 32; p += kPhaseStride) {
    const double phase = (p + 0.5) / 32.0;
    const auto dg = SimulateRigidWallImpact(kMass, 1e6, 0.0, kAlpha, 1.0, kFs,
                                            ContactScheme::kDiscreteGradient, 1, phase);
    const auto ieq = SimulateRigidWallImpact(kMass, 1e6, 0.0, kAlpha, 1.0, kFs,
                                             ContactScheme::kEnergyQuadratised, 1, phase);
    INFO("phase " << phase);
    CHECK(std::fabs(dg.exit_velocity_mps - 1.0) <= 1e-9);
    CHECK(ieq.exit_velocity_mps <= 1.0 + 1e-12);
    CHECK(ieq.exit_velocity_mps >= 1.0 - 1e-6);
  }
}

TEST_CASE(
    "automatic oversampling gives every scheme its own target of contact sub-steps, more "
    "for the less accurate schemes, up to the cap",
    "[dsp]") {
  CHECK(TargetContactSamples(ContactScheme::kDiscreteGradient) <
        TargetContactSamples(ContactScheme::kEnergyQuadratised));
  CHECK(TargetContactSamples(ContactScheme::kEnergyQuadratised) <
        TargetContactSamples(ContactScheme::kExplicitPassive));
  for (const auto& c : kSchemes) {
    for (const double k : {1e5, 1e7, 1e9, 1e11}) {
      ImpactParams params;
      params.scheme = c.scheme;
      params.stiffness = k;
      params.oversample = 0;
      const int n = ChooseContactOversample(params, kMass, kFs);
      const double samples = RigidWallContactTime(kMass, k, 1.5, 1.0) * kFs;
      const double target = TargetContactSamples(c.scheme);
      INFO(c.name << " k " << k << " oversample " << n);
      CHECK(n >= 1);
      CHECK(n <= kMaxOversample);
      CHECK((n == kMaxOversample || samples * n >= target));
      CHECK((n == 1 || samples * (n - 1) < target));
    }
    // An explicit choice is taken as given: x1, x2, x4, x8, x16 and higher.
    for (const int n : {1, 2, 4, 8, 16, 64, 256}) {
      ImpactParams params;
      params.scheme = c.scheme;
      params.oversample = n;
      CHECK(ChooseContactOversample(params, kMass, kFs) == n);
    }
  }
}
