// Output stage: gains, haptic band-pass and soft limiters (see output_stage.h).
#include "synth/output_stage.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace sas::synth {
namespace {

// RBJ audio-EQ-cookbook biquads (R. Bristow-Johnson); Q values of the Butterworth sections.
Biquad LowPass(double cutoff_hz, double q, double fs) {
  const double w = 2.0 * std::numbers::pi * cutoff_hz / fs;
  const double alpha = std::sin(w) / (2.0 * q), c = std::cos(w);
  const double a0 = 1.0 + alpha;
  Biquad b;
  b.b0 = (1.0 - c) / 2.0 / a0;
  b.b1 = (1.0 - c) / a0;
  b.b2 = b.b0;
  b.a1 = -2.0 * c / a0;
  b.a2 = (1.0 - alpha) / a0;
  return b;
}

Biquad HighPass(double cutoff_hz, double q, double fs) {
  const double w = 2.0 * std::numbers::pi * cutoff_hz / fs;
  const double alpha = std::sin(w) / (2.0 * q), c = std::cos(w);
  const double a0 = 1.0 + alpha;
  Biquad b;
  b.b0 = (1.0 + c) / 2.0 / a0;
  b.b1 = -(1.0 + c) / a0;
  b.b2 = b.b0;
  b.a1 = -2.0 * c / a0;
  b.a2 = (1.0 - alpha) / a0;
  return b;
}

}  // namespace

std::array<Biquad, 2> KWeighting(double fs) {
  fs = std::max(fs, 1.0);
  std::array<Biquad, 2> k;
  {  // the high shelf
    const double f0 = 1681.974450955533, gain_db = 3.999843853973347, q = 0.7071752369554196;
    const double t = std::tan(std::numbers::pi * f0 / fs);
    const double vh = std::pow(10.0, gain_db / 20.0);
    const double vb = std::pow(vh, 0.4996667741545416);
    const double a0 = 1.0 + t / q + t * t;
    k[0].b0 = (vh + vb * t / q + t * t) / a0;
    k[0].b1 = 2.0 * (t * t - vh) / a0;
    k[0].b2 = (vh - vb * t / q + t * t) / a0;
    k[0].a1 = 2.0 * (t * t - 1.0) / a0;
    k[0].a2 = (1.0 - t / q + t * t) / a0;
  }
  {  // the high-pass (unnormalised numerator 1, -2, 1, as in the standard)
    const double f0 = 38.13547087602444, q = 0.5003270373238773;
    const double t = std::tan(std::numbers::pi * f0 / fs);
    const double a0 = 1.0 + t / q + t * t;
    k[1].b0 = 1.0;
    k[1].b1 = -2.0;
    k[1].b2 = 1.0;
    k[1].a1 = 2.0 * (t * t - 1.0) / a0;
    k[1].a2 = (1.0 - t / q + t * t) / a0;
  }
  return k;
}

