// Block rendering = per-sample rendering bit for bit; Reset() = a fresh
// instance) plus the properties of the output stage (|sample| <= 1, never NaN, haptic band,
// haptic path off) and of the surface reader (width window, penetration, roll envelope).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <vector>

#include "support/fft.h"
#include "synth/output_stage.h"
#include "synth/scene.h"
#include "synth/surface_reader.h"
#include "synth_test_support.h"

using namespace sas::synth;

namespace {

constexpr double kFs = 48000.0;

// A bumpy 1-D profile: 4000 samples (0.6 m) of ridges up to 50 µm.
std::vector<float> BumpyProfile() {
  std::vector<float> h(4000);
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double x = static_cast<double>(i);
    h[i] = static_cast<float>(25e-6 * (1.0 + std::sin(0.37 * x) * std::sin(0.051 * x)));
  }
  return h;
}

using test::RenderTimed;
using test::TimedCommand;
using test::WoodLikeBoard;

// A gesture with every kind of event, at absolute frames.
std::vector<TimedCommand> Gesture() {
  std::vector<TimedCommand> g;
  ProbeCommand c;
  c.tip_down = true;
  c.x_m = 0.01;
  c.velocity_mps = 0.2;
  c.normal_force_n = 0.8;
  c.penetration_m = 40e-6;
  c.width_mm = 0.4;
  c.landing_speed_mps = 0.3;
  g.push_back({0, c});
  c.x_m = 0.02;
  c.style = ProbeStyle::kRub;
  c.width_mm = 4.0;
  c.velocity_mps = 0.6;
  g.push_back({1777, c});
  c.x_m = 0.05;
  c.style = ProbeStyle::kRoll;
  c.direction_x = -1.0;
  g.push_back({5000, c});
  c.burst_impulse_n_s = 2e-4;
  g.push_back({5000, c});  // two commands at the same frame
  c.burst_impulse_n_s = 0.0;
  c.tip_down = false;
  g.push_back({9001, c});
  c.burst_impulse_n_s = 5e-4;  // a bubble popping with the pen up
  g.push_back({12000, c});
  c.burst_impulse_n_s = 0.0;
  c.tip_down = true;
  c.style = ProbeStyle::kScrape;
  c.direction_x = 1.0;
  c.velocity_mps = 1.5;
  g.push_back({15000, c});
  return g;
}

// Where a rolling ball is checked against the full scan: `points` places from (x0, y0) in steps
// of (sx, sy) pixels, the track turning by `turn` radians each, for each penetration and width.
struct RollCheckPlaces {
  double x0, sx, y0, sy, turn;
  int points;
  double min_radius_m;  // the ball's radius when the probe is narrower (the pen's own ball)
};

// The rolling ball's felt height by the maximum over all 2n + 1 points of the ball along its
// track, compared bit for bit with SurfaceReader::Felt; counts the places and those felt.
void CheckRollAgainstFullScan(const SurfaceReader& reader, double pitch,
                              std::initializer_list<double> penetrations, const RollCheckPlaces& at,
                              int& compared, int& felt) {
  for (double penetration : penetrations) {
    for (double width : {0.0, 0.9e-3, 4e-3}) {
      for (int k = 0; k < at.points; ++k) {
        const double x = (at.x0 + at.sx * k) * pitch, y = (at.y0 + at.sy * k) * pitch;
        const double angle = at.turn * k;
        const double dx = std::cos(angle), dy = std::sin(angle);
        const double r = std::max(at.min_radius_m, 0.5 * width);
        const int n = static_cast<int>(std::clamp(r / pitch, 1.0, 64.0));
        const double ds = r / n;
        double full = -1e300;
        for (int i = -n; i <= n; ++i) {
          const double s = i * ds;
          const double lift = std::sqrt(std::max(r * r - s * s, 0.0)) - r;
          full = std::max(full, reader.BoxMean(x + s * dx, y + s * dy, width) + lift);
        }
        const double expected = std::max(full - (reader.max_height_m() - penetration), 0.0);
        const double got =
            reader.Felt(x, y, width, penetration, ProbeStyle::kRoll, at.min_radius_m, dx, dy);
        CHECK(got == expected);
        ++compared;
        if (expected > 0.0) ++felt;
      }
    }
  }
}

}  // namespace

