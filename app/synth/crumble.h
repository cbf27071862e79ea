#pragma once
// A crust that crumbles under the tip (CrumbleParams): dry cracked soil is not scraped like a
// board, it breaks. Along the stroke the tip meets the crust's grains one after another (on
// average every grain_spacing_m, as a Poisson process in distance, so the rate follows the hand's
// speed); each one breaks if the tip's load exceeds its strength, and strengths spread as a
// Weibull distribution (the statistics of crushing grains and aggregates: McDowell & Bolton,
// Géotechnique 48(5), 1998), so a firmer pen breaks more of them. A breaking grain frees a loose
// flake of the crust, which the tip knocks away at a fraction of its own speed (flake_speed_ratio:
// a faster stroke breaks more grains and flings them harder); the crust takes the reaction (an
// impulse on its modes, the "crunch" of the clods), and the flake rings on its own as a thin free
// plate: f ∝ h / a² (Leissa, NASA SP-160), so at one thickness its size sets its pitch, from
// flake_low_hz (the largest) to flake_high_hz (the smallest), and its mass ∝ a². Fragment sizes
// follow the power law of fragmentation, N(> a) ∝ a^-D with D ≈ 2.5 for many crushed rocks and
// soils (Turcotte, J. Geophys. Res. 91(B2), 1986): many small bright flakes, a few large ones.
// The flakes' rings are brief (η ≈ 0.15 like the crust) and broadband, which is what makes a
// crumbling sound gritty rather than tonal.
//
// Pure DSP: fixed storage, no allocation, no exceptions; its own random generator, so a material
// without [crumble] plays exactly as before.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "synth/material_params.h"
#include "synth/modal_resonator.h"

namespace sas::synth {

class CrumbleSource {
 public:
  static constexpr int kFlakes = 8;  // flakes ringing at once (each rings for about a millisecond)

  // Not real-time (std::exp and friends once). A disabled crumble never makes an event.
  void Prepare(const CrumbleParams& params, double sample_rate_hz) {
    params_ = params;
    fs_ = sample_rate_hz;
    enabled_ = params.enabled && params.grain_spacing_m > 0.0 && params.strength_n > 0.0 &&
               params.flake_low_hz > 0.0 && params.flake_high_hz >= params.flake_low_hz;
    size_floor_ = std::sqrt(params.flake_low_hz / std::max(params.flake_high_hz, 1e-300));
    floor_power_ = std::pow(size_floor_, params.size_exponent);
    Reset();
  }

  void Reset() {
    Silence();
    rng_ = kSeed;
    next_ = 0;
    events_ = 0;
  }

  // The flakes stop ringing; the grains to come stay the same (the scene's idle skip zeroes the
  // inaudible state, and must not change what a later stroke plays).
  void Silence() {
    q_.fill(0.0);
    v_.fill(0.0);
    gain_.fill(0.0);
    alive_ = 0;
  }

  bool enabled() const { return enabled_; }

  // The chance that a grain the tip meets breaks under `load_n` (Weibull).
  double BreakProbability(double load_n) const {
    if (!(load_n > 0.0)) return 0.0;
    return 1.0 - std::exp(-std::pow(load_n / params_.strength_n, params_.weibull_modulus));
  }