void OutputStage::Prepare(const OutputParams& params, double sample_rate_hz) {
  auto finite_or = [](double v, double fallback) { return std::isfinite(v) ? v : fallback; };
  sound_gain_ = finite_or(params.sound_gain, 0.0);
  haptic_gain_ = finite_or(params.haptic_gain, 0.0);
  haptic_enabled_ = params.haptic_enabled;
  haptic_ceiling_ = std::clamp(finite_or(params.haptic_ceiling, 1.0), 1e-6, 1.0);
  low_vibration_gain_ = std::clamp(finite_or(params.low_vibration_gain, 1.0), 0.0, 1.0);
  ramp_samples_ = std::max(1.0, kLowVibrationRampS * sample_rate_hz);
  low_vibration_ = params.low_vibration;
  sound_leveller_.Prepare(finite_or(params.sound_level_cap, 0.0),
                          {.window_s = kLevellerWindowS,
                           .attack_s = kLevellerAttackS,
                           .release_s = kLevellerReleaseS,
                           .landing_s = kLevellerLandingS,
                           .burst_window_s = kBurstWindowS,
                           .burst_attack_s = kBurstAttackS,
                           .burst_release_s = kBurstReleaseS,
                           .burst_over_db = kBurstOverCapDb},
                          sample_rate_hz);
  const double nyquist_guard = 0.45 * sample_rate_hz;
  const double low = std::clamp(finite_or(params.haptic_low_hz, 40.0), 1.0, nyquist_guard);
  const double high = std::clamp(finite_or(params.haptic_high_hz, 400.0), low, nyquist_guard);
  // 4th-order Butterworth before the limiter: Q = 1 / (2 cos(π/8)), 1 / (2 cos(3π/8)).
  pre_[0] = HighPass(low, 1.0 / (2.0 * std::cos(std::numbers::pi / 8.0)), sample_rate_hz);
  pre_[1] = HighPass(low, 1.0 / (2.0 * std::cos(3.0 * std::numbers::pi / 8.0)), sample_rate_hz);
  pre_[2] = LowPass(high, 1.0 / (2.0 * std::cos(std::numbers::pi / 8.0)), sample_rate_hz);
  pre_[3] = LowPass(high, 1.0 / (2.0 * std::cos(3.0 * std::numbers::pi / 8.0)), sample_rate_hz);
  sections_[0] = HighPass(low, std::numbers::sqrt2 / 2.0, sample_rate_hz);
  // 16th-order Butterworth: Q_k = 1 / (2 cos((2k - 1) π / 32)), k = 1..8. Steep enough that the
  // transducer gets (almost) nothing above 1 kHz even from a flat spectrum.
  for (int k = 1; k <= 8; ++k) {
    const double q = 1.0 / (2.0 * std::cos((2.0 * k - 1.0) * std::numbers::pi / 32.0));
    sections_[static_cast<std::size_t>(k)] = LowPass(high, q, sample_rate_hz);
  }
  sample_rate_hz_ = sample_rate_hz;
  haptic_drive_ = haptic_gain_ / haptic_ceiling_;
  Reset();
}

void OutputStage::Reset() {
  for (auto& s : pre_) s.s1 = s.s2 = 0.0;
  for (auto& s : sections_) s.s1 = s.s2 = 0.0;
  // Silent after a reset, so the trim and the stroke gains may jump to where they are asked to be.
  trim_ = trim_target_ = (low_vibration_ ? low_vibration_gain_ : 1.0) * stroke_haptic_;
  trim_step_ = 0.0;
  stroke_sound_ = stroke_sound_target_;
  stroke_sound_step_ = 0.0;
  sound_leveller_.Reset();
}

void Leveller::Prepare(double cap, const Times& times, double fs) {
  fs = std::max(fs, 1.0);
  const auto step = [fs](double seconds) { return 1.0 - std::exp(-1.0 / (seconds * fs)); };
  landing_samples = static_cast<int>(std::clamp(times.landing_s * fs, 0.0, 1e9));
  cap_square = cap > 0.0 && std::isfinite(cap) ? cap * cap : 0.0;
  burst_cap_square = cap_square * std::pow(10.0, times.burst_over_db / 10.0);
  level_step = step(times.window_s);
  attack_step = step(times.attack_s);
  release_step = step(times.release_s);
  burst_step = step(times.burst_window_s);
  burst_attack_step = step(times.burst_attack_s);
  burst_release_step = step(times.burst_release_s);
  weighting = KWeighting(fs);
  Reset();
}

void OutputStage::StartTrimRamp(double samples) {
  const double target = (low_vibration_ ? low_vibration_gain_ : 1.0) * stroke_haptic_;
  if (target == trim_target_) return;
  trim_target_ = target;
  trim_step_ = (trim_target_ - trim_) / samples;
  if (trim_step_ == 0.0) trim_ = trim_target_;
}

void OutputStage::SetLowVibration(bool on) {
  low_vibration_ = on;
  StartTrimRamp(ramp_samples_);
}

