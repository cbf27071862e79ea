#pragma once
// Compensation for the transducer on the stylus, so that the acceleration at the pen follows the
// designed ch 2 signal. An inertial actuator (voice-coil exciter, tactile transducer, linear
// resonant actuator) is a mass on a spring driven by the coil's force; the housing (the pen) feels
// the reaction of the moving mass, so its acceleration per unit drive is a second-order high-pass
// with a resonance:
//     A(s) = s² / (s² + s ω0/Q + ω0²)        (ω0 = 2π resonance_hz, Q the datasheet's Qms/Qts)
// Below ω0 it falls at 12 dB/octave, at ω0 it peaks by Q. The compensation
//     C(s) = (s² + s ω0/Q + ω0²) / (s² + s ωL/QL + ωL²),   ωL = 2π 30 Hz, QL = 1/√2
// cancels the actuator's poles and puts a 30 Hz Butterworth high-pass in their place: A·C is flat
// within ~1 dB from 40 Hz up, and C -> 1 far above ω0, so an exciter tuned below the skin's most
// sensitive band (~250 Hz) keeps its level there. The excursion at low frequencies is then that of
// a 30 Hz resonance: an LRA at 175 Hz is driven up to ~+24 dB at 40 Hz, which the final safety
// stage after this filter bounds at the transducer's ceiling.
//
// One biquad (transposed direct form II) by the bilinear transform. Each pair of roots is
// prewarped at its own natural frequency (tan(π f / fs)), so the zeros land exactly on the
// actuator's resonance and the poles exactly at 30 Hz; what the warping leaves is a Q a little
// high, by 2/3 (π f / fs)²: 0.3 % at 1 kHz and 48 kHz.
// resonance_hz <= 0 (or not finite): the identity, samples pass bit for bit.
// Real-time safe: Process allocates, locks and throws nothing. NaN and ±Inf in count as 0 and
// the input is clamped to ±kMaxInput, so the state of the (stable) filter stays finite.

#include <algorithm>
#include <cmath>

namespace sas::synth {

class TransducerEq {
 public:
  static constexpr double kTargetHz = 30.0;  // the corner of the compensated response
  static constexpr double kTargetQ = 0.70710678118654752;
  // Far above any sample the mix carries (full scale is 1), small enough that no state overflows.
  static constexpr double kMaxInput = 1e6;

  // Not real-time: designs the filter and clears the state. A q <= 0 (or not finite) or an
  // invalid sample rate also gives the identity; a resonance at or above 0.45 fs is taken as
  // 0.45 fs (the configuration allows at most 1 kHz).
  void Prepare(double sample_rate_hz, double resonance_hz, double q);
  void Reset();  // silence in the state
  bool active() const { return active_; }

  double Process(double x) {
    if (!active_) return x;
    const double in = std::isfinite(x) ? std::clamp(x, -kMaxInput, kMaxInput) : 0.0;
    const double y = b0_ * in + s1_;
    s1_ = b1_ * in - a1_ * y + s2_;
    s2_ = b2_ * in - a2_ * y;
    // A tail decaying after the input stopped would otherwise go on in subnormal arithmetic
    // (~100x slower on x86); 1e-30 is 600 dB under full scale.
    if (s1_ > -1e-30 && s1_ < 1e-30) s1_ = 0.0;
    if (s2_ > -1e-30 && s2_ < 1e-30) s2_ = 0.0;
    return y;
  }

 private:
  bool active_ = false;
  double b0_ = 1.0, b1_ = 0.0, b2_ = 0.0, a1_ = 0.0, a2_ = 0.0;
  double s1_ = 0.0, s2_ = 0.0;
};

}  // namespace sas::synth
