// A probe hitting a rigid, immovable body through the engine's own
// contact kernel (SimulateRigidWallImpact runs StepContactSample, the code Scene::Process runs)
// against the Hunt–Crossley closed forms (HuntCrossleyImpact, itself
// checked against tabulated Lambert-W values in test_hunt_crossley_closed_form.cpp).
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "synth/contact.h"
#include "synth/hunt_crossley_closed_form.h"

using namespace sas::synth;

namespace {
constexpr int kPhases = 32;
constexpr double kMass = 0.01, kAlpha = 1.5, kFs = 48000.0;
}  // namespace

TEST_CASE(
    "exit velocity matches the Lambert-W closed form within 1e-4 and max compression "
    "within 1e-3 at every one of 32 onset phases (48 kHz, 10 g, alpha 1.5, k 1e6..1e8, "
    "mu*v_in 0.1..2)",
    "[dsp]") {
  double worst_e = 0.0, worst_x = 0.0;
  for (const double k : {1e6, 1e7, 1e8}) {
    for (const double v_in : {0.5, 1.0}) {
      for (const double mu_v : {0.1, 0.5, 1.0, 2.0}) {
        const double mu = mu_v / v_in;
        const auto exact = HuntCrossleyImpact(kMass, k, mu, kAlpha, v_in);
        double worst_case_e = 0.0;
        for (int p = 0; p < kPhases; ++p) {
          const double phase = (p + 0.5) / kPhases;
          const auto run = SimulateRigidWallImpact(kMass, k, mu, kAlpha, v_in, kFs,
                                                   ContactScheme::kDiscreteGradient, 0, phase);
          REQUIRE(run.separated);
          const double e_err = std::fabs(run.exit_velocity_mps / exact.exit_speed_mps - 1.0);
          const double x_err = std::fabs(run.max_compression_m / exact.max_compression_m - 1.0);
          INFO("k " << k << " v_in " << v_in << " mu*v " << mu_v << " phase " << phase
                    << " oversample " << run.oversample << " N_c " << run.samples_per_contact);
          CHECK(e_err <= 1e-4);
          CHECK(x_err <= 1e-3);
          worst_case_e = std::max(worst_case_e, e_err);
          worst_e = std::max(worst_e, e_err);
          worst_x = std::max(worst_x, x_err);
        }
        UNSCOPED_INFO("k " << k << " v_in " << v_in << " mu*v " << mu_v << " worst e error "
                           << worst_case_e);
      }
    }
  }
  WARN("worst restitution error " << worst_e << ", worst max-compression error " << worst_x);
}

TEST_CASE(
    "without dissipation the exit speed equals the entry speed within 1e-6 for any "
    "stiffness up to 1e12, without oversampling, at every onset phase",
    "[dsp]") {
  for (const double k : {1e6, 1e8, 1e10, 1e12}) {
    for (const double alpha : {1.0, 1.5, 3.0}) {
      for (const int oversample : {1, 0}) {
        for (int p = 0; p < kPhases; p += 3) {
          const double phase = (p + 0.5) / kPhases;
          const auto run = SimulateRigidWallImpact(
              kMass, k, 0.0, alpha, 1.0, kFs, ContactScheme::kDiscreteGradient, oversample, phase);
          INFO("k " << k << " alpha " << alpha << " oversample " << oversample << " phase "
                    << phase);
          REQUIRE(run.separated);
          CHECK(std::fabs(run.exit_velocity_mps - 1.0) <= 1e-6);
        }
      }
    }
  }
}

TEST_CASE("an under-resolved stiff impact (k 1e12, one step per sample) never gains energy",
          "[dsp]") {
  for (const double mu_v : {0.0, 0.1, 1.0, 10.0}) {
    for (int p = 0; p < kPhases; ++p) {
      const auto run =
          SimulateRigidWallImpact(1e-4, 1e12, mu_v, 2.0, 1.0, 44100.0,
                                  ContactScheme::kDiscreteGradient, 1, (p + 0.5) / kPhases);
      INFO("mu*v " << mu_v << " phase " << p);
      REQUIRE(run.separated);
      CHECK(run.exit_velocity_mps <= 1.0 * (1.0 + 1e-12));
    }
  }
}

TEST_CASE("contact time without dissipation matches the Gamma-function closed form", "[dsp]") {
  // t_c = 2 (x_max / v_in) √π Γ(1 + 1/(α+1)) / Γ(1/2 + 1/(α+1)); factor 2.94328 for α = 1.5.
  const double k = 1e7, v_in = 1.0;
  const double x_max = std::pow((kAlpha + 1.0) * kMass * v_in * v_in / (2.0 * k), 1.0 / 2.5);
  const double expected = x_max / v_in * 2.94328;
  // The trajectory (hence the contact time) converges at second order: 1e-4 at x4 (155 sub-steps
  // per contact). The automatic choice is set by the restitution target, which the discrete
  // gradient's corrected loss meets with fewer sub-steps (39 here): its contact time is within 1e-3.
  const auto run = SimulateRigidWallImpact(kMass, k, 0.0, kAlpha, v_in, kFs,
                                           ContactScheme::kDiscreteGradient, 4, 0.37);
  CHECK(run.contact_time_s == Approx(expected).epsilon(1e-4));
  CHECK(run.samples_per_contact == Approx(expected * kFs).epsilon(1e-4));
  const auto automatic = SimulateRigidWallImpact(kMass, k, 0.0, kAlpha, v_in, kFs,
                                                 ContactScheme::kDiscreteGradient, 0, 0.37);
  CHECK(automatic.contact_time_s == Approx(expected).epsilon(1e-3));
}