void OutputStage::SetStrokeGains(double sound, double haptic, double ramp_s) {
  const double samples = std::max(
      1.0, std::clamp(std::isfinite(ramp_s) ? ramp_s : kLowVibrationRampS, kMinStrokeRampS, 1.0) *
               ramp_samples_ / kLowVibrationRampS);
  const auto clamp = [](double g) {
    return std::isfinite(g) ? std::clamp(g, 0.0, kMaxStrokeGain) : 1.0;
  };
  stroke_haptic_ = clamp(haptic);
  StartTrimRamp(samples);
  const double target = clamp(sound);
  if (target == stroke_sound_target_) return;
  stroke_sound_target_ = target;
  stroke_sound_step_ = (stroke_sound_target_ - stroke_sound_) / samples;
  if (stroke_sound_step_ == 0.0) stroke_sound_ = stroke_sound_target_;
}

double OutputStage::SoftShoulder(double x) {
  if (!std::isfinite(x)) return std::isnan(x) ? 0.0 : (x > 0.0 ? 1.0 : -1.0);
  const double magnitude = std::fabs(x);
  if (magnitude <= kKnee) return x;
  const double y = kKnee + (1.0 - kKnee) * std::tanh((magnitude - kKnee) / (1.0 - kKnee));
  return x > 0.0 ? y : -y;
}

namespace {

// N biquads in series over y[0..n), in place, frame-major, with their state in locals (hence
// registers: the loops are unrolled) for the whole run; the arithmetic is Biquad::Process's.
template <int N>
void Cascade(Biquad* sections, double* y, int n) {
  std::array<Biquad, N> s;
#pragma GCC unroll 16
  for (int k = 0; k < N; ++k) s[k] = sections[k];
  for (int i = 0; i < n; ++i) {
    double v = y[i];
#pragma GCC unroll 16
    for (int k = 0; k < N; ++k) v = s[k].Process(v);
    y[i] = v;
  }
#pragma GCC unroll 16
  for (int k = 0; k < N; ++k) sections[k] = s[k];
}

// Two independent cascades (N1 sections over y1, N2 over y2) in one loop: their dependency
// chains overlap. The arithmetic of each is Cascade's.
template <int N1, int N2>
void CascadePair(Biquad* sections1, double* y1, Biquad* sections2, double* y2, int n) {
  std::array<Biquad, N1> s1;
  std::array<Biquad, N2> s2;
#pragma GCC unroll 16
  for (int k = 0; k < N1; ++k) s1[k] = sections1[k];
#pragma GCC unroll 16
  for (int k = 0; k < N2; ++k) s2[k] = sections2[k];
  for (int i = 0; i < n; ++i) {
    double v1 = y1[i], v2 = y2[i];
#pragma GCC unroll 16
    for (int k = 0; k < N1; ++k) v1 = s1[k].Process(v1);
#pragma GCC unroll 16
    for (int k = 0; k < N2; ++k) v2 = s2[k].Process(v2);
    y1[i] = v1;
    y2[i] = v2;
  }
#pragma GCC unroll 16
  for (int k = 0; k < N1; ++k) sections1[k] = s1[k];
#pragma GCC unroll 16
  for (int k = 0; k < N2; ++k) sections2[k] = s2[k];
}

}  // namespace

void OutputStage::ProcessBlock(const double* pickup, const double* felt, float* out, int n) {
  while (n > 0) {
    const int done = ProcessRun(pickup, felt, out, n);
    pickup += done;
    felt += done;
    out += 2 * static_cast<std::ptrdiff_t>(done);
    n -= done;
  }
}

