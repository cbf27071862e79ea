#pragma once
// The final safety stage: the last thing every sample passes before the device, after everything
// is mixed (texture scenes, cross-fades, spoken cues, voice playback, staff test tone and sweep).
// One look-ahead peak limiter per channel (ch 1 speaker, ch 2 transducer) with its own ceiling,
// aware of inter-sample ("true") peaks as ITU-R BS.1770-4 annex 2 measures them: 4× oversampled.
//
// How: h_p (p = 1..3) is the stage's own 4× interpolation filter (16-tap Hann-windowed sinc per
// phase). For every input sample m the stage forms B(m), the largest of |x(m)| and the three
// interpolated points between m and m + 1, and needs a gain ≤ c / B(m) on the sixteen samples
// those points are made of. The gain of a sample is the smallest need over the points it takes
// part in, and over kHold samples more on each side, so the gain is flat across any one
// interpolation window (hard part); reductions further ahead fade in linearly over the rest of
// the look-ahead (no click), and the gain recovers at most 1 / (release · fs) per sample. NaN and
// ±Inf count as 0; 1e30 is just loud. Every output sample is ≤ the ceiling exactly; inter-sample
// peaks, as another 4× interpolator (libebur128's) measures them, stayed within 0.3 dB of the
// stage's own target on white noise limited by 80 dB, so the stage aims kMarginDb under the
// ceiling it is given (tests/synth/test_safety_stage.cpp).
// Cost: the output is kDelayFrames (32 samples, 0.67 ms at 48 kHz) late; per sample and channel
// 48 multiply-adds and two short minimum searches. Real-time safe: no allocation, lock or throw.

#include <array>
#include <cstdint>

namespace sas::synth {

class SafetyStage {
 public:
  static constexpr int kTaps = 16;       // input samples per interpolated point
  static constexpr int kHold = 8;        // the hard part's extra reach on each side
  static constexpr int kLookahead = 24;  // how far ahead reductions are seen, samples
  static constexpr int kDelayFrames = kLookahead + kTaps / 2;
  static constexpr double kMarginDb = 0.5;

  // Not real-time. release_s: time for the gain to recover from 0 to 1.
  void Prepare(double sample_rate_hz, double release_s = 0.05);
  // Linear ceilings in (0, 1] (values outside are clamped). Real-time safe; takes effect at once,
  // including on the samples already in the look-ahead.
  void SetCeilings(double speaker, double transducer);
  void Reset();  // silence in the delay line, gains 1
  // One frame in place: frame[0] speaker, frame[1] transducer in; out the frame kDelayFrames
  // earlier, limited.
  void Process(float* frame);

 private:
  static constexpr int kRing = 64;  // ≥ kDelayFrames + kTaps, a power of two
  struct Channel {
    double ceiling = 1.0;  // target: the configured ceiling lowered by kMarginDb
    std::array<double, kRing> x{};
    std::array<double, kRing> bound{};
    double gain = 1.0;
    // Fast path: while every sample of an interpolation window is at most ceiling / S (S the
    // largest Σ|h_p|), its points cannot exceed the ceiling and the 48 multiply-adds are skipped;
    // while no need < 1 is in reach, so are the gain's minimum searches.
    double quiet_level = 1.0;
    std::uint32_t quiet_run = 0;      // consecutive input samples at most quiet_level
    std::uint32_t since_limited = 0;  // bounds since the last one over the ceiling
  };
  double Step(Channel& ch, double in);

  std::array<std::array<double, kTaps>, 4> taps_{};  // h_p, phase 0 unused
  double taps_abs_sum_ = 1.0;                        // S = max_p Σ_k |h_p[k]| (≥ 1)
  std::array<Channel, 2> channel_{};
  std::uint32_t n_ = 0;  // input samples taken
  double release_step_ = 1.0 / 2400.0;
};

}  // namespace sas::synth
