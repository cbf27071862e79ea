// The final safety stage (synth/safety_stage.h): whatever goes in, no sample and no 4×
// oversampled peak (measured by libebur128) comes out above the ceiling; what is below the
// ceiling comes out unchanged, only late by kDelayFrames.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "support/true_peak.h"
#include "synth/safety_stage.h"

using sas::synth::SafetyStage;

namespace {

constexpr double kFs = 48000.0;

std::vector<float> Run(SafetyStage& stage, std::vector<float> stereo) {
  for (std::size_t i = 0; i + 1 < stereo.size(); i += 2) stage.Process(&stereo[i]);
  return stereo;
}

double SamplePeak(const std::vector<float>& stereo, int channel) {
  double peak = 0.0;
  for (std::size_t i = static_cast<std::size_t>(channel); i < stereo.size(); i += 2) {
    peak = std::max(peak, static_cast<double>(std::fabs(stereo[i])));
  }
  return peak;
}

// Hostile inputs, both channels: name and generator.
struct Source {
  const char* name;
  double (*sample)(int n, std::mt19937& rng);
};

const Source kSources[] = {
    {"1e30 constant", [](int, std::mt19937&) { return 1e30; }},
    {"1e30 alternating (all energy at Nyquist)",
     [](int n, std::mt19937&) { return n % 2 ? 1e30 : -1e30; }},
    {"NaN and Inf bursts in a full-scale sine",
     [](int n, std::mt19937&) {
       if (n % 97 == 0) return std::numeric_limits<double>::quiet_NaN();
       if (n % 89 == 0) return std::numeric_limits<double>::infinity();
       return std::sin(2.0 * M_PI * 1000.0 * n / kFs);
     }},
    {"full-scale sine at fs/4 + 45 degrees (samples at 0.707, peaks between them at 1)",
     [](int n, std::mt19937&) { return std::sin(M_PI / 2.0 * n + M_PI / 4.0); }},
    {"white noise at +40 dBFS",
     [](int, std::mt19937& rng) { return std::normal_distribution<double>(0.0, 100.0)(rng); }},
    {"full-scale sweep 40 Hz - 20 kHz",
     [](int n, std::mt19937&) {
       const double t = n / kFs;
       return std::sin(2.0 * M_PI * (40.0 * t + 0.5 * (20000.0 - 40.0) * t * t));
     }},
    {"clicks: single 1e6 samples in silence",
     [](int n, std::mt19937&) { return n % 1000 == 0 ? 1e6 : 0.0; }},
};

}  // namespace

TEST_CASE(
    "safety stage: no hostile source gets a sample or a 4x oversampled peak above either "
    "channel's ceiling",
    "[dsp][safety]") {
  for (const double speaker_db : {-1.0, -6.0}) {
    for (const double transducer_db : {0.0, -20.0}) {
      const double speaker = std::pow(10.0, speaker_db / 20.0);
      const double transducer = std::pow(10.0, transducer_db / 20.0);
      for (const Source& source : kSources) {
        SafetyStage stage;
        stage.Prepare(kFs);
        stage.SetCeilings(speaker, transducer);
        std::mt19937 rng(7);
        std::vector<float> in(2 * 48000);
        for (int n = 0; n < 48000; ++n) {
          const double v = source.sample(n, rng);
          in[2 * static_cast<std::size_t>(n)] = static_cast<float>(v);
          in[2 * static_cast<std::size_t>(n) + 1] = static_cast<float>(v);
        }
        const auto out = Run(stage, in);
        INFO(source.name << ", ceilings " << speaker_db << " / " << transducer_db << " dB");
        for (const float v : out) REQUIRE(std::isfinite(v));
        CHECK(SamplePeak(out, 0) <= speaker);
        CHECK(SamplePeak(out, 1) <= transducer);
        CHECK(sas::test::TruePeak(out, 2, 0) <= speaker);
        CHECK(sas::test::TruePeak(out, 2, 1) <= transducer);
      }
    }
  }
}

TEST_CASE("safety stage: a signal under the ceiling passes unchanged, kDelayFrames late",
          "[dsp][safety]") {
  SafetyStage stage;
  stage.Prepare(kFs);
  stage.SetCeilings(std::pow(10.0, -1.0 / 20.0), 1.0);
  std::vector<float> in(2 * 9600);
  for (std::size_t n = 0; n < 9600; ++n) {
    const auto t = static_cast<double>(n) / kFs;
    in[2 * n] = static_cast<float>(0.5 * std::sin(2.0 * M_PI * 440.0 * t));
    in[2 * n + 1] = static_cast<float>(0.3 * std::sin(2.0 * M_PI * 100.0 * t));
  }
  const auto out = Run(stage, in);
  const auto d = static_cast<std::size_t>(SafetyStage::kDelayFrames);
  for (std::size_t n = 0; n < d; ++n) {
    CHECK(out[2 * n] == 0.0f);
    CHECK(out[2 * n + 1] == 0.0f);
  }
  for (std::size_t n = d; n < 9600; ++n) {
    REQUIRE(out[2 * n] == in[2 * (n - d)]);
    REQUIRE(out[2 * n + 1] == in[2 * (n - d) + 1]);
  }
}

TEST_CASE(
    "safety stage: a lowered ceiling holds at once, for the samples already in the "
    "look-ahead too, and the gain recovers without a step",
    "[dsp][safety]") {
  SafetyStage stage;
  stage.Prepare(kFs, 0.05);
  stage.SetCeilings(1.0, 1.0);
  std::vector<float> frame(2);
  std::vector<float> out;
  double worst_step = 0.0;
  double previous = 0.0;
  for (int n = 0; n < 48000; ++n) {
    if (n == 12000) stage.SetCeilings(1.0, 0.1);  // low-vibration mode: transducer -20 dB
    if (n == 30000) stage.SetCeilings(1.0, 1.0);
    const double v = 0.9 * std::sin(2.0 * M_PI * 200.0 * n / kFs);
    frame[0] = frame[1] = static_cast<float>(v);
    stage.Process(frame.data());
    if (n >= 12000 && n < 30000) REQUIRE(std::fabs(frame[1]) <= 0.1);
    if (n > 30000 + SafetyStage::kDelayFrames) {
      worst_step = std::max(worst_step, std::fabs(frame[1] - previous));
    }
    previous = frame[1];
  }
  // After the ceiling comes back up the gain rises over 50 ms: the 200 Hz sine's sample-to-sample
  // change (at most 0.9 · 2π · 200 / 48000 = 0.024) plus the release, never a jump.
  CHECK(worst_step < 0.03);
}
