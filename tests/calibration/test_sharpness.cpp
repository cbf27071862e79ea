// The loudness and sharpness meter (calibration/sharpness.h) against the standards' and the
// textbook's values: ISO 532-1:2017 annex B (worked examples), the definitions of the sone and the
// acum, the doubling of loudness per 10 phon (Zwicker & Fastl, Psychoacoustics, 3rd ed., ch. 8)
// and DIN 45692:2009 annex A (the sharpness of critical-band noises and of high-pass noises).
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>
#include <random>
#include <span>
#include <vector>

#include "calibration/sharpness.h"

namespace {

using sas::kiosk::kFullScaleDbSpl;
using sas::kiosk::kLoudnessBands;

constexpr double kFs = 48000.0;

std::vector<float> Tone(double hz, double db_spl, double seconds = 1.0) {
  const double amplitude = std::sqrt(2.0) * std::pow(10.0, (db_spl - kFullScaleDbSpl) / 20.0);
  std::vector<float> x(static_cast<std::size_t>(seconds * kFs));
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] = static_cast<float>(amplitude *
                              std::sin(2.0 * std::numbers::pi * hz * static_cast<double>(i) / kFs));
  }
  return x;
}

// Noise with a flat spectrum from lo_hz to hi_hz (random phases, every 1 Hz bin of a 1 s
// period), at RMS 1.
std::vector<float> BandNoise(double lo_hz, double hi_hz, unsigned seed) {
  const int n = static_cast<int>(kFs);
  std::mt19937 rng(seed);
  cv::Mat spectrum = cv::Mat::zeros(1, n, CV_64FC2);
  for (int k = 1; k < n / 2; ++k) {
    const double f = k * kFs / n;
    if (f < lo_hz || f > hi_hz) continue;
    const double phase = 2.0 * std::numbers::pi * (static_cast<double>(rng()) / 4294967296.0);
    spectrum.at<cv::Vec2d>(0, k) = {std::cos(phase), std::sin(phase)};
    spectrum.at<cv::Vec2d>(0, n - k) = {std::cos(phase), -std::sin(phase)};
  }
  cv::Mat signal;
  cv::dft(spectrum, signal, cv::DFT_INVERSE | cv::DFT_REAL_OUTPUT);
  std::vector<float> x(static_cast<std::size_t>(n));
  double sum = 0.0;
  for (int i = 0; i < n; ++i) sum += signal.at<double>(0, i) * signal.at<double>(0, i);
  const double scale = 1.0 / std::sqrt(sum / n);
  for (int i = 0; i < n; ++i)
    x[static_cast<std::size_t>(i)] = static_cast<float>(scale * signal.at<double>(0, i));
  return x;
}

std::array<double, kLoudnessBands> Shifted(std::array<double, kLoudnessBands> levels, double db) {
  for (double& l : levels) l += db;
  return levels;
}

// The band levels of `x` shifted so that its loudness is `sone` (bisection on the level: the
// DIN 45692 test sounds are set to 4 sone, the loudness of the 1 kHz reference at 60 dB).
std::array<double, kLoudnessBands> AtLoudness(const std::vector<float>& x, double sone) {
  const auto levels = sas::kiosk::ThirdOctaveLevelsDbSpl(x, kFs, kFullScaleDbSpl);
  double lo = -60.0, hi = 60.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (sas::kiosk::StationaryLoudness(Shifted(levels, mid)).total_sone < sone) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return Shifted(levels, 0.5 * (lo + hi));
}

// Zwicker's critical bands (Zwicker & Fastl, table 6.1): band z spans kEdgeHz[z] .. kEdgeHz[z+1].
constexpr std::array<double, 25> kEdgeHz = {0,    100,  200,  300,  400,  510,   630,  770,  920,
                                            1080, 1270, 1480, 1720, 2000, 2320,  2700, 3150, 3700,
                                            4400, 5300, 6400, 7700, 9500, 12000, 15500};

}  // namespace

TEST_CASE(
    "loudness meter: a tone's band level is its SPL, its neighbours are well below, and a flat "
    "spectrum rises 1 dB per band",
    "[dsp][loudness]") {
  const auto tone = sas::kiosk::ThirdOctaveLevelsDbSpl(Tone(1000.0, 60.0), kFs, kFullScaleDbSpl);
  CHECK(tone[16] == Approx(60.0).margin(0.1));  // 1 kHz is band 16
  CHECK(tone[15] < 50.0);                       // a third-octave filter's skirt, one band away
  CHECK(tone[17] < 50.0);
  CHECK(tone[14] < 30.0);  // two bands away
  CHECK(tone[18] < 30.0);
  // An impulse has a flat power spectrum, and band b is 10^0.1 times wider than band b-1
  // (constant relative bandwidth): +1 dB per band.
  std::vector<float> impulse(48000, 0.0f);
  impulse[24000] = 1.0f;
  const auto flat = sas::kiosk::ThirdOctaveLevelsDbSpl(impulse, kFs, kFullScaleDbSpl);
  for (int b = 1; b < kLoudnessBands; ++b) {
    INFO("band " << b);
    CHECK(flat[static_cast<std::size_t>(b)] - flat[static_cast<std::size_t>(b - 1)] ==
          Approx(1.0).margin(0.2));
  }
}