TEST_CASE("block rendering equals per-sample rendering bit for bit", "[dsp][render]") {
  test::OwnedField field(4000, 1, 0.153e-3, BumpyProfile());
  const long total = 24000;
  std::vector<float> reference;
  for (const int block : {1, 7, 64, 128, 480, 24000}) {
    Scene scene;
    scene.Init(kFs);
    scene.Prepare(WoodLikeBoard(), OutputParams{}, field.view);
    const auto out = RenderTimed(scene, Gesture(), total, block);
    if (reference.empty()) {
      reference = out;
      float peak = 0.0f;
      for (float s : out) peak = std::max(peak, std::fabs(s));
      REQUIRE(peak > 1e-3f);  // the gesture makes sound
      continue;
    }
    INFO("block " << block);
    CHECK(std::memcmp(out.data(), reference.data(), out.size() * sizeof(float)) == 0);
  }
}

TEST_CASE("Reset() makes a used scene render exactly like a fresh one", "[dsp][render]") {
  test::OwnedField field(4000, 1, 0.153e-3, BumpyProfile());
  Scene fresh, used;
  for (Scene* s : {&fresh, &used}) {
    s->Init(kFs);
    s->Prepare(WoodLikeBoard(), OutputParams{}, field.view);
  }
  RenderTimed(used, Gesture(), 20000, 256);
  used.Reset();
  const auto a = RenderTimed(fresh, Gesture(), 20000, 256);
  const auto b = RenderTimed(used, Gesture(), 20000, 256);
  CHECK(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

TEST_CASE("output never exceeds 1 nor becomes NaN with exaggerated gains and hostile commands",
          "[dsp][render]") {
  test::OwnedField field(4000, 1, 0.153e-3, BumpyProfile());
  OutputParams loud;
  loud.sound_gain = 1e6;
  loud.haptic_gain = 1e6;
  Scene scene;
  scene.Init(kFs);
  scene.Prepare(WoodLikeBoard(), loud, field.view);
  auto gesture = Gesture();
  ProbeCommand bad;
  bad.tip_down = true;
  bad.x_m = std::numeric_limits<double>::quiet_NaN();
  bad.velocity_mps = std::numeric_limits<double>::infinity();
  bad.normal_force_n = -3.0;
  bad.width_mm = std::numeric_limits<double>::quiet_NaN();
  bad.burst_impulse_n_s = std::numeric_limits<double>::infinity();
  gesture.push_back({20000, bad});
  ProbeCommand absurd = bad;
  absurd.tip_down = false;
  gesture.push_back({21000, absurd});
  absurd.tip_down = true;
  absurd.x_m = 1e300;
  absurd.velocity_mps = 1e300;
  absurd.landing_speed_mps = 1e300;
  absurd.normal_force_n = 1e300;
  absurd.width_mm = 1e300;
  absurd.style = ProbeStyle::kRoll;
  gesture.push_back({22000, absurd});
  ProbeCommand sane = Gesture().front().command;
  sane.tip_down = false;
  gesture.push_back({25000, sane});
  sane.tip_down = true;
  gesture.push_back({25001, sane});
  const auto out = RenderTimed(scene, gesture, 30000, 128);
  // The transducer's channel within its ceiling (1 here) lifted by the band limit after its
  // limiter (output_stage.h); the final safety stage brings it back to the ceiling.
  OutputStage stage;
  stage.Prepare(loud, kFs);
  const auto haptic_bound = static_cast<float>(stage.BandLimitGain());
  REQUIRE(haptic_bound < 2.5f);
  float peak = 0.0f;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const float s = out[i];
    REQUIRE(std::isfinite(s));
    REQUIRE(std::fabs(s) <= (i % 2 == 0 ? 1.0f : haptic_bound));
    if (i % 2 == 0) peak = std::max(peak, std::fabs(s));
  }
  CHECK(peak > 0.9f);  // the gain really was exaggerated
  float tail = 0.0f;   // and the scene still plays after the absurd commands
  for (std::size_t i = 2 * 26000; i < out.size(); ++i) tail = std::max(tail, std::fabs(out[i]));
  CHECK(tail > 0.1f);
}

TEST_CASE("soft limiter is the identity below the knee, odd, monotone and bounded by 1", "[dsp]") {
  double previous = -1.0;
  for (double x = -1e9; x < 1e9;) {
    const double y = OutputStage::SoftLimit(x);
    REQUIRE(std::fabs(y) <= 1.0);
    REQUIRE(y >= previous);
    REQUIRE(OutputStage::SoftLimit(-x) == -y);
    if (std::fabs(x) <= OutputStage::kKnee) REQUIRE(y == x);
    previous = y;
    x = x < -1e-3 ? x * 0.9 : (x < 1e-3 ? x + 1e-4 : x * 1.1 + 1e-3);
  }
  CHECK(OutputStage::SoftLimit(std::numeric_limits<double>::quiet_NaN()) == 0.0);
  CHECK(OutputStage::SoftLimit(std::numeric_limits<double>::infinity()) == 1.0);
}

TEST_CASE(
    "haptic channel passes 40-400 Hz of the contact's force, rejects 2 kHz by more than 40 dB, "
    "takes nothing from the sound's pickup, and is silent when disabled",
    "[dsp]") {
  auto gain_at = [](double f, bool enabled, bool from_pickup = false) {
    OutputParams p;
    p.haptic_enabled = enabled;
    p.sound_gain = 1.0;
    p.haptic_gain = 1.0;
    OutputStage stage;
    stage.Prepare(p, kFs);
    double in_power = 0.0, out_power = 0.0;
    for (int n = 0; n < 48000; ++n) {
      const double x = 0.1 * std::sin(2.0 * std::numbers::pi * f * n / kFs);
      float sound = 0.0f, haptic = 0.0f;
      stage.Process(from_pickup ? x : 0.0, from_pickup ? 0.0 : x, &sound, &haptic);
      if (n >= 24000) {
        in_power += x * x;
        out_power += static_cast<double>(haptic) * haptic;
      }
    }
    return 10.0 * std::log10(out_power / in_power + 1e-300);
  };
  CHECK(std::fabs(gain_at(200.0, true)) < 1.0);
  CHECK(std::fabs(gain_at(100.0, true)) < 1.0);
  CHECK(std::fabs(gain_at(300.0, true)) < 1.0);
  CHECK(gain_at(800.0, true) < -40.0);
  CHECK(gain_at(200.0, true, true) < -290.0);  // the pickup is the speaker's alone
  CHECK(gain_at(2000.0, true) < -40.0);
  CHECK(gain_at(10.0, true) < -20.0);
  CHECK(gain_at(200.0, false) < -290.0);  // exactly zero
}

TEST_CASE(
    "surface reader: width window is the exact mean, penetration thresholds, roll "
    "bridges pits narrower than the ball",
    "[dsp]") {
  const double pitch = 1e-4;
  std::vector<float> h(100, 0.0f);
  for (int i = 0; i < 100; ++i) h[static_cast<std::size_t>(i)] = static_cast<float>(1e-6 * (i % 7));
  test::OwnedField field(100, 1, pitch, h);
  SurfaceReader reader;
  reader.Prepare(field.view);
  CHECK(reader.max_height_m() == Approx(6e-6));
  // Window of 5 pixels aligned with pixel edges: the plain mean of those pixels.
  double sum = 0.0;
  for (int i = 40; i < 45; ++i) sum += h[static_cast<std::size_t>(i)];
  CHECK(reader.BoxMean(42.5 * pitch, 0.0, 5.0 * pitch) == Approx(sum / 5.0).epsilon(1e-12));
  // Continuous in position: tiny moves give tiny changes.
  const double a = reader.BoxMean(30.0 * pitch, 0.0, 3.3 * pitch);
  const double b = reader.BoxMean(30.0001 * pitch, 0.0, 3.3 * pitch);
  CHECK(std::fabs(a - b) < 1e-9);
  // Penetration: only what rises above h_max - penetration is felt.
  CHECK(reader.Felt(6.5 * pitch, 0.0, 0.0, 0.0, ProbeStyle::kScrape, 0.0, 1.0, 0.0) == 0.0);
  CHECK(reader.Felt(6.5 * pitch, 0.0, 0.0, 2e-6, ProbeStyle::kScrape, 0.0, 1.0, 0.0) ==
        Approx(2e-6).epsilon(1e-6));
  CHECK(reader.Felt(3.5 * pitch, 0.0, 0.0, 2e-6, ProbeStyle::kScrape, 0.0, 1.0, 0.0) == 0.0);

  // A 2-pixel-wide, 50 µm deep pit: a scraping point falls in, a 2 mm ball does not.
  std::vector<float> pit(200, 50e-6f);
  pit[100] = pit[101] = 0.0f;
  test::OwnedField pit_field(200, 1, pitch, pit);
  reader.Prepare(pit_field.view);
  const double x = 101.0 * pitch;
  const double scrape = reader.Felt(x, 0.0, 0.0, 1e-3, ProbeStyle::kScrape, 2e-3, 1.0, 0.0);
  const double roll = reader.Felt(x, 0.0, 0.0, 1e-3, ProbeStyle::kRoll, 2e-3, 1.0, 0.0);
  const double flat =
      reader.Felt(50.0 * pitch, 0.0, 0.0, 1e-3, ProbeStyle::kScrape, 2e-3, 1.0, 0.0);
  CHECK(flat - scrape == Approx(50e-6).epsilon(1e-6));
  // The 1-pixel window smears the pit's edges by half a pixel, so the ball rests on the rims
  // 2 pixels from the centre and sinks by its sagitta r - sqrt(r² - (2p)²) ≈ 10 µm, not 50 µm.
  const double r = 2e-3, half_width = 2.0 * pitch;
  CHECK(flat - roll == Approx(r - std::sqrt(r * r - half_width * half_width)).epsilon(1e-6));
}

TEST_CASE("the rolling ball's envelope equals the full scan over every point of the ball",
          "[dsp]") {
  // The reader stops scanning the ball where no further point can change the result: compare
  // with the maximum over all 2n + 1 points, bit for bit, over a rough 2-D field, light to full
  // penetration, point to wide probes and every direction.
  const int w = 120, hgt = 90;
  const double pitch = 1.5e-4;
  std::vector<float> h(static_cast<std::size_t>(w * hgt));
  std::uint32_t state = 12345u;
  for (auto& v : h) {
    state = state * 1664525u + 1013904223u;
    v = static_cast<float>(200e-6 * static_cast<double>(state >> 8) / 16777216.0);
  }
  test::OwnedField field(w, hgt, pitch, h);
  SurfaceReader reader;
  reader.Prepare(field.view);
  int compared = 0, felt = 0;
  CheckRollAgainstFullScan(reader, pitch, {0.0, 2e-6, 20e-6, 80e-6, 250e-6},
                           {10.0, 2.37, 20.0, 1.61, 0.7, 40, 2e-3}, compared, felt);
  // Both outcomes are exercised: touching and not touching the felt part.
  CHECK(felt > compared / 5);
  CHECK(felt < compared);
}

TEST_CASE(
    "the rolling ball's envelope equals the full scan on a field of high and low parts, up to and "
    "beyond its edges",
    "[dsp]") {
  // The scan's ceiling is the highest point of the tiles under the ball's track: on a field whose
  // low plain, gentle slope and tall, rough block differ, the result must still be the full
  // scan's, bit for bit, with the ball on each part, across their borders and past the edges
  // (where BoxMean clamps and shifts its window).
  const int w = 150, hgt = 110;
  const double pitch = 1.5e-4;
  std::vector<float> h(static_cast<std::size_t>(w * hgt));
  std::uint32_t state = 777u;
  for (int y = 0; y < hgt; ++y) {
    for (int x = 0; x < w; ++x) {
      state = state * 1664525u + 1013904223u;
      const double noise = static_cast<double>(state >> 8) / 16777216.0;
      double v = 0.0;  // plain
      if (x >= 90 && y >= 60)
        v = 300e-6 + 200e-6 * noise;  // block
      else if (x >= 40)
        v = 1e-6 * (x - 40) + 5e-6 * noise;  // slope
      h[static_cast<std::size_t>(y * w + x)] = static_cast<float>(v);
    }
  }
  test::OwnedField field(w, hgt, pitch, h);
  SurfaceReader reader;
  reader.Prepare(field.view);
  int compared = 0, felt = 0;
  CheckRollAgainstFullScan(reader, pitch, {0.0, 20e-6, 120e-6, 400e-6, 700e-6},
                           {-8.0, 2.77, -6.0, 2.03, 0.9, 60, 1e-3}, compared, felt);
  CHECK(felt > compared / 5);
  CHECK(felt < compared);
}

TEST_CASE("2-D fields are averaged over a square window", "[dsp]") {
  std::vector<float> h(10 * 10);
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x)
      h[static_cast<std::size_t>(y * 10 + x)] = static_cast<float>(x + 10 * y);
  test::OwnedField field(10, 10, 1.0, h);
  SurfaceReader reader;
  reader.Prepare(field.view);
  // Window [3, 6) x [4, 7): mean of x in {3,4,5} plus 10 * mean of y in {4,5,6}.
  CHECK(reader.BoxMean(4.5, 5.5, 3.0) == Approx(4.0 + 50.0).epsilon(1e-12));
}

