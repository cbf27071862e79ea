// The closed-form oracle itself is checked against values computed independently (high-resolution
// RK4 integration and the Lambert-W form of Papetti, Avanzini & Rocchesso, IEEE TASLP 19(7), 2011).
#include <catch2/catch.hpp>
#include <cmath>

#include "synth/hunt_crossley_closed_form.h"

using sas::synth::HuntCrossleyImpact;
using sas::synth::HuntCrossleyRestitution;

TEST_CASE("restitution matches the tabulated Lambert-W values for mu*v_in from 0.01 to 10",
          "[dsp]") {
  struct Row {
    double mu_v, e;
  };
  const Row table[] = {{0.01, 0.9933775}, {0.1, 0.9374756}, {0.3, 0.8328698}, {0.5, 0.7484349},
                       {1.0, 0.5936243},  {2.0, 0.4107197}, {5.0, 0.1969802}, {10.0, 0.0999816}};
  for (const auto& row : table) {
    INFO("mu*v_in = " << row.mu_v);
    CHECK(HuntCrossleyRestitution(row.mu_v) == Approx(row.e).margin(1e-7));
  }
}

TEST_CASE("restitution is 1 without dissipation and falls monotonically with mu*v_in", "[dsp]") {
  CHECK(HuntCrossleyRestitution(0.0) == 1.0);
  double previous = 1.0;
  for (double u = 1e-4; u < 100.0; u *= 1.3) {
    const double e = HuntCrossleyRestitution(u);
    INFO("mu*v_in = " << u);
    REQUIRE(e < previous);
    REQUIRE(e > 0.0);
    // |v_out| < 1/mu for every entry speed (beyond mu*v_in ~ 36 the gap is below double precision).
    if (u < 30.0) REQUIRE(e * u < 1.0);
    REQUIRE(e * u <= 1.0);
    previous = e;
  }
}

TEST_CASE("impact closed form reproduces the reference example rows (m = 10 g, alpha = 1.5)",
          "[dsp]") {
  struct Row {
    double k, mu, e, x_max, t_c;
  };
  const Row rows[] = {{1e6, 0.5, 0.748434931597, 6.169314e-4, 2.106292e-3},
                      {1e8, 2.0, 0.410719686061, 7.949076e-5, 3.780250e-4},
                      {1e10, 0.1, 0.937475579950, 1.689034e-5, 5.135281e-5}};
  for (const auto& row : rows) {
    INFO("k = " << row.k << ", mu = " << row.mu);
    const auto impact = HuntCrossleyImpact(0.01, row.k, row.mu, 1.5, 1.0);
    CHECK(impact.restitution == Approx(row.e).epsilon(1e-10));
    CHECK(impact.exit_speed_mps == Approx(row.e).epsilon(1e-10));
    CHECK(impact.max_compression_m == Approx(row.x_max).epsilon(1e-6));
    // The table's contact times were checked against RK4 to 1.5e-6.
    CHECK(impact.contact_time_s == Approx(row.t_c).epsilon(3e-6));
  }
}

TEST_CASE("elastic contact time matches the tabulated Gamma-function factors for alpha 1 to 3",
          "[dsp]") {
  // t_c = factor · x_max / v_in with factor = 2√π Γ(1 + 1/(α+1)) / Γ(½ + 1/(α+1)).
  struct Row {
    double alpha, factor;
  };
  const Row rows[] = {
      {1.0, 3.14159265}, {1.5, 2.94328}, {1.7, 2.88225}, {2.0, 2.80436}, {3.0, 2.62206}};
  for (const auto& row : rows) {
    const double x_max = sas::synth::HuntCrossleyMaxCompression(0.01, 1e7, 0.0, row.alpha, 1.0);
    INFO("alpha = " << row.alpha);
    CHECK(sas::synth::HuntCrossleyContactTime(0.01, 1e7, 0.0, row.alpha, 1.0) ==
          Approx(row.factor * x_max).epsilon(2e-6));
  }
}

TEST_CASE("dissipative contact time tends to the elastic one as mu goes to zero", "[dsp]") {
  const double elastic = sas::synth::HuntCrossleyContactTime(0.01, 1e7, 0.0, 1.5, 1.0);
  const double nearly = sas::synth::HuntCrossleyContactTime(0.01, 1e7, 1e-6, 1.5, 1.0);
  CHECK(nearly == Approx(elastic).epsilon(1e-5));
  // For alpha = 1 without loss the contact is half a period of the spring-mass oscillator.
  const double half_period = std::acos(-1.0) * std::sqrt(0.01 / 1e7);
  CHECK(sas::synth::HuntCrossleyContactTime(0.01, 1e7, 0.0, 1.0, 1.0) ==
        Approx(half_period).epsilon(1e-9));
}
