// The output stage's stroke leveller: a sustained sound over the cap comes down to it, a sound
// under it passes untouched (bit for bit), and a short click is left mostly to the limiters.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "synth/output_stage.h"

using sas::synth::OutputParams;
using sas::synth::OutputStage;

namespace {

constexpr double kFs = 48000.0;
constexpr double kPi = 3.14159265358979323846;

// Channel 1 of `stage` for a sine of amplitude `amplitude` at 700 Hz, `seconds` long.
std::vector<float> PlaySine(OutputStage& stage, double amplitude, double seconds) {
  std::vector<float> out(static_cast<std::size_t>(seconds * kFs));
  for (std::size_t i = 0; i < out.size(); ++i) {
    float haptic = 0.0f;
    stage.Process(amplitude * std::sin(2.0 * kPi * 700.0 * static_cast<double>(i) / kFs), &out[i],
                  &haptic);
  }
  return out;
}

double RmsDb(const std::vector<float>& x, std::size_t from, std::size_t to) {
  double sum = 0.0;
  for (std::size_t i = from; i < to; ++i) sum += static_cast<double>(x[i]) * x[i];
  return 10.0 * std::log10(sum / static_cast<double>(to - from));
}

OutputStage Stage(double cap) {
  OutputParams p;
  p.haptic_enabled = false;
  p.sound_level_cap = cap;
  OutputStage stage;
  stage.Prepare(p, kFs);
  return stage;
}

}  // namespace

TEST_CASE("stroke leveller: a sustained sound 12 dB over the cap settles within 1 dB of it") {
  const double cap = std::pow(10.0, -30.0 / 20.0);  // -30 dBFS RMS, far under the soft limiter
  OutputStage stage = Stage(cap);
  const double amplitude = std::sqrt(2.0) * cap * std::pow(10.0, 12.0 / 20.0);
  const std::vector<float> out = PlaySine(stage, amplitude, 1.0);
  const double settled = RmsDb(out, out.size() / 2, out.size());
  CHECK(settled == Approx(-30.0).margin(1.0));
  // Without a cap the same sine keeps its level.
  OutputStage open = Stage(0.0);
  const std::vector<float> free = PlaySine(open, amplitude, 1.0);
  CHECK(RmsDb(free, free.size() / 2, free.size()) == Approx(-18.0).margin(0.1));
}

TEST_CASE("stroke leveller: a sound under the cap is bit for bit the uncapped output") {
  const double cap = std::pow(10.0, -20.0 / 20.0);
  OutputStage capped = Stage(cap);
  OutputStage open = Stage(0.0);
  const double amplitude = std::sqrt(2.0) * cap * std::pow(10.0, -3.0 / 20.0);
  CHECK(PlaySine(capped, amplitude, 0.5) == PlaySine(open, amplitude, 0.5));
}

TEST_CASE("stroke leveller: a 2 ms click over the cap keeps most of its peak") {
  const double cap = std::pow(10.0, -30.0 / 20.0);
  OutputStage stage = Stage(cap);
  const double amplitude = std::sqrt(2.0) * cap * std::pow(10.0, 12.0 / 20.0);
  const std::vector<float> click = PlaySine(stage, amplitude, 0.002);
  double peak = 0.0;
  for (const float v : click) peak = std::max(peak, static_cast<double>(std::fabs(v)));
  CHECK(20.0 * std::log10(peak / amplitude) > -3.0);
}

TEST_CASE("stroke leveller: a 30 ms burst far over the cap is held near the burst allowance") {
  // A crack struck mid-stroke: 12 dB over the cap for 30 ms, too short for the 50 ms detector to
  // hear in time. The same leveller without its burst detector is the baseline.
  const double cap = std::pow(10.0, -30.0 / 20.0);
  const double soft = std::sqrt(2.0) * cap * std::pow(10.0, -6.0 / 20.0);
  const double burst = std::sqrt(2.0) * cap * std::pow(10.0, 12.0 / 20.0);
  const auto play = [&](double burst_over_db) {
    sas::synth::Leveller leveller;
    leveller.Prepare(cap,
                     {.window_s = OutputStage::kLevellerWindowS,
                      .attack_s = OutputStage::kLevellerAttackS,
                      .release_s = OutputStage::kLevellerReleaseS,
                      .landing_s = OutputStage::kLevellerLandingS,
                      .burst_window_s = OutputStage::kBurstWindowS,
                      .burst_attack_s = OutputStage::kBurstAttackS,
                      .burst_release_s = OutputStage::kBurstReleaseS,
                      .burst_over_db = burst_over_db},
                     kFs);
    const auto sine = [&](double amplitude, double seconds) {
      std::vector<float> out(static_cast<std::size_t>(seconds * kFs));
      for (std::size_t i = 0; i < out.size(); ++i) {
        out[i] = static_cast<float>(leveller.Apply(
            amplitude * std::sin(2.0 * kPi * 700.0 * static_cast<double>(i) / kFs)));
      }
      return out;
    };
    sine(soft, 0.2);
    const std::vector<float> loud = sine(burst, 0.03);
    return RmsDb(loud, 0, loud.size()) + 30.0;  // dB over the cap
  };
  const double without = play(200.0), with = play(OutputStage::kBurstOverCapDb);
  CHECK(without > 8.0);
  CHECK(with < OutputStage::kBurstOverCapDb + 3.0);
  CHECK(with > 0.0);  // it still stands out of the stroke
}

