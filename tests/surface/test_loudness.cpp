// Loudness measures (surface/loudness.h) against ITU-R BS.1770-4: its 48 kHz K-weighting
// coefficient table and its calibration statement (a 0 dBFS 1 kHz sine in one channel reads
// -3.01 LKFS), plus the RMS measure on signals whose RMS is known in closed form.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "surface/loudness.h"

using sas::surface::KWeightedLoudnessDb;
using sas::surface::KWeightingFilters;
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

}  // namespace

TEST_CASE("K-weighting filters at 48 kHz equal the BS.1770 coefficient table", "[surface]") {
  const auto f = KWeightingFilters(48000.0);
  // ITU-R BS.1770-4, Annex 1, tables 1 and 2.
  CHECK(f[0].b0 == Approx(1.53512485958697).epsilon(1e-9));
  CHECK(f[0].b1 == Approx(-2.69169618940638).epsilon(1e-9));
  CHECK(f[0].b2 == Approx(1.19839281085285).epsilon(1e-9));
  CHECK(f[0].a1 == Approx(-1.69065929318241).epsilon(1e-9));
  CHECK(f[0].a2 == Approx(0.73248077421585).epsilon(1e-9));
  CHECK(f[1].b0 == 1.0);
  CHECK(f[1].b1 == -2.0);
  CHECK(f[1].b2 == 1.0);
  CHECK(f[1].a1 == Approx(-1.99004745483398).epsilon(1e-9));
  CHECK(f[1].a2 == Approx(0.99007225036621).epsilon(1e-9));
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
