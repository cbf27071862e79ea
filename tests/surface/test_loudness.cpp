// Loudness measures (surface/loudness.h) against ITU-R BS.1770-4: the response of its 48 kHz
// K-weighting coefficient table and its calibration statement (a 0 dBFS 1 kHz sine in one channel
// reads -3.01 LKFS), plus the RMS measure on signals whose RMS is known in closed form.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "surface/loudness.h"

using sas::surface::KWeightedLoudnessDb;
using sas::surface::RmsDb;

namespace {

std::vector<float> Sine(double frequency_hz, double amplitude, double fs, double seconds) {
  std::vector<float> x(static_cast<std::size_t>(fs * seconds));
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] = static_cast<float>(amplitude *
                              std::sin(2.0 * std::numbers::pi * frequency_hz * double(i) / fs));
  }
  return x;
}

// The gain at `hz` of BS.1770-4's K-weighting at 48 kHz (Annex 1, tables 1 and 2: the
// pre-filter shelf and the RLB high-pass biquads), from the standard's coefficients.
double KWeightingGainDb48k(double hz) {
  const std::array<std::array<double, 5>, 2> table = {{
      {1.53512485958697, -2.69169618940638, 1.19839281085285, -1.69065929318241, 0.73248077421585},
      {1.0, -2.0, 1.0, -1.99004745483398, 0.99007225036621},
  }};
  const std::complex<double> z1 = std::polar(1.0, -2.0 * std::numbers::pi * hz / 48000.0);
  std::complex<double> h = 1.0;
  for (const auto& c : table)
    h *= (c[0] + c[1] * z1 + c[2] * z1 * z1) / (1.0 + c[3] * z1 + c[4] * z1 * z1);
  return 20.0 * std::log10(std::abs(h));
}

// BS.1770 loudness of a steady sine of `amplitude` at `hz` (48 kHz): mean square a^2 / 2 through
// the K-weighting, plus -0.691 dB.
double SineLoudness48k(double hz, double amplitude) {
  return -0.691 + 10.0 * std::log10(amplitude * amplitude / 2.0) + KWeightingGainDb48k(hz);
}

}  // namespace

TEST_CASE(
    "a sine's loudness at 48 kHz follows the response of BS.1770's K-weighting coefficient table",
    "[surface]") {
  const double fs = 48000.0;
  for (const double hz : {25.0, 60.0, 250.0, 1000.0, 2000.0, 5000.0, 12000.0}) {
    const auto x = Sine(hz, 0.25, fs, 2.0);
    // The last second: whole periods of every frequency above, after the filters have settled.
    INFO(hz << " Hz");
    CHECK(KWeightedLoudnessDb(x, fs, x.size() / 2, x.size()) ==
          Approx(SineLoudness48k(hz, 0.25)).margin(0.005));
  }
}

TEST_CASE("a window is measured over the whole milliseconds that end where it ends", "[surface]") {
  // 494 frames of a 1 kHz sine at 48 kHz are 10.29 periods, whose mean square depends on the
  // phase the window starts at (up to +-0.03 dB); the 10 ms ending at the same frame are whole
  // periods and read the steady-sine loudness at every phase.
  const double fs = 48000.0;
  const auto x = Sine(1000.0, 0.5, fs, 1.0);
  for (std::size_t to = 24000; to < 24048; to += 5) {
    INFO("window ends at frame " << to);
    CHECK(KWeightedLoudnessDb(x, fs, to - 494, to) ==
          Approx(SineLoudness48k(1000.0, 0.5)).margin(1e-3));
  }
  // Shorter than half a millisecond, empty or past the end: nothing to measure.
  CHECK(KWeightedLoudnessDb(x, fs, 1000, 1020) == sas::surface::kSilenceDb);
  CHECK(KWeightedLoudnessDb(x, fs, 1000, 1000) == sas::surface::kSilenceDb);
  CHECK(KWeightedLoudnessDb(x, fs, x.size(), x.size() + 480) == sas::surface::kSilenceDb);
}

TEST_CASE("a full-scale 1 kHz sine reads -3.01 LUFS at 48 and 44.1 kHz", "[surface]") {
  for (double fs : {48000.0, 44100.0}) {
    const auto x = Sine(1000.0, 1.0, fs, 2.0);
    // Skip the first half second: the window starts after the filters have settled.
    const double loudness = KWeightedLoudnessDb(x, fs, x.size() / 4, x.size());
    CHECK(loudness == Approx(-3.01).margin(0.02));
  }
}