TEST_CASE("stroke leveller: its K-weighting at 48 kHz is BS.1770's coefficient table") {
  const auto k = sas::synth::KWeighting(48000.0);
  CHECK(k[0].b0 == Approx(1.53512485958697).margin(1e-8));
  CHECK(k[0].b1 == Approx(-2.69169618940638).margin(1e-8));
  CHECK(k[0].b2 == Approx(1.19839281085285).margin(1e-8));
  CHECK(k[0].a1 == Approx(-1.69065929318241).margin(1e-8));
  CHECK(k[0].a2 == Approx(0.73248077421585).margin(1e-8));
  CHECK(k[1].b0 == 1.0);
  CHECK(k[1].b1 == -2.0);
  CHECK(k[1].b2 == 1.0);
  CHECK(k[1].a1 == Approx(-1.99004745483398).margin(1e-8));
  CHECK(k[1].a2 == Approx(0.99007225036621).margin(1e-8));
}

TEST_CASE("stroke leveller: a bright sound is held to the same loudness as a dull one") {
  // 5 kHz sits on the K-weighting's +4 dB shelf: at the same cap its RMS settles ~4 dB lower than
  // a 700 Hz sine's, as the loudness measure hears the two alike.
  const double cap = std::pow(10.0, -30.0 / 20.0);
  const auto settle = [&](double hz) {
    OutputStage stage = Stage(cap);
    const double amplitude = std::sqrt(2.0) * cap * std::pow(10.0, 12.0 / 20.0);
    std::vector<float> out(static_cast<std::size_t>(kFs));
    for (std::size_t i = 0; i < out.size(); ++i) {
      float haptic = 0.0f;
      stage.Process(amplitude * std::sin(2.0 * kPi * hz * static_cast<double>(i) / kFs), &out[i],
                    &haptic);
    }
    return RmsDb(out, out.size() / 2, out.size());
  };
  const double dull = settle(700.0), bright = settle(5000.0);
  CHECK(dull - bright == Approx(3.6).margin(0.6));
}

TEST_CASE("stroke leveller: a soft stroke after a loud one starts at full level") {
  const double cap = std::pow(10.0, -30.0 / 20.0);
  const double loud = std::sqrt(2.0) * cap * std::pow(10.0, 15.0 / 20.0);
  const double soft = std::sqrt(2.0) * cap * std::pow(10.0, -6.0 / 20.0);
  OutputStage reference = Stage(0.0);
  const std::vector<float> free = PlaySine(reference, soft, 0.1);
  const double free_db = RmsDb(free, free.size() / 2, free.size());
  // Held down by the loud stroke, the soft one that follows without a new stroke stays muted
  // (the slow release), and comes back once the pen lands anew.
  OutputStage held = Stage(cap);
  PlaySine(held, loud, 0.5);
  const std::vector<float> muted = PlaySine(held, soft, 0.1);
  CHECK(RmsDb(muted, muted.size() / 2, muted.size()) < free_db - 6.0);
  OutputStage landed = Stage(cap);
  PlaySine(landed, loud, 0.5);
  landed.NewStroke();
  const std::vector<float> fresh = PlaySine(landed, soft, 0.1);
  CHECK(RmsDb(fresh, fresh.size() / 2, fresh.size()) == Approx(free_db).margin(0.3));
}

TEST_CASE("stroke leveller: a landing click does not hold the stroke after it down") {
  const double cap = std::pow(10.0, -30.0 / 20.0);
  const double click = std::sqrt(2.0) * cap * std::pow(10.0, 10.0 / 20.0);
  const double soft = std::sqrt(2.0) * cap * std::pow(10.0, -6.0 / 20.0);
  const double click_s = 0.5 * OutputStage::kLevellerLandingS;
  OutputStage reference = Stage(0.0);
  const std::vector<float> free = PlaySine(reference, soft, 0.3);
  const double free_db = RmsDb(free, free.size() / 2, free.size());
  // A click within the landing, then the stroke's own (soft) sound.
  const auto stroke_db = [&](bool landed) {
    OutputStage stage = Stage(cap);
    if (landed) stage.NewStroke();
    PlaySine(stage, click, click_s);
    const std::vector<float> after = PlaySine(stage, soft, 0.3);
    return RmsDb(after, after.size() / 2, after.size());
  };
  CHECK(stroke_db(true) == Approx(free_db).margin(0.1));
  CHECK(stroke_db(false) < free_db - 1.0);  // the same click mid-stroke is levelled
}

TEST_CASE(
    "stroke leveller: a landing click is held near the burst allowance over the cap, not let "
    "through whole") {
  const double cap = std::pow(10.0, -30.0 / 20.0);  // -30 dBFS RMS
  // 14 dB over the cap for the whole landing window: a firm pen landing on wood or clods.
  const double click = std::sqrt(2.0) * cap * std::pow(10.0, 14.0 / 20.0);
  OutputStage stage = Stage(cap);
  stage.NewStroke();
  const std::vector<float> out = PlaySine(stage, click, OutputStage::kLevellerLandingS);
  // After the burst detector's own window and attack, the click plays within a dB or two of the
  // allowance (cap + 3 dB = -27 dBFS RMS), not at its own -16 dBFS.
  const auto settled = static_cast<std::size_t>(0.03 * kFs);
  const double held = RmsDb(out, settled, out.size());
  CHECK(held < -30.0 + OutputStage::kBurstOverCapDb + 2.0);
  CHECK(held > -30.0 - 3.0);  // held, not muted
  OutputStage open = Stage(0.0);
  const std::vector<float> free = PlaySine(open, click, OutputStage::kLevellerLandingS);
  CHECK(RmsDb(free, settled, free.size()) == Approx(-16.0).margin(0.2));
}
