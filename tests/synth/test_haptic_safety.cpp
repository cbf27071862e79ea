// The transducer channel's protections for sensitive visitors: a peak ceiling below full
// scale that no gain can push the haptic output past, and a low-vibration mode, switched at run
// time, that lowers the haptic level by exactly its configured amount (after its 20 ms ramp)
// while the speaker channel stays bit for bit the same.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <limits>
#include <cstring>
#include <vector>

#include "synth/output_stage.h"
#include "synth/safety_stage.h"
#include "synth/scene.h"
#include "synth_test_support.h"

using namespace sas::synth;

namespace {

constexpr double kFs = 48000.0;

MaterialParams LowModes() {  // modes inside the transducer band, so ch 2 carries real signal
  MaterialParams m;
  m.resonator.mode_count = 6;
  for (int i = 0; i < 6; ++i) {
    auto& mode = m.resonator.modes[static_cast<std::size_t>(i)];
    mode.frequency_hz = 90.0 * (i + 1) * (1.0 + 0.11 * i);
    mode.decay_s = 0.2;
    mode.mass_kg = 0.02;
    mode.gain = 1.0;
  }
  m.impact.stiffness = 3e7;
  return m;
}

std::vector<float> Ridges() {  // 0.6 m of 40 µm ridges
  std::vector<float> h(4000);
  for (std::size_t i = 0; i < h.size(); ++i) {
    h[i] = static_cast<float>(20e-6 * (1.0 + std::sin(0.29 * static_cast<double>(i))));
  }
  return h;
}

// A 0.5 s stroke (tip down at frame 0), rendered in 128-frame blocks; `before_block` runs before
// each block (to switch the mode mid-stroke).
template <class F>
std::vector<float> Stroke(Scene& scene, long frames, F before_block) {
  ProbeCommand c;
  c.tip_down = true;
  c.x_m = 0.01;
  c.velocity_mps = 0.3;
  c.normal_force_n = 1.0;
  c.penetration_m = 40e-6;
  c.width_mm = 0.4;
  c.landing_speed_mps = 0.2;
  std::vector<float> out(2 * static_cast<std::size_t>(frames));
  for (long start = 0; start < frames; start += 128) {
    before_block(start);
    const int n = static_cast<int>(std::min<long>(128, frames - start));
    scene.Process(start == 0 ? &c : nullptr, start == 0 ? 1 : 0,
                  out.data() + 2 * static_cast<std::size_t>(start), n);
  }
  return out;
}

double ChannelRms(const std::vector<float>& out, int channel, long from, long to) {
  double sum = 0.0;
  for (long i = from; i < to; ++i) {
    const double x = out[static_cast<std::size_t>(2 * i + channel)];
    sum += x * x;
  }
  return std::sqrt(sum / static_cast<double>(to - from));
}

}  // namespace

TEST_CASE(
    "with exaggerated gains the transducer's drive saturates at its ceiling, the band limit lifts "
    "it by at most its own gain, and the safety stage holds the ceiling",
    "[dsp][render]") {
  test::OwnedField field(4000, 1, 0.153e-3, Ridges());
  for (const double ceiling_db : {-20.0, -6.0, 0.0}) {
    OutputParams p;
    p.sound_gain = 1e3;
    p.haptic_gain = 1e6;
    p.haptic_ceiling = std::pow(10.0, ceiling_db / 20.0);
    Scene scene;
    scene.Init(kFs);
    scene.Prepare(LowModes(), p, field.view);
    auto out = Stroke(scene, 24000, [](long) {});
    OutputStage stage;
    stage.Prepare(p, kFs);
    double haptic_peak = 0.0, sound_peak = 0.0;
    for (std::size_t i = 0; i < out.size(); i += 2) {
      sound_peak = std::max(sound_peak, static_cast<double>(std::fabs(out[i])));
      haptic_peak = std::max(haptic_peak, static_cast<double>(std::fabs(out[i + 1])));
    }
    INFO("ceiling " << ceiling_db << " dBFS, haptic peak " << 20.0 * std::log10(haptic_peak));
    CHECK(haptic_peak <= p.haptic_ceiling * stage.BandLimitGain());
    CHECK(haptic_peak > 0.95 * p.haptic_ceiling);  // the gain really pushed it to the ceiling
    CHECK(sound_peak > 0.95);                      // the ceiling is the transducer's only
    // Through the final safety stage (as every device sample goes): never over the ceiling.
    SafetyStage safety;
    safety.Prepare(kFs);
    safety.SetCeilings(1.0, p.haptic_ceiling);
    float limited = 0.0f;
    for (std::size_t i = 0; i < out.size(); i += 2) {
      safety.Process(&out[i]);
      limited = std::max(limited, std::fabs(out[i + 1]));
    }
    CHECK(limited <= static_cast<float>(p.haptic_ceiling));
    CHECK(limited > 0.8 * p.haptic_ceiling);
  }
}