TEST_CASE(
    "automatic oversampling gives every default-range impact at least the target number "
    "of contact sub-steps",
    "[dsp]") {
  for (const double k : {1e5, 1e6, 1e7, 1e8, 1e9}) {
    ImpactParams params;
    params.stiffness = k;
    params.oversample = 0;
    const int n = ChooseContactOversample(params, kMass, kFs);
    const double t_c = RigidWallContactTime(kMass, k, 1.5, 1.0);
    INFO("k " << k << " oversample " << n);
    CHECK(n >= 1);
    CHECK(t_c * kFs * n >= kTargetContactSamples);
    CHECK((n == 1 || t_c * kFs * (n - 1) < kTargetContactSamples));
  }
}

TEST_CASE(
    "contact time with dissipation matches the quadrature closed form within 1e-3 at 60 "
    "sub-steps per contact and within 2e-3 at the automatic choice",
    "[dsp]") {
  // Second order in the sub-steps (see the Gamma-function case above).
  for (const double k : {1e6, 1e7, 1e8}) {
    for (const double mu_v : {0.1, 1.0, 2.0}) {
      const double expected = HuntCrossleyContactTime(kMass, k, mu_v, kAlpha, 1.0);
      const int oversample = static_cast<int>(std::ceil(60.0 / (expected * kFs)));
      for (const double phase : {0.05, 0.5, 0.95}) {
        const auto run = SimulateRigidWallImpact(kMass, k, mu_v, kAlpha, 1.0, kFs,
                                                 ContactScheme::kDiscreteGradient, oversample,
                                                 phase);
        const auto automatic = SimulateRigidWallImpact(kMass, k, mu_v, kAlpha, 1.0, kFs,
                                                       ContactScheme::kDiscreteGradient, 0, phase);
        INFO("k " << k << " mu*v " << mu_v << " phase " << phase);
        CHECK(run.contact_time_s == Approx(expected).epsilon(1e-3));
        CHECK(automatic.contact_time_s == Approx(expected).epsilon(2e-3));
      }
    }
  }
}

TEST_CASE(
    "at k 1e10 and 1e12 (fewer than 3 samples per contact at "
    "48 kHz) the default configuration meets 1e-3 restitution error and never gains energy",
    "[dsp]") {
  const ImpactParams defaults;  // the default scheme with automatic oversampling
  REQUIRE(defaults.scheme == kDefaultContactScheme);
  REQUIRE(defaults.oversample == 0);
  for (const double k : {1e10, 1e12}) {
    for (const double mu_v : {0.0, 0.1, 1.0}) {
      const auto exact = HuntCrossleyImpact(kMass, k, mu_v, kAlpha, 1.0);
      REQUIRE(exact.contact_time_s * kFs < 3.0);
      double worst = 0.0;
      for (int p = 0; p < kPhases; ++p) {
        const auto run = SimulateRigidWallImpact(kMass, k, mu_v, kAlpha, 1.0, kFs, defaults.scheme,
                                                 defaults.oversample, (p + 0.5) / kPhases);
        INFO("k " << k << " mu*v " << mu_v << " phase " << p << " oversample " << run.oversample);
        REQUIRE(run.separated);
        const double error = std::fabs(run.exit_velocity_mps / exact.exit_speed_mps - 1.0);
        CHECK(error <= 1e-3);
        CHECK(run.exit_velocity_mps <= 1.0 * (1.0 + 1e-9));
        worst = std::max(worst, error);
      }
      UNSCOPED_INFO("k " << k << " mu*v " << mu_v << " worst restitution error " << worst);
    }
  }
}

TEST_CASE("the contact's binomial power series agrees with pow to rounding over its reach",
          "[dsp]") {
  for (const double alpha : {1.1, 1.2, 1.3, 2.5, 3.0}) {
    ImpactParams params;
    params.shape_alpha = alpha;
    ImpactModel m;
    m.Set(params);
    REQUIRE(m.has_pow_series);
    // 1 + δ exact in double (δ a multiple of 2^-20), so pow sees the same number.
    for (int i = -8192; i <= 8192; ++i) {
      const double delta = i * 0x1p-20;
      INFO("alpha " << alpha << " delta " << delta);
      CHECK(std::fabs(m.PowRatio(delta) / std::pow(1.0 + delta, alpha) - 1.0) <= 0x1p-51);
    }
  }
  ImpactParams fast;  // α = 1.5 keeps its sqrt
  ImpactModel m;
  m.Set(fast);
  CHECK_FALSE(m.has_pow_series);
}

TEST_CASE(
    "with alpha 1.2 (powers from the series) exit velocity matches the closed form within 1e-4",
    "[dsp]") {
  constexpr double kShape = 1.2;
  for (const double k : {5e3, 1e6}) {
    for (const double mu_v : {0.1, 1.0}) {
      const auto exact = HuntCrossleyImpact(kMass, k, mu_v, kShape, 1.0);
      for (int p = 0; p < kPhases; p += 4) {
        const auto run =
            SimulateRigidWallImpact(kMass, k, mu_v, kShape, 1.0, kFs,
                                    ContactScheme::kDiscreteGradient, 0, (p + 0.5) / kPhases);
        INFO("k " << k << " mu*v " << mu_v << " phase " << p);
        REQUIRE(run.separated);
        CHECK(std::fabs(run.exit_velocity_mps / exact.exit_speed_mps - 1.0) <= 1e-4);
      }
    }
  }
}
