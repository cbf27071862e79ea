#pragma once
// The explicit reference the contact schemes are measured against: contact solved the way the
// Sound Design Toolkit (SDT) solves it, written here from its published description (Avanzini &
// Rocchesso, DAFx 2001; Papetti, Avanzini & Rocchesso, IEEE TASLP 19(7), 2011; the SDT manual),
// for the benchmark only. Per sample, in this order:
//   1. each body is a set of modes discretised by impulse invariance: the sampled impulse response
//      e^{-g t} sin(w t) / (m w) gives p[n+1] = b1 F[n] - a1 p[n] - a2 p[n-1] (one sample of delay
//      from force to position), and the velocity is the exact derivative of the free damped
//      sinusoid through the last two positions, v[n+1] = b0v p[n+1] + b1v p[n]. A point mass is
//      the limit w, g -> 0: central differences and a backward-difference velocity;
//   2. the contact force is explicit in the current state: impact f = k x^α (1 + μ ẋ) for x > 0
//      (no clamp against a pulling force), friction the elasto-plastic bristle law with a
//      forward-Euler bristle update and the force from the bristle state before it;
//   3. passivity guard: the bodies' energy after the step under the candidate force (gain-weighted
//      Σ ½(K p² + m v²)) may exceed their energy without it only by what the contact has stored
//      (0 after an impact separates; every sample for friction); otherwise the force is bisected
//      towards 0 until the excess is within 0.1 % of the energy (relative), at most 50 times, and
//      what is left below becomes the stored energy;
//   4. +f on the first body, -f on the second; both step.
// SDT weights each mode by its pickup gain, both for sharing the force and for the position,
// velocity and energy at the contact; here every mode takes the whole contact force with its own
// modal mass at the contact point (the synth's parameterisation of the same driving-point
// physics), so the reference and the synth simulate the same bodies.
// Passes over the modes are fused where the algorithm allows it: the reference should be as cheap
// as the method permits, so a comparison with it is about the method, not the implementation.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace sas::bench {

// A body of up to kMax impulse-invariant modes (or one inertial mass), contact pickup only.
class SdtBody {
 public:
  static constexpr int kMax = 64;

  // Mode i: frequency (Hz, 0 for a free mass), amplitude decay time constant (s, exp(-t/decay);
  // SDT's "decay" is twice it; 0: undamped), modal mass at the contact (kg), output gain.
  void Set(int count, const double* freq_hz, const double* decay_s, const double* mass_kg,
           const double* out_gain, double fs_hz) {
    n_ = count;
    const double t = 1.0 / fs_hz;
    for (int i = 0; i < n_; ++i) {
      const double w = 2.0 * std::numbers::pi * freq_hz[i];
      const double wt = w * t;
      const double g = decay_s[i] > 0.0 ? 1.0 / decay_s[i] : 0.0;
      const double r = std::exp(-g * t);
      const double sinc = wt > 0.0 ? std::sin(wt) / wt : 1.0;
      b1_[i] = r * sinc * t * t / mass_kg[i];
      a1_[i] = -2.0 * r * std::cos(wt);
      a2_[i] = r * r;
      b0v_[i] = std::cos(wt) / (t * sinc) - g;
      b1v_[i] = -r / (t * sinc);
      k_[i] = w * w * mass_kg[i];
      m_[i] = mass_kg[i];
      out_[i] = out_gain[i];
    }
    Reset();
  }
  void Reset() {
    p0_.fill(0.0);
    p1_.fill(0.0);
    v_.fill(0.0);
  }
  // A free mass (mode 0) placed at p with velocity v (consistent previous position).
  void Place(double p, double v, double t) {
    p0_[0] = p;
    p1_[0] = p - v * t;
    v_[0] = v;
  }
  double Position() const {
    double s = 0.0;
    for (int i = 0; i < n_; ++i) s += p0_[i];
    return s;
  }
  double Velocity() const {
    double s = 0.0;
    for (int i = 0; i < n_; ++i) s += v_[i];
    return s;
  }
  double Output() const {  // Σ output gain · modal velocity
    double s = 0.0;
    for (int i = 0; i < n_; ++i) s += out_[i] * v_[i];
    return s;
  }
  // The energy the body would have after this step under force f (at the contact pickup).
  double PredictEnergy(double f) const {
    double e = 0.0;
    for (int i = 0; i < n_; ++i) {
      const double p = b1_[i] * f - a1_[i] * p0_[i] - a2_[i] * p1_[i];
      const double v = b0v_[i] * p + b1v_[i] * p0_[i];
      e += 0.5 * (k_[i] * p * p + m_[i] * v * v);
    }
    return e;
  }
  void Step(double f) {
    for (int i = 0; i < n_; ++i) {
      const double p = b1_[i] * f - a1_[i] * p0_[i] - a2_[i] * p1_[i];
      v_[i] = b0v_[i] * p + b1v_[i] * p0_[i];
      p1_[i] = p0_[i];
      p0_[i] = p;
    }
  }
  int count() const { return n_; }

