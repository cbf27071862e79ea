#pragma once
// Randomised stress sets for the synth, shared by the Catch2 stress test
// (tests/synth/test_stress.cpp, a few thousand sets) and the benchmark's long mode
// (`contact_bench --stress N`, >= 10^5 sets), so both draw from the same ranges and run the same
// checks. A set is fully determined by (seed, index): a failing index can be replayed alone.
//
// Ranges: Hunt–Crossley k 1e3–1e12, α 1–4, μ 0–10; probe mass 1e-4–1 kg; speeds up to
// 10 m/s; 1–64 modes, 20 Hz – 24 kHz (some above the 0.45 fs limit), decays 1 ms–10 s, modal
// masses 1e-4–10 kg; friction σ0 up to 1e7; every contact scheme and oversampling; exaggerated
// output gains; a random gesture with discontinuous jumps of position, force, style, width and
// tip up/down, bursts, on a rough profile with steps.
// Checks: every output sample finite and |y| <= 1 (the limiter), and in a final stretch with no
// input (tip held down without sliding, or lifted; once a lift or a style switch's glide has
// ended) the total mechanical energy Scene::TotalEnergy() of the unlimited physics never rises
// from one sample to the next by more than kStressEnergyTolerance of the energy scale.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "synth/material_params.h"
#include "synth/output_stage.h"
#include "synth/probe_command.h"
#include "synth/scene.h"
#include "synth_test_support.h"