TEST_CASE(
    "low-vibration mode lowers the haptic RMS by its configured amount and leaves the sound "
    "channel unchanged",
    "[dsp][render]") {
  test::OwnedField field(4000, 1, 0.153e-3, Ridges());
  const double attenuation_db = 12.0;
  OutputParams p;
  p.low_vibration_gain = std::pow(10.0, -attenuation_db / 20.0);
  p.haptic_gain = 0.05;  // peaks below the limiter's knee: the attenuation is exactly linear
  const long frames = 24000;
  const long switch_frame = 6016;  // a block boundary; the ramp then takes 960 frames
  Scene normal, low;
  for (Scene* s : {&normal, &low}) {
    s->Init(kFs);
    s->Prepare(LowModes(), p, field.view);
  }
  REQUIRE_FALSE(low.low_vibration());
  const auto a = Stroke(normal, frames, [](long) {});
  const auto b = Stroke(low, frames, [&](long start) {
    if (start == switch_frame) low.SetLowVibration(true);
  });
  CHECK(low.low_vibration());
  for (long i = 0; i < frames; ++i) {  // speaker channel: identical samples
    REQUIRE(a[static_cast<std::size_t>(2 * i)] == b[static_cast<std::size_t>(2 * i)]);
  }
  // Before the switch nothing changes; after the ramp the transducer is exactly 12 dB lower.
  CHECK(ChannelRms(b, 1, 0, switch_frame) == ChannelRms(a, 1, 0, switch_frame));
  const long settled = switch_frame + 960;
  // The trim acts before the transducer's band limit, whose memory (its 40 Hz high-pass, its
  // low-pass's delay) carries the ramp on for a few tens of milliseconds: measured 0.1 s on.
  const long filtered = settled + 4800;
  const double ratio_db =
      20.0 * std::log10(ChannelRms(b, 1, filtered, frames) / ChannelRms(a, 1, filtered, frames));
  CHECK(ChannelRms(a, 1, filtered, frames) > 1e-4);  // there is vibration to lower
  CHECK(ratio_db == Approx(-attenuation_db).margin(0.01));
  // The ramp never steps: neighbouring haptic samples differ by no more than in normal mode + a
  // bit.
  double max_step_a = 0.0, max_step_b = 0.0;
  for (long i = switch_frame; i < settled; ++i) {
    const auto k = static_cast<std::size_t>(2 * i + 1);
    max_step_a = std::max(max_step_a, static_cast<double>(std::fabs(a[k] - a[k - 2])));
    max_step_b = std::max(max_step_b, static_cast<double>(std::fabs(b[k] - b[k - 2])));
  }
  CHECK(max_step_b <= max_step_a * 1.01);

  // Switched off, a reset scene renders exactly like one that never was in low-vibration mode.
  low.SetLowVibration(false);
  low.Reset();
  normal.Reset();
  const auto c = Stroke(low, 4800, [](long) {});
  const auto d = Stroke(normal, 4800, [](long) {});
  CHECK(std::memcmp(c.data(), d.data(), c.size() * sizeof(float)) == 0);
}