 private:
  int n_ = 0;
  std::array<double, kMax> b1_{}, a1_{}, a2_{}, b0v_{}, b1v_{}, k_{}, m_{}, out_{};
  std::array<double, kMax> p0_{}, p1_{}, v_{};
};

// The passivity guard (step 3 above): the force that keeps the bodies' predicted energy within
// what the contact holds; `stored` is updated. Counts bisection iterations in *iterations.
inline double GuardForce(const SdtBody& first, const SdtBody& second, double f, double* stored,
                         int* iterations) {
  constexpr double kMaxError = 0.001;
  constexpr int kMaxIterations = 50;
  const double h = first.PredictEnergy(0.0) + second.PredictEnergy(0.0) + *stored;
  double w = first.PredictEnergy(f) + second.PredictEnergy(-f) - h;
  if (w > 0.0) {
    double lo = 0.0, hi = f;
    int count = 0;
    while ((w > 0.0 || w < -kMaxError * h) && count < kMaxIterations) {
      f = 0.5 * (lo + hi);
      w = first.PredictEnergy(f) + second.PredictEnergy(-f) - h;
      (w < 0.0 ? lo : hi) = f;
      ++count;
    }
    *iterations += count;
  }
  *stored = -w;
  return f;
}

// Hunt–Crossley impact of a probe (second body: one free mass moving towards +) on a first body
// (a rigid wall when it has no modes). Compression x = p_probe - p_body.
struct SdtImpact {
  double k = 1e8, mu = 0.5, alpha = 1.5;
  double stored = 0.0;
  int guard_iterations = 0;

  // One sample; returns the force on the first body.
  double Step(SdtBody& body, SdtBody& probe) {
    const double x = probe.Position() - body.Position();
    double f = 0.0;
    if (x <= 0.0) {
      stored = 0.0;
    } else {
      const double xdot = probe.Velocity() - body.Velocity();
      f = k * std::pow(x, alpha) * (1.0 + mu * xdot);
    }
    f = GuardForce(body, probe, f, &stored, &guard_iterations);
    body.Step(f);
    probe.Step(-f);
    return f;
  }
};

// Elasto-plastic friction between a rubbing probe (second body, driven by an external force) and
// the first body; v = relative velocity along the stroke (second minus first).
struct SdtFriction {
  double fn = 1.0, sigma0 = 1000, sigma1 = 10, sigma2 = 10, sigma3 = 0.0;
  double mu_s = 0.8, mu_d = 0.2, v_s = 0.1, c_ba = 0.1;
  double z = 0.0;
  double t = 1.0 / 48000.0;
  double stored = 0.0;
  int guard_iterations = 0;
  std::uint64_t noise = 0x9e3779b97f4a7c15ull;

  double Noise() {  // uniform in [-1, 1)
    noise ^= noise << 13;
    noise ^= noise >> 7;
    noise ^= noise << 17;
    return static_cast<double>(noise >> 11) * (2.0 / 9007199254740992.0) - 1.0;
  }
  double Force(double v) {
    if (fn <= 0.0) {
      z = 0.0;
      return 0.0;
    }
    const double fc = mu_d * fn, fs = mu_s * fn;
    const double ratio = v / v_s;
    const double sgn_v = (v > 0.0) - (v < 0.0), sgn_z = (z > 0.0) - (z < 0.0);
    const double zss = sgn_v * (fc + (fs - fc) * std::exp(-ratio * ratio)) / sigma0;
    const double zba = sgn_v * c_ba * fc / sigma0;
    double alpha_z = 1.0;
    if (sgn_v != sgn_z || std::fabs(z) < std::fabs(zba)) {
      alpha_z = 0.0;
    } else if (std::fabs(z) < std::fabs(zss)) {
      alpha_z = 0.5 + 0.5 * std::sin(std::numbers::pi * (z - 0.5 * (zss + zba)) / (zss - zba));
    }
    double dz = v * (1.0 - alpha_z * z / zss);
    if (!std::isnormal(dz)) dz = 0.0;
    const double w = sigma3 > 0.0 ? Noise() * std::sqrt(std::fabs(v) * fn) : 0.0;
    const double f = sigma0 * z + sigma1 * dz + sigma2 * v + sigma3 * w;
    z += dz * t;
    return f;
  }
  // One sample. The hand imposes the probe's velocity each sample (SDT sets the exciter's
  // velocity from outside the same way), so the probe's kinetic energy is what the guard lets
  // flow into the body.
  double Step(SdtBody& body, SdtBody& probe, double probe_velocity) {
    probe.Place(body.Position(), probe_velocity, t);
    const double v = probe.Velocity() - body.Velocity();
    stored = 0.0;
    double f = Force(v);
    f = GuardForce(body, probe, f, &stored, &guard_iterations);
    body.Step(f);
    probe.Step(-f);
    return f;
  }
};

}  // namespace sas::bench