namespace sas::synth::test {

inline constexpr std::uint64_t kStressSeed = 0x5CA7C4ull;
// Per-sample energy rise allowed, relative to the energy scale of the stretch (rounding only).
inline constexpr double kStressEnergyTolerance = 1e-9;

struct StressSet {
  int index = 0;
  double sample_rate_hz = 48000.0;
  MaterialParams material;
  OutputParams output;
  std::vector<float> profile;  // 1-D height field, metres
  std::vector<TimedCommand> gesture;
  long gesture_frames = 0;  // rendered in blocks of block_frames
  int block_frames = 128;
  ProbeCommand rest;     // the final command: no input after it
  long rest_frames = 0;  // rendered frame by frame, energy checked
};

struct StressOutcome {
  long non_finite = 0;             // output samples that are NaN or Inf
  long over_limit = 0;             // |y| > 1 (sound), > HapticBound(output) (transducer)
  double peak = 0.0;               // max |y|
  double worst_energy_rise = 0.0;  // largest per-sample rise / energy scale in the rest stretch
  bool energy_finite = true;
  bool ok(double tolerance = kStressEnergyTolerance) const {
    return non_finite == 0 && over_limit == 0 && energy_finite && worst_energy_rise <= tolerance;
  }
};

class StressRandom {
 public:
  explicit StressRandom(std::uint64_t seed) : rng_(seed) {}
  double Uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
  }
  double LogUniform(double lo, double hi) { return std::exp(Uniform(std::log(lo), std::log(hi))); }
  int Int(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  bool Chance(double p) { return Uniform(0.0, 1.0) < p; }

 private:
  std::mt19937_64 rng_;
};

inline StressSet MakeStressSet(std::uint64_t seed, int index) {
  StressRandom r(seed ^ (0x9E3779B97F4A7C15ull * static_cast<std::uint64_t>(index + 1)));
  StressSet set;
  set.index = index;
  set.sample_rate_hz = r.Chance(0.8) ? 48000.0 : (r.Chance(0.5) ? 44100.0 : 96000.0);
  MaterialParams& m = set.material;
  m.resonator.mode_count = r.Int(1, kMaxModes);
  for (int i = 0; i < m.resonator.mode_count; ++i) {
    ModeParams& mode = m.resonator.modes[static_cast<std::size_t>(i)];
    mode.frequency_hz = r.LogUniform(20.0, 24000.0);
    mode.decay_s = r.LogUniform(1e-3, 10.0);
    mode.mass_kg = r.LogUniform(1e-4, 10.0);
    mode.gain = r.Chance(0.05) ? 0.0 : r.Uniform(-1.0, 1.0);
  }
  m.impact.enabled = r.Chance(0.9);
  m.impact.stiffness = r.LogUniform(1e3, 1e12);
  m.impact.shape_alpha = r.Chance(0.3) ? 1.5 : r.Uniform(1.0, 4.0);
  m.impact.dissipation_s_per_m = r.Chance(0.15) ? 0.0 : r.LogUniform(1e-3, 10.0);
  m.impact.scheme = static_cast<ContactScheme>(r.Int(0, 3));
  m.impact.oversample = r.Chance(0.5) ? 0 : 1 << r.Int(0, 6);
  m.friction.enabled = r.Chance(0.7);
  m.friction.bristle_stiffness = r.LogUniform(1.0, 1e7);
  m.friction.bristle_damping = r.Chance(0.1) ? 0.0 : r.LogUniform(1e-3, 1e3);
  m.friction.viscous_friction = r.Chance(0.1) ? 0.0 : r.LogUniform(1e-3, 1e2);
  m.friction.noise_coefficient = r.Chance(0.3) ? 0.0 : r.LogUniform(1e-3, 1.0);
  m.friction.dynamic_coefficient = r.Uniform(0.0, 1.0);
  m.friction.static_coefficient = m.friction.dynamic_coefficient + r.Uniform(0.0, 1.0);
  m.friction.stribeck_velocity_mps = r.LogUniform(1e-3, 1.0);
  m.friction.breakaway_ratio = r.Uniform(0.02, 0.98);
  m.probe.mass_kg = r.LogUniform(1e-4, 1.0);
  m.probe.ball_radius_m = r.LogUniform(1e-4, 1e-2);
  set.output.sound_gain = r.LogUniform(1e-2, 1e6);
  set.output.haptic_gain = r.LogUniform(1e-2, 1e6);
  set.output.haptic_enabled = r.Chance(0.8);

  // A rough 1-D profile (78 mm) with steps: smooth noise plus jumps up to 1 mm.
  set.profile.resize(512);
  double level = 0.0;
  for (std::size_t i = 0; i < set.profile.size(); ++i) {
    if (r.Chance(0.02)) level = r.Uniform(0.0, 1e-3);
    set.profile[i] = static_cast<float>(level + r.Uniform(0.0, 5e-5));
  }

  const double pitch = 0.153e-3;
  set.block_frames = r.Chance(0.5) ? 128 : r.Int(1, 512);
  set.gesture_frames = static_cast<long>(r.Int(1024, 3072));
  const int count = r.Int(4, 16);
  auto random_command = [&]() {
    ProbeCommand c;
    c.tip_down = r.Chance(0.75);
    c.x_m = r.Uniform(0.0, 512.0 * pitch);
    c.y_m = 0.0;
    c.velocity_mps = r.Chance(0.2) ? 0.0 : r.LogUniform(1e-3, 10.0);
    c.normal_force_n = r.Chance(0.1) ? 0.0 : r.LogUniform(1e-3, 10.0);
    c.width_mm = r.Uniform(0.0, 10.0);
    c.penetration_m = r.Uniform(0.0, 1.2e-3);
    c.style = static_cast<ProbeStyle>(r.Int(0, 2));
    const double angle = r.Uniform(0.0, 6.283185307179586);
    c.direction_x = std::cos(angle);
    c.direction_y = std::sin(angle);
    c.landing_speed_mps = r.Uniform(0.0, 10.0);
    c.burst_impulse_n_s = r.Chance(0.15) ? r.LogUniform(1e-7, 1e-2) : 0.0;
    return c;
  };
  for (int i = 0; i < count; ++i) {
    set.gesture.push_back(
        {static_cast<long>(r.Int(0, static_cast<int>(set.gesture_frames) - 1)), random_command()});
  }
  std::sort(set.gesture.begin(), set.gesture.end(),
            [](const TimedCommand& a, const TimedCommand& b) { return a.frame < b.frame; });

  // The rest: pen held down without sliding (the probe lands or stays), or lifted. No noise, no
  // burst, no moving surface: no input from here on.
  set.rest = random_command();
  set.rest.velocity_mps = 0.0;
  set.rest.burst_impulse_n_s = 0.0;
  set.rest_frames = static_cast<long>(r.Int(128, 512));
  return set;
}

// The most a scene's transducer sample can be: the ceiling the limiter saturates at, lifted by
// the band limit after it by at most its own gain (synth/output_stage.h; the final safety stage
// holds the ceiling itself).
inline double HapticBound(const OutputParams& output, double sample_rate_hz) {
  OutputStage stage;
  stage.Prepare(output, sample_rate_hz);
  const double ceiling = std::isfinite(output.haptic_ceiling)
                             ? std::clamp(output.haptic_ceiling, 1e-6, 1.0)
                             : 1.0;
  return ceiling * stage.BandLimitGain();
}

inline StressOutcome RunStressSet(const StressSet& set, const SceneSkips& skips = SceneSkips{}) {
  OwnedField field(static_cast<int>(set.profile.size()), 1, 0.153e-3, set.profile);
  Scene scene;
  scene.SetSkips(skips);
  scene.Init(set.sample_rate_hz);
  scene.Prepare(set.material, set.output, field.view);
  StressOutcome outcome;
  const double haptic_bound = HapticBound(set.output, set.sample_rate_hz);
  auto check = [&](const float* samples, std::size_t n) {  // interleaved frames
    for (std::size_t i = 0; i < n; ++i) {
      const double y = static_cast<double>(samples[i]);
      if (!std::isfinite(y)) {
        ++outcome.non_finite;
      } else {
        if (std::fabs(y) > (i % 2 == 0 ? 1.0 : haptic_bound)) ++outcome.over_limit;
        outcome.peak = std::max(outcome.peak, std::fabs(y));
      }
    }
  };
  const std::vector<float> out =
      RenderTimed(scene, set.gesture, set.gesture_frames, set.block_frames);
  check(out.data(), out.size());

  float frame[2];
  ProbeCommand rest = set.rest;
  scene.Process(&rest, 1, frame, 1);
  check(frame, 2);
  // A lift is carried out by the hand (Scene: the load taken off over a few ms), and a style
  // switched with the tip down glides the felt surface to the new style's (20 ms): inputs like
  // the gesture. The energy is watched from their end on.
  const auto input = [&] {
    const SceneProbeState state = scene.probe_state();
    return state.unloading || state.gliding;
  };
  for (long n = 0; input() && n < static_cast<long>(set.sample_rate_hz); ++n) {
    scene.Process(nullptr, 0, frame, 1);
    check(frame, 2);
  }
  // Energy scale of the stretch: the largest magnitude the stored energy and its parts take in
  // it, so the tolerance is relative to the physics at hand and not to an absolute joule figure.
  // The push's potential f_N · height is part of the total: its magnitude sets the rounding
  // level, so it is part of the scale.
  const double push = rest.tip_down ? rest.normal_force_n : 0.0;
  auto magnitude = [&]() {
    const SceneProbeState st = scene.probe_state();
    return std::fabs(scene.TotalEnergy()) + scene.ResonatorEnergy() +
           (st.active ? std::fabs(push * st.height_m) : 0.0);
  };
  std::vector<double> energies;
  energies.reserve(static_cast<std::size_t>(set.rest_frames) + 1);
  energies.push_back(scene.TotalEnergy());
  double scale = magnitude();
  for (long n = 0; n < set.rest_frames; ++n) {
    scene.Process(nullptr, 0, frame, 1);
    check(frame, 2);
    energies.push_back(scene.TotalEnergy());
    scale = std::max(scale, magnitude());
  }
  for (double e : energies) {
    if (!std::isfinite(e)) outcome.energy_finite = false;
  }
  if (scale > 0.0 && outcome.energy_finite) {
    for (std::size_t i = 1; i < energies.size(); ++i) {
      outcome.worst_energy_rise =
          std::max(outcome.worst_energy_rise, (energies[i] - energies[i - 1]) / scale);
    }
  }
  return outcome;
}

}  // namespace sas::synth::test