TEST_CASE(
    "stroke gains set mid-stroke scale sound and vibration by exactly their amount after a 20 ms "
    "ramp that never steps, and a reset scene takes them at once",
    "[dsp][render]") {
  test::OwnedField field(4000, 1, 0.153e-3, Ridges());
  OutputParams p;
  p.sound_gain = 0.1;  // peaks below the limiters' knees even at +6 dB: the gain is exactly linear
  p.haptic_gain = 0.05;
  const long frames = 24000;
  const long switch_frame = 6016;  // a block boundary; the ramp then takes 960 frames
  const double sound_db = 5.0, haptic_db = -7.0;
  Scene plain, gained;
  for (Scene* s : {&plain, &gained}) {
    s->Init(kFs);
    s->Prepare(LowModes(), p, field.view);
  }
  const auto a = Stroke(plain, frames, [](long) {});
  const auto b = Stroke(gained, frames, [&](long start) {
    if (start == switch_frame) {
      gained.SetStrokeGains(std::pow(10.0, sound_db / 20.0), std::pow(10.0, haptic_db / 20.0));
    }
  });
  for (int channel : {0, 1}) {
    CHECK(ChannelRms(b, channel, 0, switch_frame) == ChannelRms(a, channel, 0, switch_frame));
  }
  const long settled = switch_frame + 960;
  REQUIRE(ChannelRms(a, 0, settled, frames) > 1e-4);
  REQUIRE(ChannelRms(a, 1, settled, frames) > 1e-4);
  // The transducer's factor acts before its band limit, whose memory carries the ramp on for a
  // few tens of milliseconds: its ratio is measured 0.1 s on.
  const auto ratio_db = [&](int channel) {
    const long from = channel == 1 ? settled + 4800 : settled;
    return 20.0 * std::log10(ChannelRms(b, channel, from, frames) /
                             ChannelRms(a, channel, from, frames));
  };
  CHECK(ratio_db(0) == Approx(sound_db).margin(0.01));
  CHECK(ratio_db(1) == Approx(haptic_db).margin(0.01));
  // The ramp never steps: during it neighbouring samples differ no more than the larger of the
  // two signals' own steps allows (a jump of 5 dB on one sample would show as a step ~0.8 x the
  // signal's amplitude).
  for (int channel : {0, 1}) {
    double max_step_a = 0.0, max_step_b = 0.0;
    for (long i = switch_frame; i < settled; ++i) {
      const auto k = static_cast<std::size_t>(2 * i + channel);
      max_step_a = std::max(max_step_a, static_cast<double>(std::fabs(a[k] - a[k - 2])));
      max_step_b = std::max(max_step_b, static_cast<double>(std::fabs(b[k] - b[k - 2])));
    }
    CHECK(max_step_b <= max_step_a * std::max(1.0, std::pow(10.0, sound_db / 20.0)) * 1.01);
  }
  // A reset scene takes the gains at once: its first stroke is the plain one scaled exactly.
  gained.SetStrokeGains(2.0, 0.5);
  gained.Reset();
  plain.Reset();
  const auto c = Stroke(gained, 4800, [](long) {});
  const auto d = Stroke(plain, 4800, [](long) {});
  CHECK(ChannelRms(c, 0, 0, 4800) == Approx(2.0 * ChannelRms(d, 0, 0, 4800)).epsilon(1e-6));
  CHECK(ChannelRms(c, 1, 0, 4800) == Approx(0.5 * ChannelRms(d, 1, 0, 4800)).epsilon(1e-6));
  // Back at 1, the scene renders bit for bit like one that never had a stroke gain.
  gained.SetStrokeGains(1.0, 1.0);
  gained.Reset();
  plain.Reset();
  const auto e = Stroke(gained, 4800, [](long) {});
  const auto f = Stroke(plain, 4800, [](long) {});
  CHECK(std::memcmp(e.data(), f.data(), e.size() * sizeof(float)) == 0);
}

TEST_CASE(
    "for any finite input the output stage stays within its ceiling times its band limit's gain "
    "and the safety stage after it within the ceiling",
    "[dsp]") {
  OutputParams p;
  p.haptic_gain = 1e12;
  p.haptic_ceiling = 0.1;
  OutputStage stage;
  stage.Prepare(p, kFs);
  SafetyStage safety;
  safety.Prepare(kFs);
  safety.SetCeilings(1.0, p.haptic_ceiling);
  float peak = 0.0f, limited = 0.0f;
  for (int n = 0; n < 48000; ++n) {
    const double x = 1e3 * std::sin(0.013 * n) * std::sin(0.0007 * n * n);
    float frame[2] = {0.0f, 0.0f};
    stage.Process(0.0, x, &frame[0], &frame[1]);
    peak = std::max(peak, std::fabs(frame[1]));
    safety.Process(frame);
    limited = std::max(limited, std::fabs(frame[1]));
  }
  CHECK(peak <= p.haptic_ceiling * stage.BandLimitGain());
  CHECK(peak > 0.099f);
  CHECK(limited <= static_cast<float>(p.haptic_ceiling));
}