TEST_CASE(
    "the scene goes idle after the pen is lifted and the sound has decayed, and wakes on "
    "the next touch",
    "[dsp][render]") {
  Scene scene;
  scene.Init(kFs);
  scene.Prepare(WoodLikeBoard(), OutputParams{}, HeightFieldView{});
  CHECK(scene.IsIdle());
  std::vector<float> out(2 * 48000);
  ProbeCommand tap;
  tap.tip_down = true;
  tap.landing_speed_mps = 0.5;
  tap.normal_force_n = 0.3;
  scene.Process(&tap, 1, out.data(), 4800);
  CHECK(!scene.IsIdle());
  ProbeCommand lift;
  scene.Process(&lift, 1, out.data(), 4800);
  CHECK(!scene.IsIdle());  // still ringing
  CHECK(scene.ResonatorEnergy() > 0.0);
  for (int i = 0; i < 20 && !scene.IsIdle(); ++i) scene.Process(nullptr, 0, out.data(), 48000);
  REQUIRE(scene.IsIdle());
  scene.Process(nullptr, 0, out.data(), 4800);
  float peak = 0.0f;
  for (int i = 0; i < 2 * 4800; ++i)
    peak = std::max(peak, std::fabs(out[static_cast<std::size_t>(i)]));
  CHECK(peak < 1e-6f);  // -120 dBFS
  scene.Process(&tap, 1, out.data(), 480);
  CHECK(!scene.IsIdle());
}

