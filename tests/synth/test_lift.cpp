// Lifting the pen: a hand cannot take the tip's load away in one sample, so a pen lifted in one
// step (a pen-up report, pressure straight to 0) must not make the surface pop louder than the
// stroke it ends. Checked on a soft, springy material (bubble wrap's modes and contact, the one
// that deflects most under the pen) and on a stiff one (glass, where a light roll ends with a
// click when the load goes at once), over a bumpy relief that a firm pen feels
// whole and a lifted one would feel only at its peaks.

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "synth_test_support.h"

namespace sas::synth {
namespace {

// The shipped bubble wrap's resonator and contact (textures/materials/bubble_wrap.toml): seven
// light, damped modes 180 Hz - 2.9 kHz and a soft contact (k = 5e3 N/m^1.2).
MaterialParams SoftSheet() {
  MaterialParams m;
  const double f[] = {180, 410, 690, 1050, 1480, 2100, 2900};
  const double tau[] = {0.0221, 0.0097, 0.00577, 0.00379, 0.00269, 0.00189, 0.00137};
  const double mass[] = {0.006, 0.004, 0.004, 0.003, 0.003, 0.002, 0.002};
  const double gain[] = {0.8, -0.7, 0.6, -0.5, 0.45, -0.35, 0.3};
  m.resonator.mode_count = 7;
  for (std::size_t i = 0; i < 7; ++i) {
    m.resonator.modes[i] = ModeParams{f[i], tau[i], mass[i], gain[i]};
  }
  m.probe.mass_kg = 0.005;
  m.impact.stiffness = 5e3;
  m.impact.dissipation_s_per_m = 3.0;
  m.impact.shape_alpha = 1.2;
  m.friction.bristle_stiffness = 2e3;
  m.friction.bristle_damping = 4.5;
  m.friction.viscous_friction = 1.0;
  m.friction.noise_coefficient = 0.3;
  m.friction.static_coefficient = 0.45;
  m.friction.dynamic_coefficient = 0.3;
  m.friction.stribeck_velocity_mps = 0.08;
  m.friction.breakaway_ratio = 0.4;
  return m;
}

// The shipped glass tile (textures/materials/glass.toml): eight stiff modes 3.2 - 21.6 kHz, a hard
// contact, and a friction that squeaks when slow.
MaterialParams GlassTile() {
  MaterialParams m;
  const double f[] = {3151, 6841, 8916, 12606, 12990, 18525, 18755, 21599};
  const double tau[] = {0.02719, 0.03699, 0.03596, 0.03298, 0.03266, 0.02837, 0.02821, 0.02634};
  const double mass[] = {0.03219, 0.05102, 0.1034, 0.1639, 0.2363, 0.06787, 0.7589, 0.02722};
  const double gain[] = {0.53, 0.83, -0.54, -0.85, 0.79, 0.02, -0.80, 0.41};
  m.resonator.mode_count = 8;
  for (std::size_t i = 0; i < 8; ++i) {
    m.resonator.modes[i] = ModeParams{f[i], tau[i], mass[i], gain[i]};
  }
  m.probe.mass_kg = 0.005;
  m.probe.ball_radius_m = 0.001;
  m.impact.stiffness = 1e8;
  m.impact.dissipation_s_per_m = 0.2;
  m.friction.bristle_stiffness = 2e5;
  m.friction.bristle_damping = 2.0;
  m.friction.viscous_friction = 0.4;
  m.friction.noise_coefficient = 0.2;
  m.friction.static_coefficient = 0.47;
  m.friction.dynamic_coefficient = 0.2;
  m.friction.stribeck_velocity_mps = 0.05;
  m.friction.breakaway_ratio = 0.7;
  return m;
}

// Bumps 0.3 mm high, 2 mm apart, on a 0.1 mm grid.
std::vector<float> Bumps(int w, int h) {
  std::vector<float> heights(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      heights[static_cast<std::size_t>(y * w + x)] = static_cast<float>(
          0.15e-3 * (1.0 + std::sin(2.0 * 3.14159265358979 * x / 20.0) *
                               std::sin(2.0 * 3.14159265358979 * y / 20.0)));
    }
  }
  return heights;
}

struct LiftPeaks {
  double stroke = 0.0;  // max |ch 1| while the pen moves on the surface (landing included)
  double lift = 0.0;    // max |ch 1| from the lift on
};

LiftPeaks StrokeThenLift(const MaterialParams& material, double pressure, ProbeStyle style) {
  constexpr double fs = 48000.0;
  constexpr int w = 400, h = 400;
  test::OwnedField field(w, h, 1e-4, Bumps(w, h));
  Scene scene;
  scene.Init(fs);
  scene.Prepare(material, OutputParams{}, field.view);

  ProbeCommand down;
  down.tip_down = true;
  down.x_m = 0.01;
  down.y_m = 0.013;
  down.velocity_mps = 0.1;
  down.normal_force_n = 2.0 * pressure;
  down.penetration_m = 0.3e-3 * pressure;
  down.width_mm = style == ProbeStyle::kRub ? 4.0 : 0.3;
  down.style = style;
  down.landing_speed_mps = 0.005;
  const long lift_frame = static_cast<long>(0.3 * fs);
  ProbeCommand up = down;  // a pen-up report: pressure 0, nothing felt, not moving
  up.tip_down = false;
  up.velocity_mps = 0.0;
  up.normal_force_n = 0.0;
  up.penetration_m = 0.0;
  up.x_m = down.x_m + 0.1 * 0.3;
  const long total = lift_frame + static_cast<long>(0.3 * fs);
  const std::vector<float> out =
      test::RenderTimed(scene, {{0, down}, {lift_frame, up}}, total, 256);
  LiftPeaks peaks;
  for (long n = 0; n < total; ++n) {
    const double a = std::abs(out[2 * static_cast<std::size_t>(n)]);
    double& peak = n < lift_frame ? peaks.stroke : peaks.lift;
    peak = std::max(peak, a);
  }
  return peaks;
}

TEST_CASE("lift: a pen lifted in one step makes no sound louder than the stroke it ends") {
  for (const ProbeStyle style : {ProbeStyle::kScrape, ProbeStyle::kRub, ProbeStyle::kRoll}) {
    for (const double pressure : {0.2, 0.5, 0.9}) {
      for (const bool soft : {true, false}) {
        const MaterialParams material = soft ? SoftSheet() : GlassTile();
        const LiftPeaks peaks = StrokeThenLift(material, pressure, style);
        CAPTURE(ProbeStyleName(style));
        CAPTURE(pressure);
        CAPTURE(soft);
        CAPTURE(20.0 * std::log10(peaks.stroke));
        CAPTURE(20.0 * std::log10(peaks.lift));
        REQUIRE(peaks.stroke > 1e-6);  // the stroke sounds
        CHECK(peaks.lift <= peaks.stroke);
      }
    }
  }
}

}  // namespace
}  // namespace sas::synth
