// The transducer's compensation (synth/transducer_eq.h), checked against the actuator itself: the
// compensated drive goes through an independent simulation of the mass on its spring (the ODE
// integrated by RK4, not the bilinear filter), and the acceleration it gives the housing must be
// flat over the skin's band, 40-400 Hz.
#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <vector>

#include "synth/transducer_eq.h"

using sas::synth::TransducerEq;

namespace {

constexpr double kFs = 48000.0;
constexpr double kPi = 3.14159265358979323846;
// Third-octave steps (ISO 266) over the band the vibration path uses.
constexpr double kBandHz[] = {40, 50, 63, 80, 100, 125, 160, 200, 250, 315, 400};

struct Actuator {
  const char* name;
  double resonance_hz;
  double q;
};
// Datasheet-typical: a linear resonant actuator (Precision Microdrives C10-100 is rated at
// 175 Hz), and a voice-coil exciter / tactile transducer.
constexpr Actuator kLra{"linear resonant actuator", 175.0, 10.0};
constexpr Actuator kExciter{"voice-coil exciter", 60.0, 2.0};

// The housing's acceleration for a drive force f (one value per sample): the moving mass (m = 1)
// on its spring and damper, x'' + (w0/Q) x' + w0^2 x = f, x relative to the housing, which feels
// the reaction -m x''. RK4 at 8 steps per sample, f linear between samples; the acceleration is
// read at each sample from the state (up to the constant -m / M of the housing's mass).
std::vector<double> HousingAcceleration(const Actuator& actuator, const std::vector<double>& f) {
  const double w0 = 2.0 * kPi * actuator.resonance_hz;
  const double c = w0 / actuator.q, k = w0 * w0;
  constexpr int kSteps = 8;
  const double h = 1.0 / (kFs * kSteps);
  double x = 0.0, v = 0.0;
  std::vector<double> a(f.size());
  for (std::size_t n = 0; n < f.size(); ++n) {
    a[n] = f[n] - c * v - k * x;
    if (n + 1 == f.size()) break;
    const double f0 = f[n], df = f[n + 1] - f[n];
    for (int s = 0; s < kSteps; ++s) {
      const auto drive = [&](double step) { return f0 + df * step / kSteps; };
      const auto accel = [&](double xx, double vv, double force) {
        return force - c * vv - k * xx;
      };
      const double fa = drive(s), fm = drive(s + 0.5), fb = drive(s + 1.0);
      const double k1x = v, k1v = accel(x, v, fa);
      const double k2x = v + 0.5 * h * k1v, k2v = accel(x + 0.5 * h * k1x, v + 0.5 * h * k1v, fm);
      const double k3x = v + 0.5 * h * k2v, k3v = accel(x + 0.5 * h * k2x, v + 0.5 * h * k2v, fm);
      const double k4x = v + h * k3v, k4v = accel(x + h * k3x, v + h * k3v, fb);
      x += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
      v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    }
  }
  return a;
}

// Amplitude of the sine at `hz` in y[from..], by least squares on cos, sin and a constant (the
// window need not hold whole periods).
double SineAmplitude(const std::vector<double>& y, std::size_t from, double hz) {
  double m[3][4] = {};
  for (std::size_t n = from; n < y.size(); ++n) {
    const double phase = 2.0 * kPi * hz * static_cast<double>(n) / kFs;
    const double basis[3] = {std::cos(phase), std::sin(phase), 1.0};
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) m[i][j] += basis[i] * basis[j];
      m[i][3] += basis[i] * y[n];
    }
  }
  for (int i = 0; i < 3; ++i) {  // Gauss-Jordan; the matrix is well conditioned (near-diagonal)
    for (int r = 0; r < 3; ++r) {
      if (r == i) continue;
      const double ratio = m[r][i] / m[i][i];
      for (int col = 0; col < 4; ++col) m[r][col] -= ratio * m[i][col];
    }
  }
  return std::hypot(m[0][3] / m[0][0], m[1][3] / m[1][1]);
}

