// The vibration figures (calibration/felt.h) on signals whose answer is known without the code:
// the skin weighting follows the threshold curve it cites, a sine's crest is 3 dB and its energy
// lies where it is, a clipped sine sits at its ceiling, and the classifiers tell apart clusters
// that are apart.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "calibration/felt.h"

namespace {

constexpr double kFs = 48000.0;

std::vector<float> Sine(double hz, double amplitude, double seconds) {
  std::vector<float> x(static_cast<std::size_t>(seconds * kFs));
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] = static_cast<float>(amplitude *
                              std::sin(2.0 * std::numbers::pi * hz * static_cast<double>(i) / kFs));
  }
  return x;
}

double Db(double linear) { return 20.0 * std::log10(linear); }

}  // namespace

TEST_CASE("skin weighting: flat over the Pacinian band, falling where the threshold rises",
          "[calibration]") {
  using sas::kiosk::SkinWeightingGain;
  // In acceleration the threshold is flat from 40 to 250 Hz: within the Butterworth corners'
  // 3 dB there, within 1 dB in the middle.
  for (const double hz : {63.0, 100.0, 160.0}) {
    INFO(hz << " Hz");
    CHECK(std::fabs(Db(SkinWeightingGain(hz, kFs))) < 1.0);
  }
  CHECK(Db(SkinWeightingGain(40.0, kFs)) == Approx(-3.0).margin(0.1));
  CHECK(Db(SkinWeightingGain(250.0, kFs)) == Approx(-3.0).margin(0.1));
  // Below 40 Hz 12 dB per octave, above 250 Hz 24 dB per octave (far from the corners).
  CHECK(Db(SkinWeightingGain(5.0, kFs)) - Db(SkinWeightingGain(10.0, kFs)) ==
        Approx(-12.0).margin(0.5));
  CHECK(Db(SkinWeightingGain(2000.0, kFs)) - Db(SkinWeightingGain(1000.0, kFs)) ==
        Approx(-24.0).margin(0.5));
  // The weighted level of a signal measured through SkinWeighted agrees with the gain.
  for (const double hz : {100.0, 500.0}) {
    const auto x = Sine(hz, 0.5, 1.0);
    const auto w = sas::kiosk::SkinWeighted(x, kFs);
    double sum = 0.0;
    for (std::size_t i = w.size() / 2; i < w.size(); ++i) sum += double{w[i]} * w[i];
    const double rms = std::sqrt(sum / static_cast<double>(w.size() - w.size() / 2));
    CHECK(Db(rms / (0.5 / std::numbers::sqrt2)) == Approx(Db(SkinWeightingGain(hz, kFs))).margin(0.05));
  }
}

TEST_CASE("felt figures: a sine's crest, band and ceiling", "[calibration]") {
  const auto in_band = sas::kiosk::MeasureFelt(Sine(160.0, 0.25, 1.0), kFs, 1.0);
  CHECK(in_band.crest_db == Approx(3.01).margin(0.05));
  CHECK(in_band.band_fraction > 0.99);
  CHECK(in_band.above_1k_db < -40.0);
  CHECK(in_band.near_ceiling == 0.0);
  CHECK(in_band.skin_db == Approx(Db(0.25 / std::numbers::sqrt2)).margin(0.3));

  const auto high = sas::kiosk::MeasureFelt(Sine(1500.0, 0.25, 1.0), kFs, 1.0);
  CHECK(high.band_fraction < 0.01);
  CHECK(high.above_1k_db > -0.1);
  // 1.5 kHz is felt far less than 160 Hz at the same amplitude.
  CHECK(high.skin_db < in_band.skin_db - 30.0);

  // A sine squared off at the ceiling: most of its samples are within 1 dB of it.
  auto clipped = Sine(160.0, 4.0, 1.0);
  for (float& v : clipped) v = std::clamp(v, -0.5f, 0.5f);
  const auto squared = sas::kiosk::MeasureFelt(clipped, kFs, 0.5);
  CHECK(squared.near_ceiling > 0.8);
  CHECK(squared.crest_db < 1.0);
  // The same against a ceiling 6 dB higher: never near it.
  CHECK(sas::kiosk::MeasureFelt(clipped, kFs, 1.0).near_ceiling == 0.0);
}

TEST_CASE("felt figures: bursts are impulsive and periodic, noise is neither", "[calibration]") {
  // 10 bursts a second of a 200 Hz tone, 20 ms each, against steady noise of the same band.
  auto bursts = Sine(200.0, 0.3, 2.0);
  for (std::size_t i = 0; i < bursts.size(); ++i) {
    if (i % 4800 >= 960) bursts[i] = 0.0f;
  }
  std::mt19937 rng(7);
  std::normal_distribution<float> normal(0.0f, 0.05f);
  std::vector<float> noise(bursts.size());
  for (float& v : noise) v = normal(rng);
  const auto b = sas::kiosk::MeasureFelt(bursts, kFs, 1.0);
  const auto n = sas::kiosk::MeasureFelt(sas::kiosk::SkinWeighted(noise, kFs), kFs, 1.0);
  CHECK(b.features[11] > 0.8);  // periodicity: the bursts repeat every 100 ms
  CHECK(n.features[11] < 0.3);
  CHECK(b.features[12] > 0.5);  // quiet between the bursts
  CHECK(n.features[12] < 0.1);
  CHECK(b.features[8] > n.features[8]);  // kurtosis: impulsive
  CHECK(b.features[13] == Approx(std::log2(200.0)).margin(0.1));  // the spectrum's peak
}

TEST_CASE("felt classifiers: clusters that are apart are told apart", "[calibration]") {
  // Two labels, each two clusters (as a texture's styles are) on opposite sides: one centroid
  // per label lands between them and fails, the neighbours do not.
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(0.0, 0.3);
  std::vector<sas::kiosk::FeltFeatures> x, test_x;
  std::vector<int> label, test_label;
  const auto add = [&](double a, double b, int l, auto& xs, auto& ls) {
    sas::kiosk::FeltFeatures f{};
    f[0] = a + normal(rng);
    f[1] = b + normal(rng);
    xs.push_back(f);
    ls.push_back(l);
  };
  for (int i = 0; i < 100; ++i) {
    for (auto* xs : {&x, &test_x}) {
      auto& ls = xs == &x ? label : test_label;
      add(-2.0, -2.0, 0, *xs, ls);
      add(2.0, 2.0, 0, *xs, ls);
      add(-2.0, 2.0, 1, *xs, ls);
      add(2.0, -2.0, 1, *xs, ls);
    }
  }
  sas::kiosk::NearestNeighbours neighbours;
  neighbours.Fit(x, label);
  sas::kiosk::NearestCentroid centroid;
  centroid.Fit(x, label);
  int right = 0, centroid_right = 0;
  for (std::size_t i = 0; i < test_x.size(); ++i) {
    right += neighbours.Predict(test_x[i]) == test_label[i] ? 1 : 0;
    centroid_right += centroid.Predict(test_x[i]) == test_label[i] ? 1 : 0;
  }
  CHECK(right >= static_cast<int>(test_x.size()) * 99 / 100);
  CHECK(centroid_right < static_cast<int>(test_x.size()) * 3 / 4);
  // One cluster per label: the centroid is right too.
  sas::kiosk::FeltFeatures a{}, b{};
  a[0] = -3.0;
  b[0] = 3.0;
  centroid.Fit({a, b}, {4, 7});
  a[0] = -2.5;
  CHECK(centroid.Predict(a) == 4);
}