TEST_CASE(
    "passive sweep: one command at a set velocity advances the probe by v per second and "
    "the profile under it keeps the resonator sounding, a flat surface does not",
    "[dsp][render]") {
  auto sweep = [](const std::vector<float>& profile, double* x_after) {
    test::OwnedField field(static_cast<int>(profile.size()), 1, 0.153e-3, profile);
    MaterialParams m = WoodLikeBoard();
    m.friction.enabled = false;  // the profile alone, through the impact model
    for (auto& mode : m.resonator.modes) mode.decay_s *= 0.2;  // the landing rings out in 1 s
    Scene scene;
    scene.Init(kFs);
    scene.Prepare(m, OutputParams{}, field.view);
    ProbeCommand c;
    c.tip_down = true;
    c.x_m = 0.01;
    c.velocity_mps = 0.3;
    c.normal_force_n = 0.5;
    c.penetration_m = 60e-6;
    c.width_mm = 0.2;
    c.landing_speed_mps = 0.0;
    std::vector<float> out(2 * 72000);
    scene.Process(&c, 1, out.data(), 72000);  // 1.5 s: 0.45 m of profile
    *x_after = scene.probe_state().x_m;
    double energy = 0.0;  // sound energy in the last half second (the landing has rung out)
    for (std::size_t i = 2 * 48000; i < out.size(); i += 2) energy += out[i] * out[i];
    return energy;
  };
  double x_bumpy = 0.0, x_flat = 0.0;
  const double bumpy = sweep(BumpyProfile(), &x_bumpy);
  const double flat = sweep(std::vector<float>(4000, 25e-6f), &x_flat);
  CHECK(x_bumpy == Approx(0.01 + 0.45).epsilon(1e-9));
  CHECK(bumpy > 1e-4);
  CHECK(flat < 1e-3 * bumpy);
}

