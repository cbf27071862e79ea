// Adaptive contact oversampling (ContactSubstepsForSpeed in synth/contact.h). With the
// automatic setting the kernel chooses the sub-steps of each compression from its impact speed:
// the accuracy rule (1e-4 relative restitution from 0.1 m/s, 1e-5 m/s absolute below) is checked
// against the Lambert-W closed form through the scene's own kernel (SimulateRigidWallImpact), and
// a pen resting or sliding on the surface is shown to run at one sub-step per sample while a tap
// gets more.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "synth/contact.h"
#include "synth/contact_kernel.h"
#include "synth/hunt_crossley_closed_form.h"
#include "synth/scene.h"
#include "synth_test_support.h"

using namespace sas::synth;

namespace {

constexpr double kFs = 48000.0;
#if defined(__SANITIZE_ADDRESS__)
constexpr int kPhaseStride = 8;  // ~10x slower under the sanitizer
#else
constexpr int kPhaseStride = 2;
#endif

struct Contact {
  const char* name;
  double mass_kg, k, alpha, mu;
};
// The metal plate's nib (textures/materials/metal.toml), and a soft and a stiff 10 g probe.
constexpr Contact kContacts[] = {
    {"metal nib 5 g k 1e8", 0.005, 1e8, 1.5, 0.15},
    {"10 g k 1e6", 0.01, 1e6, 1.5, 0.3},
    {"10 g k 1e10", 0.01, 1e10, 1.5, 0.3},
};

ImpactParams Automatic(const Contact& c) {
  ImpactParams p;
  p.enabled = true;
  p.scheme = kDefaultContactScheme;
  p.stiffness = c.k;
  p.shape_alpha = c.alpha;
  p.dissipation_s_per_m = c.mu;
  p.oversample = 0;
  return p;
}

// A 5 g nib (k = 1e8, the metal's) on a three-mode plate, with the metal's friction and the
// automatic oversampling.
MaterialParams NibOnPlate() {
  MaterialParams m;
  m.resonator.mode_count = 3;
  m.resonator.modes[0] = ModeParams{337.0, 1.2, 0.34, 0.5};
  m.resonator.modes[1] = ModeParams{683.0, 0.6, 0.54, 0.8};
  m.resonator.modes[2] = ModeParams{1004.0, 0.4, 1.1, -0.5};
  m.probe.mass_kg = 0.005;
  m.impact.enabled = true;
  m.impact.stiffness = 1e8;
  m.impact.shape_alpha = 1.5;
  m.impact.dissipation_s_per_m = 0.15;
  m.impact.oversample = 0;
  m.friction = test::MetalFriction();
  return m;
}

}  // namespace

TEST_CASE(
    "adaptive oversampling: the default scheme meets 1e-4 relative restitution error from 0.1 to "
    "3 m/s and 1e-5 m/s absolute below 0.1 m/s",
    "[dsp]") {
  for (const auto& c : kContacts) {
    for (const double v_in : {0.002, 0.01, 0.03, 0.1, 0.3, 1.0, 3.0}) {
      const double exact = HuntCrossleyImpact(c.mass_kg, c.k, c.mu, c.alpha, v_in).exit_speed_mps;
      double worst_abs = 0.0;
      int most_substeps = 0;
      for (int p = 0; p < 32; p += kPhaseStride) {
        const auto run = SimulateRigidWallImpact(c.mass_kg, c.k, c.mu, c.alpha, v_in, kFs,
                                                 kDefaultContactScheme, 0, (p + 0.5) / 32.0);
        REQUIRE(run.separated);
        worst_abs = std::max(worst_abs, std::fabs(run.exit_velocity_mps - exact));
        most_substeps = std::max(most_substeps, run.oversample);
      }
      INFO(c.name << " v " << v_in << " m/s: sub-steps " << most_substeps << ", exit error "
                  << worst_abs << " m/s (" << worst_abs / exact << " relative)");
      if (v_in >= kAbsoluteSpeedFloor) {
        CHECK(worst_abs <= kRestitutionTolerance * exact);
      } else {
        CHECK(worst_abs <= kRestitutionTolerance * kAbsoluteSpeedFloor);
      }
    }
  }
}