// The housing's steady-state acceleration in dB per band frequency for a unit sine drive through
// the compensation (resonance_hz 0: none). 0.25 s to settle (over 13 time constants of the
// slowest mode, the LRA's 2Q/w0 = 18 ms), then 0.25 s measured.
std::vector<double> AccelerationDb(const Actuator& actuator, double eq_resonance_hz) {
  const auto settle = static_cast<std::size_t>(0.25 * kFs);
  const std::size_t total = 2 * settle;
  std::vector<double> db;
  for (const double hz : kBandHz) {
    TransducerEq eq;
    eq.Prepare(kFs, eq_resonance_hz, actuator.q);
    std::vector<double> drive(total);
    for (std::size_t n = 0; n < total; ++n) {
      drive[n] = eq.Process(std::sin(2.0 * kPi * hz * static_cast<double>(n) / kFs));
    }
    db.push_back(20.0 *
                 std::log10(SineAmplitude(HousingAcceleration(actuator, drive), settle, hz)));
  }
  return db;
}

// The largest |level - mean level| in dB.
double MaxDeviationDb(const std::vector<double>& db) {
  double mean = 0.0;
  for (const double d : db) mean += d / static_cast<double>(db.size());
  double worst = 0.0;
  for (const double d : db) worst = std::max(worst, std::fabs(d - mean));
  return worst;
}

// The actuator's own response, |A(jw)| = w^2 / |w0^2 - w^2 + j w w0 / Q|, in dB.
double ActuatorDb(const Actuator& actuator, double hz) {
  const double r = hz / actuator.resonance_hz;
  return 20.0 * std::log10(r * r / std::hypot(1.0 - r * r, r / actuator.q));
}

// The design's target, A·C: a 30 Hz Butterworth high-pass (2nd order), in dB.
double TargetDb(double hz) {
  const double r = hz / TransducerEq::kTargetHz;
  return 20.0 * std::log10(r * r / std::sqrt(1.0 + r * r * r * r));
}

}  // namespace

TEST_CASE(
    "transducer eq: through a simulated actuator (RK4 of its ODE), the compensated acceleration "
    "at the pen is flat within 3 dB over 40-400 Hz for an LRA and an exciter, and is the 30 Hz "
    "Butterworth high-pass designed",
    "[dsp]") {
  for (const Actuator& actuator : {kLra, kExciter}) {
    const auto db = AccelerationDb(actuator, actuator.resonance_hz);
    const double deviation = MaxDeviationDb(db);
    INFO(actuator.name << ": compensated, max deviation from the mean " << deviation << " dB");
    CHECK(deviation <= 3.0);
    for (std::size_t i = 0; i < db.size(); ++i) {
      INFO(kBandHz[i] << " Hz: " << db[i] << " dB, the target " << TargetDb(kBandHz[i]) << " dB");
      CHECK(db[i] == Approx(TargetDb(kBandHz[i])).margin(0.1));
    }
  }
}

TEST_CASE(
    "transducer eq: without compensation the same simulated actuators are far from flat over "
    "40-400 Hz (the check above can fail)",
    "[dsp]") {
  const auto lra = AccelerationDb(kLra, 0.0);
  INFO("LRA uncompensated: max deviation " << MaxDeviationDb(lra) << " dB");
  CHECK(MaxDeviationDb(lra) > 10.0);  // -26 dB at 40 Hz against +13 dB at 160 Hz
  const auto exciter = AccelerationDb(kExciter, 0.0);
  INFO("exciter uncompensated: max deviation " << MaxDeviationDb(exciter) << " dB");
  CHECK(MaxDeviationDb(exciter) > 3.0);
  // The simulation is the actuator the compensation assumes: its steady state is A(jw).
  for (std::size_t i = 0; i < std::size(kBandHz); ++i) {
    INFO(kBandHz[i] << " Hz");
    CHECK(lra[i] == Approx(ActuatorDb(kLra, kBandHz[i])).margin(0.1));
    CHECK(exciter[i] == Approx(ActuatorDb(kExciter, kBandHz[i])).margin(0.1));
  }
}