TEST_CASE("the output stage's block path gives Process's samples bit for bit", "[dsp]") {
  // The scene runs its frames through ProcessBlock; it must be Process frame by frame, including
  // the gain ramps, the leveller, NaN input, and the band-pass guard's reset on overflow.
  const double cap = GENERATE(0.05, 0.0);  // leveller on / off
  const bool haptic = GENERATE(true, false);
  OutputParams p;
  p.sound_level_cap = cap;
  p.haptic_gain = 3.0;
  p.haptic_enabled = haptic;
  OutputStage per_frame, block;
  per_frame.Prepare(p, kFs);
  block.Prepare(p, kFs);
  constexpr int kFrames = 6000;
  std::vector<double> pickup(kFrames), felt(kFrames);
  for (int n = 0; n < kFrames; ++n) {
    pickup[static_cast<std::size_t>(n)] = 0.4 * std::sin(0.05 * n) * std::sin(0.0003 * n * n);
    felt[static_cast<std::size_t>(n)] = 0.02 * std::sin(0.01 * n);
  }
  pickup[700] = std::numeric_limits<double>::quiet_NaN();
  felt[900] = std::numeric_limits<double>::infinity();
  pickup[2000] = 1.7e308;  // the band-pass overflows: the guard resets the stage
  pickup[2001] = -1.7e308;
  std::vector<float> e(2 * kFrames), f(2 * kFrames);
  int n = 0;
  for (int chunk = 1; n < kFrames; chunk = chunk % 97 + 7) {
    const int len = std::min(chunk, kFrames - n);
    if (n > 3000 && n < 3200) {  // a ramp starting inside the run
      per_frame.SetStrokeGains(0.5, 2.0, 0.005);
      block.SetStrokeGains(0.5, 2.0, 0.005);
    }
    for (int i = n; i < n + len; ++i) {
      const auto k = static_cast<std::size_t>(i);
      per_frame.Process(pickup[k], felt[k], &e[2 * k], &e[2 * k + 1]);
    }
    block.ProcessBlock(&pickup[static_cast<std::size_t>(n)], &felt[static_cast<std::size_t>(n)],
                       &f[2 * static_cast<std::size_t>(n)], len);
    n += len;
  }
  CHECK(std::memcmp(e.data(), f.data(), e.size() * sizeof(float)) == 0);
  if (haptic) CHECK(std::fabs(f[2 * 2500 + 1]) > 0.0f);  // signal on ch 2 after the reset
}

TEST_CASE(
    "the transducer carries the friction's noise in its material's felt share and the sound all "
    "of it",
    "[dsp][render]") {
  // A flat field: the steady push and the steady slide leave only the noise term to feel (after
  // the landing).
  test::OwnedField field(4000, 1, 0.153e-3, std::vector<float>(4000, 20e-6f));
  OutputParams p;
  p.haptic_gain = 0.05;
  const auto rms_db = [](const std::vector<float>& out, int channel) {
    return 20.0 * std::log10(ChannelRms(out, channel, 4800, 24000) + 1e-30);
  };
  std::vector<std::vector<float>> outs;
  for (const double share : {1.0, 0.1, 0.0}) {
    // One stiff mode far above the band: the surface's own ring does not reach the pen's band.
    MaterialParams m = LowModes();
    m.resonator.mode_count = 1;
    m.resonator.modes[0].frequency_hz = 6000.0;
    m.friction.noise_coefficient = 5.0;  // dry soil's grit, loud enough to stand out
    m.friction.felt_noise_share = share;
    Scene scene;
    scene.Init(kFs);
    scene.Prepare(m, p, field.view);
    outs.push_back(Stroke(scene, 24000, [](long) {}));
  }
  for (long i = 0; i < 24000; ++i) {  // the speaker hears the same slide
    REQUIRE(outs[0][static_cast<std::size_t>(2 * i)] == outs[2][static_cast<std::size_t>(2 * i)]);
  }
  INFO("felt share 1: " << rms_db(outs[0], 1) << " dB, 0.1: " << rms_db(outs[1], 1)
                        << " dB, 0: " << rms_db(outs[2], 1) << " dB");
  CHECK(rms_db(outs[0], 1) > -100.0);  // there is noise to feel
  // A tenth of the noise term is up to 20 dB less of it; what is left at 0 is the force the
  // noise still causes (the bristle and the modes it moves), over 20 dB under.
  CHECK(rms_db(outs[1], 1) < rms_db(outs[0], 1) - 15.0);
  CHECK(rms_db(outs[1], 1) > rms_db(outs[2], 1));
  CHECK(rms_db(outs[2], 1) < rms_db(outs[0], 1) - 20.0);
}