TEST_CASE(
    "white noise through the haptic channel keeps less than -40 dB of its energy above "
    "1 kHz",
    "[dsp]") {
  // Power spectrum by a plain radix-2 FFT (tests/support/fft.h, independent of the filter design).
  constexpr std::size_t kN = 1 << 16;
  std::vector<double> re(kN), im(kN, 0.0);
  OutputParams p;
  p.haptic_gain = 1.0;
  OutputStage stage;
  stage.Prepare(p, kFs);
  std::uint64_t state = 12345;
  for (std::size_t n = 0; n < kN + 4800; ++n) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    const double x = 0.05 * (static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5);
    float sound = 0.0f, haptic = 0.0f;
    stage.Process(0.0, x, &sound, &haptic);
    if (n >= 4800) re[n - 4800] = haptic;  // after the filters have settled
  }
  sas::test::FftInPlace(re, im);
  double total = 0.0, above = 0.0;
  for (std::size_t k = 1; k < kN / 2; ++k) {
    const double power = re[k] * re[k] + im[k] * im[k];
    total += power;
    if (static_cast<double>(k) * kFs / static_cast<double>(kN) > 1000.0) above += power;
  }
  REQUIRE(total > 0.0);
  CHECK(10.0 * std::log10(above / total) < -40.0);
}

TEST_CASE(
    "impact and friction can each be switched off: with both off nothing reaches the "
    "resonator, with one off the other still sounds",
    "[dsp][render]") {
  test::OwnedField field(4000, 1, 0.153e-3, BumpyProfile());
  auto render = [&](bool impact, bool friction) {
    MaterialParams m = WoodLikeBoard();
    m.impact.enabled = impact;
    m.friction.enabled = friction;
    Scene scene;
    scene.Init(kFs);
    scene.Prepare(m, OutputParams{}, field.view);
    const auto out = RenderTimed(scene, Gesture(), 24000, 128);
    double energy = 0.0;
    for (float s : out) energy += static_cast<double>(s) * s;
    return energy;
  };
  CHECK(render(false, false) == 0.0);
  CHECK(render(true, false) > 1e-3);
  CHECK(render(false, true) > 1e-3);
}