TEST_CASE("K-weighting lifts 4 kHz by about 4 dB and cuts 20 Hz relative to 1 kHz", "[surface]") {
  const double fs = 48000.0;
  const auto at = [&](double hz) {
    const auto x = Sine(hz, 0.1, fs, 2.0);
    return KWeightedLoudnessDb(x, fs, x.size() / 2, x.size());
  };
  const double ref = at(1000.0);
  CHECK(at(4000.0) - ref == Approx(3.3).margin(0.5));  // shelf nearly at its +4 dB plateau
  CHECK(at(20.0) - ref < -3.0);                        // RLB high-pass
}

TEST_CASE("RMS in dB matches the closed form and reads one channel of interleaved data",
          "[surface]") {
  const auto x = Sine(250.0, 0.5, 48000.0, 1.0);  // whole periods: RMS = 0.5 / sqrt 2
  CHECK(RmsDb(x, 0, x.size()) == Approx(20.0 * std::log10(0.5 / std::sqrt(2.0))).margin(1e-3));
  std::vector<float> interleaved;
  for (float v : x) {
    interleaved.push_back(0.0f);
    interleaved.push_back(v);
  }
  const std::span<const float> all(interleaved);
  CHECK(RmsDb(all.subspan(1), 0, x.size(), 2) == Approx(RmsDb(x, 0, x.size())).margin(1e-9));
  CHECK(RmsDb(all, 0, x.size(), 2) == sas::surface::kSilenceDb);
  CHECK(RmsDb(x, 10, 10) == sas::surface::kSilenceDb);  // empty window
}

TEST_CASE(
    "the loudness of many windows from one filtering pass equals each window measured on its own, "
    "and a closed-form sine's level in each",
    "[surface]") {
  // Interleaved stereo: a 1 kHz sine whose amplitude steps 0.5 -> 0.125 -> 1 in three 0.5 s parts
  // on channel 1; channel 2 holds noise-free junk that must not leak in.
  const double fs = 48000.0;
  std::vector<float> mono;
  for (const double amplitude : {0.5, 0.125, 1.0}) {
    const auto part = Sine(1000.0, amplitude, fs, 0.5);
    mono.insert(mono.end(), part.begin(), part.end());
  }
  std::vector<float> stereo(2 * mono.size());
  for (std::size_t i = 0; i < mono.size(); ++i) {
    stereo[2 * i] = mono[i];
    stereo[2 * i + 1] = 0.9f;
  }
  // One window in each part, past the previous part's filter transient; a gap between windows;
  // the last runs past the end (clamped).
  const std::vector<sas::surface::FrameWindow> windows = {
      {2400, 24000}, {26400, 48000}, {50400, 60000}, {62400, 90000}};
  const auto many = KWeightedLoudnessDb(stereo, fs, windows, 2);
  REQUIRE(many.size() == windows.size());
  for (std::size_t w = 0; w < windows.size(); ++w) {
    CHECK(many[w] ==
          Approx(KWeightedLoudnessDb(stereo, fs, windows[w].from, windows[w].to, 2)).margin(1e-9));
  }
  // A 1 kHz sine of amplitude a reads -3.01 + 20 log10(a) (the BS.1770 calibration point).
  CHECK(many[0] == Approx(-3.01 + 20.0 * std::log10(0.5)).margin(0.02));
  CHECK(many[1] == Approx(-3.01 + 20.0 * std::log10(0.125)).margin(0.02));
  CHECK(many[2] == Approx(-3.01).margin(0.02));
  CHECK(many[3] == Approx(-3.01).margin(0.02));
  // Overlapping or out-of-order windows give the same answers.
  const std::vector<sas::surface::FrameWindow> overlapping = {{26400, 48000}, {2400, 30000}};
  const auto apart = KWeightedLoudnessDb(stereo, fs, overlapping, 2);
  REQUIRE(apart.size() == 2);
  CHECK(apart[0] == Approx(many[1]).margin(1e-9));
  CHECK(apart[1] == Approx(KWeightedLoudnessDb(stereo, fs, 2400, 30000, 2)).margin(1e-9));
}