int OutputStage::ProcessRun(const double* pickup, const double* felt, float* out, int n) {
  n = std::min(n, kBlockFrames);
  // The inputs of both channels (the sound's gain ramp as Process's first half).
  double sound[kBlockFrames], heard[kBlockFrames], y[kBlockFrames];
  for (int i = 0; i < n; ++i) {
    const double p = std::isfinite(pickup[i]) ? pickup[i] : 0.0;
    const double f = std::isfinite(felt[i]) ? felt[i] : 0.0;
    if (stroke_sound_ != stroke_sound_target_) {
      stroke_sound_ += stroke_sound_step_;
      if ((stroke_sound_step_ > 0.0) == (stroke_sound_ >= stroke_sound_target_)) {
        stroke_sound_ = stroke_sound_target_;
      }
    }
    sound[i] = heard[i] = sound_gain_ * stroke_sound_ * p;
    y[i] = f;
  }
  // The filters, with their state in registers: the K-weighting beside the haptic channel's
  // pre-limiter band (6 independent chains in one loop).
  static_assert(kPreSections == 4 && kSections == 9);
  const bool levelled = sound_leveller_.cap_square > 0.0;
  if (levelled && haptic_enabled_) {
    CascadePair<2, 4>(sound_leveller_.weighting.data(), heard, pre_.data(), y, n);
  } else if (levelled) {
    Cascade<2>(sound_leveller_.weighting.data(), heard, n);
  } else if (haptic_enabled_) {
    Cascade<4>(pre_.data(), y, n);
  }
  // The sound channel; the limiter in a loop of its own (measured faster).
  if (levelled) {
    for (int i = 0; i < n; ++i) sound[i] = sound_leveller_.ApplyHeard(sound[i], heard[i]);
  }
  for (int i = 0; i < n; ++i) out[2 * i] = static_cast<float>(SoftLimit(sound[i]));
  if (!haptic_enabled_) {
    for (int i = 0; i < n; ++i) out[2 * i + 1] = 0.0f;
    return n;
  }
  // Process's order: the trim, the limiter, then the band limit. A non-finite value out of the
  // high-pass (frame m) or the band limit (frame j) resets the stage after that frame's sound, as
  // Process does, and the frames after it (both channels, run from the old state) are run again.
  int m = 0;
  for (; m < n; ++m) {
    if (!std::isfinite(y[m])) break;
    if (trim_ != trim_target_) {
      trim_ += trim_step_;
      if ((trim_step_ > 0.0) == (trim_ >= trim_target_)) trim_ = trim_target_;
    }
    y[m] = haptic_ceiling_ * SoftLimit(haptic_drive_ * trim_ * y[m]);
  }
  Cascade<4>(&sections_[0], y, m);
  Cascade<5>(&sections_[4], y, m);
  for (int i = 0; i < m; ++i) {
    if (!std::isfinite(y[i])) {
      Reset();
      out[2 * i + 1] = 0.0f;
      return i + 1;
    }
    out[2 * i + 1] = static_cast<float>(y[i]);
  }
  if (m < n) {
    Reset();
    out[2 * m + 1] = 0.0f;
    return m + 1;
  }
  return n;
}

double OutputStage::BandLimitGain() const {
  // The band limit's L1 norm: its impulse response summed over two seconds (by then it has
  // decayed far under 1e-12 of its peak). Not real-time: for tests and tools, not Prepare.
  auto sections = sections_;
  for (auto& s : sections) s.s1 = s.s2 = 0.0;
  double sum = 0.0;
  const auto n = static_cast<long>(std::max(1.0, 2.0 * sample_rate_hz_));
  for (long i = 0; i < n; ++i) {
    double v = i == 0 ? 1.0 : 0.0;
    for (auto& s : sections) v = s.Process(v);
    sum += std::fabs(v);
  }
  return std::isfinite(sum) && sum > 1.0 ? sum : 1.0;
}

double OutputStage::FilterActivity() const {
  double m = 0.0;
  for (const auto& s : pre_) m = std::max({m, std::fabs(s.s1), std::fabs(s.s2)});
  for (const auto& s : sections_) m = std::max({m, std::fabs(s.s1), std::fabs(s.s2)});
  return m;
}

}  // namespace sas::synth
