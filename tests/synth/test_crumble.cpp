// The crumbling crust (synth/crumble.h): grains break at the rate the distance and the load say
// (Poisson in distance, Weibull in load), flakes come in the sizes of the fragmentation power law,
// and in the scene a crumbling stroke is broadband where the same stroke without it is not, while
// the idle skip still matches the full computation.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "support/fft.h"
#include "synth/crumble.h"
#include "synth/scene.h"
#include "synth_test_support.h"

using namespace sas::synth;

namespace {

constexpr double kFs = 48000.0;

CrumbleParams Crust() {
  CrumbleParams p;
  p.enabled = true;
  p.grain_spacing_m = 1e-3;
  p.strength_n = 0.5;
  p.weibull_modulus = 3.0;
  p.flake_low_hz = 2000.0;
  p.flake_high_hz = 12000.0;
  p.size_exponent = 2.5;
  p.flake_mass_kg = 3e-3;
  p.flake_speed_ratio = 0.2;
  p.flake_loss_factor = 0.15;
  p.flake_gain = 0.2;
  return p;
}

// Slides `metres` in steps of 1 µm under `load_n`; returns the impulses of the grains that broke.
std::vector<double> Slide(CrumbleSource& crumble, double metres, double load_n) {
  std::vector<double> impulses;
  const auto steps = static_cast<long>(metres / 1e-6);
  for (long i = 0; i < steps; ++i) {
    const double impulse = crumble.Slide(1e-6, load_n);
    if (impulse > 0.0) impulses.push_back(impulse);
    crumble.Ring();
  }
  return impulses;
}

// A firm upright pen (1 N, a 0.3 mm point) on the flat test field, moving at `velocity_mps`.
ProbeCommand FirmPen(double velocity_mps) {
  ProbeCommand c;
  c.tip_down = true;
  c.x_m = 0.01;
  c.y_m = 0.0006;
  c.normal_force_n = 1.0;
  c.width_mm = 0.3;
  c.velocity_mps = velocity_mps;
  return c;
}

}  // namespace

TEST_CASE("grains break once per grain spacing under a firm load, as a Poisson process") {
  CrumbleSource crumble;
  crumble.Prepare(Crust(), kFs);
  // 10 N against a 0.5 N strength: every grain breaks; 1 m / 1 mm = 1000 expected (σ ≈ 32).
  const auto impulses = Slide(crumble, 1.0, 10.0);
  CHECK(std::fabs(static_cast<double>(impulses.size()) - 1000.0) < 4.0 * std::sqrt(1000.0));
  CHECK(crumble.events() == impulses.size());
}

TEST_CASE("the load breaks grains as a Weibull distribution of strengths says") {
  CrumbleSource crumble;
  crumble.Prepare(Crust(), kFs);
  // At the scale strength 1 - 1/e of the grains break: 632 of 1000 (σ ≈ 25).
  CHECK(crumble.BreakProbability(0.5) == Approx(1.0 - std::exp(-1.0)));
  const auto at_scale = Slide(crumble, 1.0, 0.5);
  CHECK(std::fabs(static_cast<double>(at_scale.size()) - 632.1) < 4.0 * 25.0);
  // A fifth of it: 1 - e^(-0.008) = 0.8 % of 1000, about 8.
  crumble.Reset();
  const auto light = Slide(crumble, 1.0, 0.1);
  CHECK(light.size() < 25);
  // No load, no motion: nothing breaks.
  crumble.Reset();
  CHECK(Slide(crumble, 0.1, 0.0).empty());
  CHECK(crumble.Slide(0.0, 10.0) == 0.0);
}

TEST_CASE("flakes come in the fragmentation power law's sizes, and a disabled crust never breaks") {
  CrumbleSource crumble;
  const CrumbleParams p = Crust();
  crumble.Prepare(p, kFs);
  const auto impulses = Slide(crumble, 3.0, 10.0);
  REQUIRE(impulses.size() > 2500);
  // Impulse = flake mass · launch speed (0.2 of 1 µm per sample), mass ∝ size²:
  // size / largest = sqrt(J / (M v)).
  const double floor = std::sqrt(p.flake_low_hz / p.flake_high_hz);
  const double middle = std::sqrt(floor);  // the geometric middle of the size range
  int small = 0;
  for (const double j : impulses) {
    const double size = std::sqrt(j / (p.flake_mass_kg * p.flake_speed_ratio * 1e-6 * kFs));
    CHECK(size >= floor - 1e-12);
    CHECK(size <= 1.0 + 1e-12);
    if (size < middle) ++small;
  }
  // N(> a) ∝ a^-2.5 truncated to [floor, 1]: P(a < middle) = (1 - (floor/middle)^D) / (1 -
  // floor^D).
  const double expected =
      (1.0 - std::pow(floor / middle, p.size_exponent)) / (1.0 - std::pow(floor, p.size_exponent));
  const double share = static_cast<double>(small) / static_cast<double>(impulses.size());
  CHECK(share == Approx(expected).margin(0.03));

  CrumbleParams off = p;
  off.enabled = false;
  CrumbleSource none;
  none.Prepare(off, kFs);
  CHECK(Slide(none, 1.0, 10.0).empty());
  CHECK(none.Ring() == 0.0);
}