TEST_CASE(
    "adaptive oversampling: sub-steps grow with the impact speed, one for a gentle touch, the "
    "material's full count for a 3 m/s strike",
    "[dsp]") {
  for (const auto& c : kContacts) {
    INFO(c.name);
    const ImpactParams params = Automatic(c);
    const int full = ChooseContactOversample(params, c.mass_kg, kFs);
    int previous = 0;
    for (double v = 1e-4; v <= 3.0; v *= 1.25) {
      const int n = ContactSubstepsForSpeed(params, c.mass_kg, kFs, v);
      CHECK(n >= previous);
      previous = n;
    }
    CHECK(ContactSubstepsForSpeed(params, c.mass_kg, kFs, 1e-4) == 1);
    CHECK(ContactSubstepsForSpeed(params, c.mass_kg, kFs, 3.0) <= full);
    CHECK(ContactSubstepsForSpeed(params, c.mass_kg, kFs, 3.0) >= (full + 1) / 2);
    // The speed limits the levels are chosen by agree with the count.
    for (int n : {1, 2, 4, 8}) {
      const double v = MaxSpeedForSubsteps(params, c.mass_kg, kFs, n);
      if (v <= 0.0 || v >= 1e3) continue;
      CHECK(ContactSubstepsForSpeed(params, c.mass_kg, kFs, 0.99 * v) <= n);
      CHECK(ContactSubstepsForSpeed(params, c.mass_kg, kFs, 1.01 * v) > n);
    }
  }
}

TEST_CASE(
    "adaptive oversampling: a pen resting and sliding on a flat plate runs one sub-step per "
    "sample, a tap at 0.3 m/s runs more",
    "[dsp][render]") {
  MaterialParams m = NibOnPlate();
  Scene scene;
  scene.Init(kFs);
  scene.Prepare(m, OutputParams{}, HeightFieldView{});  // flat: no profile
  REQUIRE(scene.contact_oversample() > 1);              // the material's count (the ceiling)

  ProbeCommand tap;
  tap.tip_down = true;
  tap.landing_speed_mps = 0.3;
  tap.normal_force_n = 1.0;
  tap.velocity_mps = 0.0;
  std::vector<float> out(2);
  int most_during_landing = 0;
  scene.Process(&tap, 1, out.data(), 1);
  for (int n = 0; n < 480; ++n) {  // 10 ms: the landing bounces and settles
    scene.Process(nullptr, 0, out.data(), 1);
    most_during_landing = std::max(most_during_landing, scene.probe_state().substeps);
  }
  CHECK(most_during_landing > 1);

  // Settled under the push, then a slow slide (3 cm/s, like the kiosk's slow stroke).
  for (int n = 0; n < 48000; ++n) scene.Process(nullptr, 0, out.data(), 1);
  ProbeCommand slide = tap;
  slide.velocity_mps = 0.03;
  scene.Process(&slide, 1, out.data(), 1);
  int most_while_sliding = 0;
  long in_contact = 0;
  for (int n = 0; n < 24000; ++n) {
    scene.Process(nullptr, 0, out.data(), 1);
    const SceneProbeState s = scene.probe_state();
    if (s.compression_m > 0.0) ++in_contact;
    most_while_sliding = std::max(most_while_sliding, s.substeps);
  }
  CHECK(in_contact == 24000);  // the pen stays on the surface
  CHECK(most_while_sliding == 1);
}