TEST_CASE("loudness meter: ISO 532-1 annex B.2 test signal 1 (machinery noise) is 83.3 sone",
          "[dsp][loudness]") {
  // The standard's third-octave levels (dB SPL, 25 Hz .. 12.5 kHz) and its result, 83.296 sone.
  const std::array<double, kLoudnessBands> levels = {-60, -60, 78, 79, 89, 72, 80, 89, 75, 87,
                                                     85,  79,  86, 80, 71, 70, 72, 71, 72, 74,
                                                     69,  65,  67, 77, 68, 58, 45, 30};
  CHECK(sas::kiosk::StationaryLoudness(levels).total_sone == Approx(83.296).epsilon(0.005));
}

TEST_CASE(
    "loudness meter: a 1 kHz tone is 1 sone at 40 dB SPL and 4 sone at 60 dB (ISO 532-1 annex "
    "B.3: 4.019), and each 10 dB above doubles it",
    "[dsp][loudness]") {
  const auto sone = [](double db) {
    return sas::kiosk::LoudnessSone(Tone(1000.0, db), kFs, kFullScaleDbSpl);
  };
  // The sone is defined by this tone; 5 % is the tolerance ISO 532-1 gives implementations on
  // its test signals.
  CHECK(sone(40.0) == Approx(1.0).epsilon(0.05));
  CHECK(sone(60.0) == Approx(4.019).epsilon(0.05));
  for (const double db : {50.0, 60.0, 70.0, 80.0}) {
    INFO(db << " dB");
    CHECK(sone(db) / sone(db - 10.0) == Approx(2.0).epsilon(0.1));
    // For a 1 kHz tone the loudness level is its SPL, by definition of the phon.
    CHECK(sas::kiosk::LoudnessLevelPhon(sone(db)) == Approx(db).margin(1.5));
  }
}

TEST_CASE("sharpness: critical-band noise at 1 kHz and 60 dB SPL is 1 acum (DIN 45692)",
          "[dsp][loudness]") {
  std::vector<float> x = BandNoise(920.0, 1080.0, 1);
  const float gain = static_cast<float>(std::pow(10.0, (60.0 - kFullScaleDbSpl) / 20.0));
  for (float& v : x) v *= gain;
  CHECK(sas::kiosk::Sharpness(x, kFs, kFullScaleDbSpl) == Approx(1.0).margin(0.05));
}

TEST_CASE(
    "sharpness: critical-band noises at 4 sone match DIN 45692 table A.2 and rise with their "
    "centre from 250 Hz to 10.5 kHz",
    "[dsp][loudness]") {
  // DIN 45692:2009 table A.2: one critical band wide, centred at 2.5 .. 22.5 Bark.
  constexpr std::array<double, 21> kAcum = {0.38, 0.49, 0.60, 0.71, 0.82, 0.93, 1.00,
                                            1.13, 1.26, 1.35, 1.49, 1.64, 1.78, 2.06,
                                            2.40, 2.82, 3.48, 4.43, 5.52, 6.81, 8.55};
  double previous = 0.0;
  for (std::size_t i = 0; i < kAcum.size(); ++i) {
    const double lo = kEdgeHz[i + 2], hi = kEdgeHz[i + 3];
    const auto levels = AtLoudness(BandNoise(lo, hi, static_cast<unsigned>(10 + i)), 4.0);
    const double s = sas::kiosk::SharpnessAcum(sas::kiosk::StationaryLoudness(levels));
    INFO(lo << " - " << hi << " Hz: " << s << " acum, DIN " << kAcum[i]);
    // DIN 45692's tolerance: 5 %, or 0.05 acum where that is wider.
    CHECK(std::fabs(s - kAcum[i]) <= std::max(0.05 * kAcum[i], 0.05));
    CHECK(s > previous);
    previous = s;
  }
}

TEST_CASE(
    "sharpness: high-pass noises (lower edge 250 Hz .. 8.5 kHz, upper 10 kHz) at 4 sone match "
    "DIN 45692 table A.3 and rise with their lower edge",
    "[dsp][loudness]") {
  // DIN 45692:2009 table A.3: the lower edge at the centres of 2.5 .. 21.5 Bark.
  constexpr std::array<double, 20> kLowerHz = {250,  350,  450,  570,  700,  840,  1000,
                                               1170, 1370, 1600, 1850, 2150, 2500, 2900,
                                               3400, 4000, 4800, 5800, 7000, 8500};
  constexpr std::array<double, 20> kAcum = {2.70, 2.74, 2.78, 2.85, 2.91, 2.96, 3.05,
                                            3.12, 3.20, 3.30, 3.42, 3.53, 3.69, 3.89,
                                            4.12, 4.49, 5.04, 5.69, 6.47, 7.46};
  double previous = 0.0;
  for (std::size_t i = 0; i < kAcum.size(); ++i) {
    const auto levels =
        AtLoudness(BandNoise(kLowerHz[i], 10000.0, static_cast<unsigned>(40 + i)), 4.0);
    const double s = sas::kiosk::SharpnessAcum(sas::kiosk::StationaryLoudness(levels));
    INFO(kLowerHz[i] << " Hz - 10 kHz: " << s << " acum, DIN " << kAcum[i]);
    CHECK(std::fabs(s - kAcum[i]) <= std::max(0.05 * kAcum[i], 0.05));
    CHECK(s > previous);
    previous = s;
  }
}

TEST_CASE("sharpness: silence has no loudness and no sharpness", "[dsp][loudness]") {
  const std::vector<float> silence(4800, 0.0f);
  CHECK(sas::kiosk::LoudnessSone(silence, kFs, kFullScaleDbSpl) == 0.0);
  CHECK(sas::kiosk::Sharpness(silence, kFs, kFullScaleDbSpl) == 0.0);
}
