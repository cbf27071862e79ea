#pragma once
// Helpers shared by the synth tests: small materials, a height field with its summed-area table
// built here independently of app/surface, and estimators written from first principles.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "synth/height_field_view.h"
#include "synth/material_params.h"
#include "synth/probe_command.h"
#include "synth/scene.h"

namespace sas::synth::test {

// A height field plus the summed-area table in the layout HeightFieldView documents.
struct OwnedField {
  std::vector<float> heights;
  std::vector<double> sat;
  HeightFieldView view;

  OwnedField(int width, int height, double pitch_m, std::vector<float> h) : heights(std::move(h)) {
    const auto stride = static_cast<std::size_t>(width) + 1;
    sat.assign(stride * (static_cast<std::size_t>(height) + 1), 0.0);
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const auto i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                       static_cast<std::size_t>(x);
        sat[(static_cast<std::size_t>(y) + 1) * stride + static_cast<std::size_t>(x) + 1] =
            heights[i] +
            sat[static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x) + 1] +
            sat[(static_cast<std::size_t>(y) + 1) * stride + static_cast<std::size_t>(x)] -
            sat[static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x)];
      }
    }
    view.height_m = heights.data();
    view.summed_area = sat.data();
    view.width = width;
    view.height = height;
    view.pitch_m = pitch_m;
  }
  OwnedField(const OwnedField&) = delete;
  OwnedField& operator=(const OwnedField&) = delete;
};

// Least-squares fit of x[n+1] = c1 x[n] + c2 x[n-1] (the exact recursion of a sampled damped
// sinusoid: c1 = 2 r cos θ, c2 = -r²). Returns {frequency_hz, decay_s (1/e)}.
struct DampedSine {
  double frequency_hz = 0.0;
  double decay_s = 0.0;
};
template <class Seq>
DampedSine FitDampedSine(const Seq& x, std::size_t begin, std::size_t end, double fs) {
  double s11 = 0, s12 = 0, s22 = 0, r1 = 0, r2 = 0;
  for (std::size_t n = begin + 1; n + 1 < end; ++n) {
    const double a = static_cast<double>(x[n]), b = static_cast<double>(x[n - 1]),
                 y = static_cast<double>(x[n + 1]);
    s11 += a * a;
    s12 += a * b;
    s22 += b * b;
    r1 += a * y;
    r2 += b * y;
  }
  const double det = s11 * s22 - s12 * s12;
  const double c1 = (r1 * s22 - r2 * s12) / det;
  const double c2 = (s11 * r2 - s12 * r1) / det;
  const double r = std::sqrt(-c2);
  const double theta = std::acos(c1 / (2.0 * r));
  DampedSine out;
  out.frequency_hz = theta * fs / (2.0 * 3.14159265358979323846);
  out.decay_s = -1.0 / (fs * std::log(r));
  return out;
}

// A probe command at an absolute frame of a rendering.
struct TimedCommand {
  long frame = 0;
  ProbeCommand command;
};

// Renders `total` frames in blocks of `block`, each command placed on its frame within its block.
// Returns the interleaved 2-channel output.
inline std::vector<float> RenderTimed(Scene& scene, const std::vector<TimedCommand>& gesture,
                                      long total, int block) {
  std::vector<float> out(2 * static_cast<std::size_t>(total));
  std::vector<ProbeCommand> pending;
  std::size_t next = 0;
  for (long start = 0; start < total; start += block) {
    const int frames = static_cast<int>(std::min<long>(block, total - start));
    pending.clear();
    while (next < gesture.size() && gesture[next].frame < start + frames) {
      ProbeCommand c = gesture[next].command;
      c.frame_offset = static_cast<std::uint32_t>(std::max(0L, gesture[next].frame - start));
      pending.push_back(c);
      ++next;
    }
    scene.Process(pending.data(), static_cast<int>(pending.size()),
                  out.data() + 2 * static_cast<std::size_t>(start), frames);
  }
  return out;
}

inline double Cents(double measured, double target) {
  return 1200.0 * std::log2(measured / target);
}

// The rubbing demo of the Sound Design Toolkit: σ0 = 1000,
// σ1 = 39, σ2 = 13, c_ba = 0.3, μ_d = 0.03, μ_s = 0.75, v_s = 0.05, exciter 0.1 kg, six modes
// 100–600 Hz with decays 0.01–0.06 s.
// A small, well-damped wooden board: 12 modes 220 Hz - 5 kHz, decays 25-300 ms, with impact,
// friction and its noise term on (scene, skip and allocation tests).
inline MaterialParams WoodLikeBoard() {
  MaterialParams m;
  m.resonator.mode_count = 12;
  for (int i = 0; i < 12; ++i) {
    auto& mode = m.resonator.modes[static_cast<std::size_t>(i)];
    mode.frequency_hz = 220.0 * (i + 1) * (1.0 + 0.07 * i);
    mode.decay_s = 0.3 / (1.0 + i);
    mode.mass_kg = 0.03;
    mode.gain = 1.0 / (1.0 + 0.5 * i);
  }
  m.impact.stiffness = 3e7;
  m.impact.dissipation_s_per_m = 0.4;
  m.friction.noise_coefficient = 0.5;  // exercise the noise generator too
  return m;
}

// The friction of textures/materials/metal.toml (plastic nib on steel; the SDT's typical set).
inline FrictionParams MetalFriction() {
  FrictionParams f;
  f.enabled = true;
  f.bristle_stiffness = 1e4;
  f.bristle_damping = 10.0;
  f.viscous_friction = 0.4;
  f.static_coefficient = 0.3;
  f.dynamic_coefficient = 0.18;
  f.stribeck_velocity_mps = 0.05;
  f.breakaway_ratio = 0.7;
  return f;
}

inline MaterialParams SdtRubbingDemo() {
  MaterialParams m;
  m.impact.enabled = false;
  m.friction.enabled = true;
  m.friction.bristle_stiffness = 1000.0;
  m.friction.bristle_damping = 39.0;
  m.friction.viscous_friction = 13.0;
  m.friction.noise_coefficient = 0.0;
  m.friction.breakaway_ratio = 0.3;
  m.friction.dynamic_coefficient = 0.03;
  m.friction.static_coefficient = 0.75;
  m.friction.stribeck_velocity_mps = 0.05;
  m.probe.mass_kg = 0.1;
  m.resonator.mode_count = 6;
  for (int i = 0; i < 6; ++i) {
    auto& mode = m.resonator.modes[static_cast<std::size_t>(i)];
    mode.frequency_hz = 100.0 * (i + 1);
    mode.decay_s = 0.01 + 0.01 * i;
    mode.mass_kg = 0.1;
    mode.gain = 1.0;
  }
  return m;
}

}  // namespace sas::synth::test