TEST_CASE(
    "adaptive oversampling: a pen held on a ringing plate keeps at most the sustained contact's "
    "sub-steps, though the plate closes on it at a tap's speed",
    "[dsp]") {
  // The scene's kernel on its own: a 5 g nib (k = 1e8, the glass's) pressed at 3 N on one plate
  // mode (glass's lowest), settled, then the mode kicked so that it closes on the nib at 1.5 times
  // the speed the sustained count serves; the nib stays pressed throughout.
  ImpactParams params;
  params.enabled = true;
  params.scheme = kDefaultContactScheme;
  params.stiffness = 1e8;
  params.shape_alpha = 1.5;
  params.dissipation_s_per_m = 0.2;
  params.oversample = 0;
  ContactKernelConfig config;
  config.scheme = params.scheme;
  config.impact.Set(params);
  config.probe_mass_kg = 0.005;
  config.SetTiming(kFs, ChooseContactOversample(params, config.probe_mass_kg, kFs));
  REQUIRE(config.substeps > kSustainedContactSubsteps);
  ResonatorParams plate;
  plate.mode_count = 1;
  plate.modes[0] = ModeParams{3151.0, 0.337, 0.0322, 0.53};
  ModalState modes;
  modes.Prepare(plate, kFs, config.substeps, false, true);
  config.adaptive = true;
  config.SetLevels(params, modes, kFs);
  ProbeDynamics probe;
  probe.active = true;
  SampleDrive drive;
  drive.push_n = 3.0;
  drive.friction_share = 0.0;
  for (int n = 0; n < 4800; ++n) StepContactSample(config, modes, probe, drive);
  REQUIRE(probe.compression_m > 0.0);
  REQUIRE(probe.substeps_used == 1);

  const double kick =
      1.5 * MaxSpeedForSubsteps(params, config.probe_mass_kg, kFs, kSustainedContactSubsteps);
  REQUIRE(ContactSubstepsForSpeed(params, config.probe_mass_kg, kFs, kick) >
          kSustainedContactSubsteps);
  modes.v[0] += kick;                    // up: towards the nib
  AdvanceModes(modes, modes.full, 0.0);  // (refreshes the mode sums the kernel reads)
  int most = 0;
  double fastest = 0.0;
  bool pressed = true;
  for (int n = 0; n < 480; ++n) {
    const double closing = modes.ContactVelocity() - probe.velocity_mps;
    fastest = std::max(fastest, closing);
    StepContactSample(config, modes, probe, drive);
    pressed = pressed && probe.compression_m > 0.0 && probe.touched;
    most = std::max(most, probe.substeps_used);
  }
  CHECK(pressed);               // one sustained contact: the nib never leaves the plate
  CHECK(fastest > 0.5 * kick);  // the plate does close on it at a tap's speed
  CHECK(most > 1);
  CHECK(most <= kSustainedContactSubsteps);
}

TEST_CASE(
    "adaptive oversampling with the pressed floor: a pen dragged slowly over a plate gets the held "
    "count on every pressed sample while friction acts, and one sub-step when it rolls",
    "[dsp][render]") {
  MaterialParams m = NibOnPlate();
  m.impact.sustained_substeps = 8;
  // Counts of the sub-steps a settled pen sliding at 3 cm/s gets, for each sample in contact.
  auto slide = [&](bool floor, ProbeStyle style) {
    MaterialParams params = m;
    params.impact.pressed_floor = floor;
    Scene scene;
    scene.Init(kFs);
    scene.Prepare(params, OutputParams{}, HeightFieldView{});
    REQUIRE(scene.contact_oversample() >= 8);
    ProbeCommand down;
    down.tip_down = true;
    down.landing_speed_mps = 0.3;
    down.normal_force_n = 1.0;
    down.style = style;
    std::vector<float> out(2);
    scene.Process(&down, 1, out.data(), 1);
    for (int n = 0; n < 48000; ++n) scene.Process(nullptr, 0, out.data(), 1);
    ProbeCommand moving = down;
    moving.velocity_mps = 0.03;
    scene.Process(&moving, 1, out.data(), 1);
    std::vector<int> counts(16, 0);
    for (int n = 0; n < 12000; ++n) {
      scene.Process(nullptr, 0, out.data(), 1);
      const SceneProbeState s = scene.probe_state();
      REQUIRE(s.compression_m > 0.0);  // the pen stays on the surface
      ++counts[static_cast<std::size_t>(std::min(s.substeps, 15))];
    }
    return counts;
  };
  const auto capped = slide(false, ProbeStyle::kScrape);
  CHECK(capped[1] == 12000);  // a cap: the slowly closing contact keeps one
  const auto floored = slide(true, ProbeStyle::kScrape);
  CHECK(floored[8] == 12000);
  const auto rolled = slide(true, ProbeStyle::kRoll);  // no friction: the impact rule alone
  CHECK(rolled[1] == 12000);
}
