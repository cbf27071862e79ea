// The transducer's compensation (transducer_eq.h).
#include "synth/transducer_eq.h"

namespace sas::synth {

namespace {

// s² + s ω/q + ω² under s = K (1 - z⁻¹) / (1 + z⁻¹), K = 2 fs, times (1 + z⁻¹)² / K²: the
// coefficients of 1, z⁻¹, z⁻². With ω prewarped to K tan(ω T / 2), ω / K is t = tan(π f / fs).
// Numerator and denominator share K, so their ratio is the transformed C(s) with no other scale.
struct Quadratic {
  double c0, c1, c2;
};

Quadratic Bilinear(double t, double q) {
  return {1.0 + t / q + t * t, 2.0 * (t * t - 1.0), 1.0 - t / q + t * t};
}

}  // namespace

void TransducerEq::Prepare(double sample_rate_hz, double resonance_hz, double q) {
  active_ = sample_rate_hz > 0.0 && std::isfinite(sample_rate_hz) && resonance_hz > 0.0 &&
            std::isfinite(resonance_hz) && q > 0.0 && std::isfinite(q);
  b0_ = 1.0;
  b1_ = b2_ = a1_ = a2_ = 0.0;
  Reset();
  if (!active_) return;
  const double f0 = std::min(resonance_hz, 0.45 * sample_rate_hz);
  const double fl = std::min(kTargetHz, 0.45 * sample_rate_hz);
  // The zeros sit on the actuator's poles; the poles are the 30 Hz Butterworth's.
  const Quadratic zeros = Bilinear(std::tan(M_PI * f0 / sample_rate_hz), q);
  const Quadratic poles = Bilinear(std::tan(M_PI * fl / sample_rate_hz), kTargetQ);
  b0_ = zeros.c0 / poles.c0;
  b1_ = zeros.c1 / poles.c0;
  b2_ = zeros.c2 / poles.c0;
  a1_ = poles.c1 / poles.c0;
  a2_ = poles.c2 / poles.c0;
}

void TransducerEq::Reset() {
  s1_ = 0.0;
  s2_ = 0.0;
}

}  // namespace sas::synth
