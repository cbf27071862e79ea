// Acceptance 3 of issue 3: with the probe resting on a lossy resonator and no further input, the
// total mechanical energy (resonator + probe + contact potential + bristle + potential of the
// constant push) never increases from one sample to the next. This is what the discrete-gradient
// contact guarantees by construction (contact.h); the test checks it sample by sample.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "synth/scene.h"

using namespace sas::synth;

namespace {

MaterialParams LossyPlate(int modes) {
  MaterialParams m;
  m.resonator.mode_count = modes;
  for (int i = 0; i < modes; ++i) {
    auto& mode = m.resonator.modes[static_cast<std::size_t>(i)];
    mode.frequency_hz = 180.0 * (i + 1) * (1.0 + 0.13 * i);
    mode.decay_s = 0.8 / (1.0 + 0.5 * i);
    mode.mass_kg = 0.02 * (1.0 + 0.3 * i);
    mode.gain = 1.0 / (1.0 + i);
  }
  m.friction.noise_coefficient = 0.0;  // the noise term is an input, not part of the passive model
  return m;
}

struct EnergyRun {
  double worst_rise = 0.0;  // largest per-sample increase relative to the injected energy
  double start = 0.0, end = 0.0;
  double max_bristle = 0.0;
};

// Lands the probe (tip down, no sliding) and then renders `seconds` with no command at all.
EnergyRun RunUnforced(const MaterialParams& m, double fs, double seconds, double push_n,
                      double landing_mps) {
  Scene scene;
  scene.Init(fs);
  scene.Prepare(m, OutputParams{}, HeightFieldView{});
  ProbeCommand land;
  land.tip_down = true;
  land.normal_force_n = push_n;
  land.landing_speed_mps = landing_mps;
  land.velocity_mps = 0.0;
  land.style = ProbeStyle::kRub;
  float frame[2];
  scene.Process(&land, 1, frame, 1);
  const double injected = 0.5 * m.probe.mass_kg * landing_mps * landing_mps;
  EnergyRun run;
  run.start = scene.TotalEnergy();
  double previous = run.start;
  const long samples = static_cast<long>(seconds * fs);
  for (long n = 0; n < samples; ++n) {
    scene.Process(nullptr, 0, frame, 1);
    const double e = scene.TotalEnergy();
    run.worst_rise = std::max(run.worst_rise, (e - previous) / injected);
    run.max_bristle = std::max(run.max_bristle, std::fabs(scene.probe_state().bristle_m));
    previous = e;
  }
  run.end = previous;
  return run;
}

}  // namespace

TEST_CASE("probe resting on a lossy resonator: total energy never increases over 10 s (impact)",
          "[dsp]") {
  MaterialParams m = LossyPlate(8);
  m.friction.enabled = false;
  const EnergyRun run = RunUnforced(m, 48000.0, 10.0, 0.5, 0.5);
  WARN("largest per-sample energy rise / injected energy: " << run.worst_rise);
  CHECK(run.worst_rise <= 1e-9);
  CHECK(run.end < run.start);
}

TEST_CASE(
    "probe resting on a lossy resonator: total energy never increases over 10 s (impact "
    "and friction)",
    "[dsp]") {
  MaterialParams m = LossyPlate(8);
  m.friction.enabled = true;
  const EnergyRun run = RunUnforced(m, 48000.0, 10.0, 0.5, 0.5);
  CHECK(run.max_bristle > 0.0);  // the friction did act
  WARN("largest per-sample energy rise / injected energy: " << run.worst_rise);
  CHECK(run.worst_rise <= 1e-9);
  CHECK(run.end < run.start);
}

TEST_CASE("energy never increases for random stiff, light, lossy and lossless contacts", "[dsp]") {
  std::mt19937_64 rng(20261122);
  auto log_uniform = [&](double lo, double hi) {
    return std::exp(std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(rng));
  };
  double worst = 0.0;
  for (int set = 0; set < 24; ++set) {
    MaterialParams m = LossyPlate(1 + set % 6);
    for (int i = 0; i < m.resonator.mode_count; ++i) {
      auto& mode = m.resonator.modes[static_cast<std::size_t>(i)];
      mode.mass_kg = log_uniform(1e-4, 1.0);
      mode.decay_s = log_uniform(1e-3, 10.0);
      mode.frequency_hz = log_uniform(50.0, 20000.0);
    }
    m.impact.stiffness = log_uniform(1e3, 1e12);
    m.impact.shape_alpha = std::uniform_real_distribution<double>(1.0, 4.0)(rng);
    m.impact.dissipation_s_per_m = set % 4 == 0 ? 0.0 : log_uniform(1e-3, 10.0);
    m.impact.oversample = set % 3 == 0 ? 1 : 0;  // include unresolved contacts
    m.probe.mass_kg = log_uniform(1e-4, 1.0);
    m.friction.enabled = set % 2 == 1;
    m.friction.bristle_stiffness = log_uniform(1e2, 1e7);
    m.friction.bristle_damping = log_uniform(1e-2, 1e2);
    const double push = log_uniform(1e-3, 5.0);
    const double landing = log_uniform(1e-3, 10.0);
    INFO("set " << set << " k " << m.impact.stiffness << " alpha " << m.impact.shape_alpha << " mu "
                << m.impact.dissipation_s_per_m << " probe " << m.probe.mass_kg << " sigma0 "
                << m.friction.bristle_stiffness);
    const EnergyRun run = RunUnforced(m, 48000.0, 0.1, push, landing);
    CHECK(run.worst_rise <= 1e-9);
    worst = std::max(worst, run.worst_rise);
  }
  WARN("largest per-sample energy rise / injected energy over the random sets: " << worst);
}
