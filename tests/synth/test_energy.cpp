// With the probe resting on a lossy resonator and no further input, the
// total mechanical energy (resonator + probe + contact energy + bristle + potential of the
// constant push) never increases from one sample to the next. Every contact scheme guarantees it
// by construction (contact.h) for its own contact energy: V(x) for the discrete gradient, the
// received energy E of the passivity guard (explicit, trapezoid), the quadratised ψ²/2 (IEQ);
// the tests check it sample by sample, for each scheme.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
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

#if defined(__SANITIZE_ADDRESS__)
constexpr double kSchemeRunS = 0.1;  // ~10x slower under the sanitizer
constexpr int kSchemeSets = 4;
#else
constexpr double kSchemeRunS = 0.5;
constexpr int kSchemeSets = 12;
#endif

constexpr ContactScheme kAllSchemes[] = {
    ContactScheme::kExplicitPassive, ContactScheme::kTrapezoidNewton,
    ContactScheme::kDiscreteGradient, ContactScheme::kEnergyQuadratised};

// Random stiff, light, lossy and lossless contacts (0.1 s each); returns the worst rise.
double WorstRiseOverRandomSets(ContactScheme scheme, int sets, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  auto log_uniform = [&](double lo, double hi) {
    return std::exp(std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(rng));
  };
  double worst = 0.0;
  for (int set = 0; set < sets; ++set) {
    MaterialParams m = LossyPlate(1 + set % 6);
    for (int i = 0; i < m.resonator.mode_count; ++i) {
      auto& mode = m.resonator.modes[static_cast<std::size_t>(i)];
      mode.mass_kg = log_uniform(1e-4, 1.0);
      mode.decay_s = log_uniform(1e-3, 10.0);
      mode.frequency_hz = log_uniform(50.0, 20000.0);
    }
    m.impact.scheme = scheme;
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
    INFO("scheme " << static_cast<int>(scheme) << " set " << set << " k " << m.impact.stiffness
                   << " alpha " << m.impact.shape_alpha << " mu " << m.impact.dissipation_s_per_m
                   << " probe " << m.probe.mass_kg << " sigma0 " << m.friction.bristle_stiffness);
    const EnergyRun run = RunUnforced(m, 48000.0, 0.1, push, landing);
    CHECK(run.worst_rise <= 1e-9);
    worst = std::max(worst, run.worst_rise);
  }
  return worst;
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
  const double worst = WorstRiseOverRandomSets(ContactScheme::kDiscreteGradient, 24, 20261122);
  WARN("largest per-sample energy rise / injected energy over the random sets: " << worst);
}

TEST_CASE(
    "every contact scheme: probe resting on a lossy resonator, total energy with the scheme's "
    "own contact energy never increases over 0.5 s (impact and friction), a rigid pen or a nib "
    "under a pen body (the body's motion, the sensor spring and the hand's work on it counted)",
    "[dsp]") {
  for (const ContactScheme scheme : kAllSchemes) {
    for (const bool friction : {false, true}) {
      for (const bool body : {false, true}) {
        MaterialParams m = LossyPlate(8);
        m.impact.scheme = scheme;
        m.friction.enabled = friction;
        if (body) {  // a 0.3 g nib on 1e4 N/m under a 15 g body
          m.probe.mass_kg = 3e-4;
          m.probe.body_mass_kg = 0.015;
          m.probe.body_spring_n_per_m = 1e4;
        }
        const EnergyRun run = RunUnforced(m, 48000.0, kSchemeRunS, 0.5, 0.5);
        INFO("scheme " << static_cast<int>(scheme) << " friction " << friction << " body "
                       << body);
        CHECK(run.worst_rise <= 1e-9);
        CHECK(run.end < run.start);
        if (friction) CHECK(run.max_bristle > 0.0);
      }
    }
  }
}

TEST_CASE(
    "every contact scheme: energy never increases for random stiff, light, lossy and lossless "
    "contacts",
    "[dsp]") {
  std::uint64_t seed = 20261123;
  for (const ContactScheme scheme : kAllSchemes) {
    if (scheme == ContactScheme::kDiscreteGradient) continue;  // 24 sets in the test above
    const double worst = WorstRiseOverRandomSets(scheme, kSchemeSets, seed++);
    WARN("scheme " << static_cast<int>(scheme) << ": largest per-sample energy rise / injected "
                   << "energy over the random sets: " << worst);
  }
}

