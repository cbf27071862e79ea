// The character figures (calibration/character.h) on signals whose answer is known without the
// code: white noise is flat, a tone is not, a sine's crest is 3 dB, a click train has one onset
// per click.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "calibration/character.h"

namespace {

constexpr double kFs = 48000.0;

std::vector<float> Noise(double seconds, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> normal(0.0f, 0.1f);
  std::vector<float> x(static_cast<std::size_t>(seconds * kFs));
  for (float& v : x) v = normal(rng);
  return x;
}

std::vector<float> Sine(double hz, double seconds) {
  std::vector<float> x(static_cast<std::size_t>(seconds * kFs));
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] = static_cast<float>(0.5 *
                              std::sin(2.0 * std::numbers::pi * hz * static_cast<double>(i) / kFs));
  }
  return x;
}

}  // namespace

TEST_CASE("white noise is flat, a tone is not, and a tone in noise lies between") {
  const std::vector<float> noise = Noise(2.0, 1);
  // Welch's average of ~46 segments: the log of a chi-square estimate is biased low by about
  // 1 / (2 K), so even ideal white noise reads a little under 1.
  CHECK(sas::kiosk::SpectralFlatness(noise, kFs) > 0.9);
  CHECK(sas::kiosk::SpectralFlatness(noise, kFs) <= 1.0);
  std::vector<float> tone = Sine(1000.0, 2.0);
  const std::vector<float> faint = Noise(2.0, 2);
  for (std::size_t i = 0; i < tone.size(); ++i) tone[i] += 1e-3f * faint[i];
  const double tonal = sas::kiosk::SpectralFlatness(tone, kFs);
  CHECK(tonal < 0.01);
  CHECK(tonal > 0.0);
  // Pink noise (power ∝ 1/f, Voss-McCartney's sum of held random values) sits between them.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  std::vector<float> pink(static_cast<std::size_t>(2.0 * kFs));
  std::vector<float> rows(16, 0.0f);
  for (std::size_t i = 0; i < pink.size(); ++i) {
    for (std::size_t r = 0; r < rows.size(); ++r) {
      if (i % (std::size_t{1} << r) == 0) rows[r] = uniform(rng);
    }
    float sum = 0.0f;
    for (const float v : rows) sum += v;
    pink[i] = 0.05f * sum;
  }
  const double pink_flatness = sas::kiosk::SpectralFlatness(pink, kFs);
  CHECK(pink_flatness > tonal);
  CHECK(pink_flatness < 0.8);
  // Outside the band nothing counts: a 20 kHz tone over white noise is flat between 100 Hz and
  // 10 kHz.
  std::vector<float> high = Sine(20000.0, 2.0);
  for (std::size_t i = 0; i < high.size(); ++i) high[i] += noise[i];
  CHECK(sas::kiosk::SpectralFlatness(high, kFs) > 0.9);
  CHECK(sas::kiosk::SpectralFlatness(std::vector<float>(1000, 0.0f), kFs) == 0.0);
}

TEST_CASE("a sine's crest factor is 3 dB and a lone click's is its length") {
  CHECK(sas::kiosk::CrestFactorDb(Sine(440.0, 1.0)) == Approx(10.0 * std::log10(2.0)).margin(0.01));
  std::vector<float> click(10000, 0.0f);
  click[5000] = 1.0f;
  CHECK(sas::kiosk::CrestFactorDb(click) == Approx(10.0 * std::log10(10000.0)).margin(1e-6));
  CHECK(sas::kiosk::CrestFactorDb(std::vector<float>(100, 0.0f)) == 0.0);
}

TEST_CASE("a click train has one onset per click, steady noise has none") {
  for (const double rate : {4.0, 12.0, 30.0}) {
    std::vector<float> x = Noise(3.0, 4);
    for (float& v : x) v *= 1e-3f;  // a quiet floor, 60 dB under the clicks
    const auto period = static_cast<std::size_t>(kFs / rate);
    for (std::size_t start = period / 2; start + 480 < x.size(); start += period) {
      for (std::size_t i = 0; i < 480; ++i) {  // 10 ms decaying 2 kHz burst
        x[start + i] += static_cast<float>(
            std::exp(-static_cast<double>(i) / 96.0) *
            std::sin(2.0 * std::numbers::pi * 2000.0 * static_cast<double>(i) / kFs));
      }
    }
    INFO("clicks per second " << rate);
    CHECK(sas::kiosk::OnsetRatePerS(x, kFs) == Approx(rate).margin(0.7));
  }
  CHECK(sas::kiosk::OnsetRatePerS(Noise(3.0, 5), kFs) < 1.0);
}