TEST_CASE("a flake rings out within milliseconds, and silencing it keeps the grains to come") {
  CrumbleSource a, b;
  a.Prepare(Crust(), kFs);
  b.Prepare(Crust(), kFs);
  double impulse = 0.0;
  while (impulse == 0.0) {
    impulse = a.Slide(1e-5, 10.0);
    REQUIRE(b.Slide(1e-5, 10.0) == impulse);
  }
  CHECK(a.Ring() != 0.0);  // heard on the sample it broke
  b.Ring();
  for (int i = 0; i < static_cast<int>(0.05 * kFs); ++i) a.Ring();
  CHECK(a.AmplitudeBound() == 0.0);  // 2 kHz at η 0.15: τ ≈ 1 ms, 50 ms is 50 τ
  CHECK(a.Ring() == 0.0);
  b.Silence();
  CHECK(b.AmplitudeBound() == 0.0);
  for (int i = 0; i < 20000; ++i) REQUIRE(a.Slide(1e-5, 10.0) == b.Slide(1e-5, 10.0));
}

TEST_CASE("a crumbling stroke is broadband, the same stroke without the crust is not",
          "[dsp][render]") {
  test::OwnedField field(4000, 8, 0.153e-3, std::vector<float>(4000 * 8, 0.0f));
  const auto high_share = [&](bool crumbling) {
    MaterialParams m = test::WoodLikeBoard();
    m.friction.noise_coefficient = 0.0;  // the crust's breaks alone, not the friction's noise
    m.crumble = Crust();
    m.crumble.enabled = crumbling;
    Scene scene;
    scene.Init(kFs);
    scene.Prepare(m, OutputParams{}, field.view);
    ProbeCommand down = FirmPen(0.0);
    down.landing_speed_mps = 0.005;
    ProbeCommand move = down;
    move.velocity_mps = 0.1;
    const long settle = static_cast<long>(0.2 * kFs);
    const std::size_t n = 1u << 15;
    const auto out =
        test::RenderTimed(scene, {{0, down}, {settle, move}}, settle + static_cast<long>(n), 256);
    std::vector<double> re(n), im(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) re[i] = out[2 * (static_cast<std::size_t>(settle) + i)];
    sas::test::FftInPlace(re, im);
    double high = 0.0, total = 0.0;
    for (std::size_t k = 1; k < n / 2; ++k) {
      const double p = re[k] * re[k] + im[k] * im[k];
      total += p;
      if (static_cast<double>(k) * kFs / static_cast<double>(n) > 5000.0) high += p;
    }
    return high / total;
  };
  const double plain = high_share(false);
  const double crumbling = high_share(true);
  INFO("power above 5 kHz: " << plain << " without, " << crumbling << " with the crust");
  CHECK(crumbling > 10.0 * plain);
}

TEST_CASE("idle skip with a crumbling crust: zeros after the lift match the full computation",
          "[dsp][render]") {
  test::OwnedField field(4000, 8, 0.153e-3, std::vector<float>(4000 * 8, 0.0f));
  MaterialParams m = test::WoodLikeBoard();
  m.crumble = Crust();
  const ProbeCommand down = FirmPen(0.2);
  ProbeCommand lift = down;
  lift.tip_down = false;
  const long total = static_cast<long>(5.0 * kFs);
  const auto render = [&](bool skip) {
    Scene scene;
    scene.Init(kFs);
    SceneSkips skips;
    skips.idle_blocks = skip;
    scene.SetSkips(skips);
    scene.Prepare(m, OutputParams{}, field.view);
    auto out =
        test::RenderTimed(scene, {{0, down}, {static_cast<long>(0.3 * kFs), lift}}, total, 128);
    CHECK(scene.IsIdle());
    return out;
  };
  const auto skipped = render(true);
  const auto full = render(false);
  double worst = 0.0;
  for (std::size_t i = 0; i < full.size(); ++i) {
    worst = std::max(worst, std::fabs(static_cast<double>(skipped[i]) - full[i]));
  }
  CHECK(worst <= 1e-7);
}