  // One sample of the tip sliding `ds_m` under `load_n`. Returns the impulse (N s, >= 0) a
  // breaking grain put on its flake this sample, 0 if none broke; the crust takes it in
  // reaction (the scene kicks its modes). The new flake starts ringing this sample.
  double Slide(double ds_m, double load_n) {
    if (!enabled_ || !(ds_m > 0.0) || !(load_n > 0.0)) return 0.0;
    const double chance = ds_m / params_.grain_spacing_m * BreakProbability(load_n);
    if (Uniform01() >= chance) return 0.0;
    // The flake's size a / a_max by the truncated power law (inverse of its distribution).
    const double u = Uniform01();
    const double r =
        size_floor_ * std::pow(1.0 - u * (1.0 - floor_power_), -1.0 / params_.size_exponent);
    const double size = std::clamp(r, size_floor_, 1.0);
    const double frequency_hz = params_.flake_low_hz / (size * size);
    const double mass_kg = params_.flake_mass_kg * size * size;
    ++events_;
    const double launch_mps = params_.flake_speed_ratio * ds_m * fs_;
    const double impulse = mass_kg * launch_mps;
    // A flake above 0.45 fs cannot ring at this rate: its reaction on the crust is all there is.
    if (frequency_hz >= kMaxModeFrequencyRatio * fs_) return impulse;
    const auto k = static_cast<std::size_t>(next_);
    next_ = (next_ + 1) % kFlakes;
    const double decay_s = 1.0 / (std::numbers::pi * frequency_hz * params_.flake_loss_factor);
    step_[k] = ComputeModeStep(frequency_hz, decay_s, 1.0, 1.0 / fs_);
    q_[k] = 0.0;
    v_[k] = launch_mps;
    // Each flake lies its own way up: the sign of its ring at the pickup is random.
    gain_[k] = Uniform01() < 0.5 ? params_.flake_gain : -params_.flake_gain;
    alive_ |= 1u << k;
    return impulse;
  }

  // Advances the ringing flakes by one sample; returns their pickup velocity before the step
  // (a flake that broke this sample is heard at once).
  double Ring() {
    if (alive_ == 0) return 0.0;
    double pickup = 0.0;
    for (int i = 0; i < kFlakes; ++i) {
      if ((alive_ & (1u << i)) == 0) continue;
      const auto k = static_cast<std::size_t>(i);
      pickup += gain_[k] * v_[k];
      const ModeStep& m = step_[k];
      const double q = m.a11 * q_[k] + m.a12 * v_[k];
      const double v = m.a21 * q_[k] + m.a22 * v_[k];
      q_[k] = q;
      v_[k] = v;
      // Rung out: far below anything the idle check or an output sample could notice.
      if (std::fabs(gain_[k]) * (std::fabs(v) + std::fabs(q) * kOmegaBound) < kRungOut) {
        alive_ &= ~(1u << i);
        q_[k] = v_[k] = 0.0;
      }
    }
    return pickup;
  }

  // Upper bound of the flakes' pickup amplitude (the scene's idle check adds it to the modes').
  double AmplitudeBound() const {
    double sum = 0.0;
    for (int i = 0; i < kFlakes; ++i) {
      if ((alive_ & (1u << i)) == 0) continue;
      const auto k = static_cast<std::size_t>(i);
      sum += std::fabs(gain_[k]) * (std::fabs(v_[k]) + std::fabs(q_[k]) * kOmegaBound);
    }
    return sum;
  }

  // Grains broken since Reset (tests and meters).
  std::uint64_t events() const { return events_; }

 private:
  static constexpr std::uint64_t kSeed = 0xD1B54A32D192ED03ull;
  // ω of the fastest flake any sample rate allows (0.45 · 192 kHz), bounding |ω q| by ω_max |q|.
  static constexpr double kOmegaBound = 2.0 * std::numbers::pi * 0.45 * 192000.0;
  static constexpr double kRungOut = 1e-12;

  double Uniform01() {  // xorshift64*: uniform in [0, 1)
    rng_ ^= rng_ >> 12;
    rng_ ^= rng_ << 25;
    rng_ ^= rng_ >> 27;
    return static_cast<double>((rng_ * 0x2545F4914F6CDD1Dull) >> 11) * (1.0 / 9007199254740992.0);
  }

  CrumbleParams params_{};
  double fs_ = 48000.0;
  bool enabled_ = false;
  double size_floor_ = 1.0;   // smallest flake / largest
  double floor_power_ = 1.0;  // size_floor_^D
  std::uint64_t rng_ = kSeed;
  std::array<ModeStep, kFlakes> step_{};
  std::array<double, kFlakes> q_{};
  std::array<double, kFlakes> v_{};
  std::array<double, kFlakes> gain_{};
  unsigned alive_ = 0;
  int next_ = 0;
  std::uint64_t events_ = 0;
};

}  // namespace sas::synth