TEST_CASE("transducer eq: far above the resonance the drive is unchanged", "[dsp]") {
  for (const double hz : {2000.0, 5000.0}) {
    TransducerEq eq;
    eq.Prepare(kFs, kExciter.resonance_hz, kExciter.q);
    std::vector<double> out(static_cast<std::size_t>(0.1 * kFs));
    for (std::size_t n = 0; n < out.size(); ++n) {
      out[n] = eq.Process(std::sin(2.0 * kPi * hz * static_cast<double>(n) / kFs));
    }
    INFO(hz << " Hz");
    CHECK(20.0 * std::log10(SineAmplitude(out, out.size() / 2, hz)) == Approx(0.0).margin(0.05));
  }
}

TEST_CASE("transducer eq: resonance 0 (the default) passes every sample bit for bit", "[dsp]") {
  TransducerEq eq;
  CHECK_FALSE(eq.active());  // unprepared: the identity too
  eq.Prepare(kFs, 0.0, 10.0);
  CHECK_FALSE(eq.active());
  constexpr double kLargest = std::numeric_limits<double>::max();
  const double samples[] = {0.0,  -0.0, 0.3, -1.0,    1e-310,   -4.9e-324, 0.123456789012345,
                            1e30, -1e6, 2e6, 1.0 / 3, 0.999999, kLargest};
  for (int round = 0; round < 3; ++round) {
    for (const double x : samples) {
      CHECK(std::bit_cast<std::uint64_t>(eq.Process(x)) == std::bit_cast<std::uint64_t>(x));
    }
  }
  for (int i = 0; i < 4800; ++i) {  // a float sine, as the player passes it
    const auto x = static_cast<double>(static_cast<float>(std::sin(0.01 * i)));
    REQUIRE(std::bit_cast<std::uint64_t>(eq.Process(x)) == std::bit_cast<std::uint64_t>(x));
  }
  // Invalid profiles are not guessed at: no compensation.
  eq.Prepare(kFs, 175.0, 0.0);
  CHECK_FALSE(eq.active());
  eq.Prepare(kFs, std::numeric_limits<double>::quiet_NaN(), 10.0);
  CHECK_FALSE(eq.active());
  eq.Prepare(kFs, 175.0, 10.0);
  CHECK(eq.active());
}

TEST_CASE(
    "transducer eq: NaN and Inf count as silence and huge inputs leave the state finite: the "
    "output is what a 0 there would have given",
    "[dsp]") {
  TransducerEq eq, reference;
  eq.Prepare(kFs, kLra.resonance_hz, kLra.q);
  reference.Prepare(kFs, kLra.resonance_hz, kLra.q);
  for (int n = 0; n < 9600; ++n) {
    const double x = 0.5 * std::sin(2.0 * kPi * 100.0 * n / kFs);
    double hostile = x;
    bool bad = true;
    switch (n % 701) {
      case 13:
        hostile = std::numeric_limits<double>::quiet_NaN();
        break;
      case 200:
        hostile = std::numeric_limits<double>::infinity();
        break;
      case 400:
        hostile = -std::numeric_limits<double>::infinity();
        break;
      default:
        bad = false;
    }
    const double got = eq.Process(hostile);
    const double want = reference.Process(bad ? 0.0 : x);
    REQUIRE(got == want);
  }
  // Loud enough to overflow a plain biquad's state (b1 x alone is -inf at 1e308).
  for (int n = 0; n < 4800; ++n) {
    const double y = eq.Process(n % 2 ? std::numeric_limits<double>::max() : -1e308);
    REQUIRE(std::isfinite(y));
  }
  double tail = 0.0;
  for (int n = 0; n < 48000; ++n) {
    const double y = eq.Process(0.0);
    REQUIRE(std::isfinite(y));
    if (n >= 47000) tail = std::max(tail, std::fabs(y));
  }
  CHECK(tail < 1e-3);  // and it comes back to rest
}
