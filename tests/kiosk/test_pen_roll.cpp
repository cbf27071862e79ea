// Rolling with the pen: a held barrel button, reported by the pen source at the platform boundary
// (the fake standing in for libinput's TABLET_TOOL_BUTTON), through the kiosk's control loop to
// the engine and the scene; and what a button pressed or released mid-stroke sounds like.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tablet_rig.h"

using namespace sas;

namespace {

constexpr std::int64_t kBlockNs = 2'666'667;  // 128 frames at 48 kHz

// The kiosk under its control loop with a fake tablet; each pen reading the loop drains goes to
// the engine as the live kiosk hands it on (with `forced`, as the headless visit's roll strokes).
struct Rig : test::TabletRig {
  Rig() : TabletRig(std::make_unique<platform::FakePenSource>(true)) {}
  // One block of the kiosk's life: the tablet's reading (if any) from half a block ago, the
  // control loop's pass now, then the audio block that plays it.
  void Block(std::optional<platform::PenReading> reading = {}) {
    const std::int64_t now = blocks * kBlockNs;
    if (reading) {
      reading->time_ns = now - kBlockNs / 2;
      REQUIRE(fake->Push(*reading));
    }
    control.Step(now, [this](const platform::PenReading& r) { engine.OnPen(r, forced); });
    output.RenderBlocks(1);
    ++blocks;
  }

  std::optional<synth::ProbeStyle> forced;
  std::int64_t blocks = 0;
};

platform::PenReading TabletReading(double x_px, bool down, bool barrel) {
  platform::PenReading r;
  r.x_px = x_px;
  r.y_px = 540.0;
  r.pressure = down ? 0.5 : 0.0;
  r.tip_down = down;
  r.in_proximity = true;
  r.barrel_button = barrel;
  return r;
}

// Channel 1 of interleaved stereo.
std::vector<float> Sound(const std::vector<float>& stereo) {
  std::vector<float> out(stereo.size() / 2);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = stereo[2 * i];
  return out;
}

double Rms(const std::vector<float>& a) {
  double sum = 0.0;
  for (const float v : a) sum += static_cast<double>(v) * v;
  return std::sqrt(sum / static_cast<double>(std::max<std::size_t>(a.size(), 1)));
}

// Puts the token of the texture `key` on its switch and lets the cross-fade end.
void Choose(Rig& rig, const std::string& key) {
  const auto& textures = rig.engine.textures();
  for (std::size_t t = 0; t < textures.size(); ++t) {
    if (textures[t].key != key) continue;
    rig.engine.OnToken(rig.blocks * kBlockNs, rig.engine.TokenForTexture(t));
    for (int i = 0; i < 240; ++i) rig.Block();  // 0.64 s: past the 0.45 s cross-fade
    REQUIRE(rig.engine.surface().texture == static_cast<int>(t));
    rig.output.ClearBuffer();
    return;
  }
  FAIL("no texture " << key);
}

// An upright pen stroking along the screen's middle at 100 mm/s, a report every two blocks (a
// 188 Hz tablet: 2 px at 0.265 mm a pixel). `barrel(i)`: the button before report i.
constexpr double kPxPerReport = 0.1 * 2.0 * 128.0 / 48000.0 / 0.265e-3;

}  // namespace

TEST_CASE(
    "pen roll: a barrel button held, from the pen source through the control loop, makes the "
    "stroke a roll: the engine's stroke style is the roll's and the sound is the forced roll's "
    "sample for sample, unlike the plain stroke's",
    "[kiosk]") {
  // The same stroke three times: barrel button held (as the tablet reports it), no button but
  // the roll forced as the headless visit forces it, and neither.
  const auto stroke = [](bool barrel, std::optional<synth::ProbeStyle> forced,
                         synth::ProbeStyle* style) {
    Rig rig;
    rig.forced = forced;
    rig.output.ClearBuffer();
    double x = 400.0;
    for (int i = 0; i < 120; ++i) {
      rig.Block(TabletReading(x += kPxPerReport, true, barrel));
      rig.Block();
      if (i == 60) *style = rig.engine.stroke_style();
    }
    rig.Block(TabletReading(x, false, false));
    for (int i = 0; i < 60; ++i) rig.Block();
    return rig.output.buffer();
  };
  synth::ProbeStyle barrel_style{}, forced_style{}, plain_style{};
  const auto barrel = stroke(true, {}, &barrel_style);
  const auto forced = stroke(false, synth::ProbeStyle::kRoll, &forced_style);
  const auto plain = stroke(false, {}, &plain_style);
  CHECK(barrel_style == synth::ProbeStyle::kRoll);
  CHECK(forced_style == synth::ProbeStyle::kRoll);
  CHECK(plain_style == synth::ProbeStyle::kScrape);
  REQUIRE(barrel.size() == forced.size());
  REQUIRE(barrel.size() == plain.size());
  CHECK(barrel == forced);  // both channels, every sample
  std::vector<float> difference(plain.size());
  for (std::size_t i = 0; i < plain.size(); ++i) difference[i] = barrel[i] - plain[i];
  const double plain_rms = Rms(Sound(plain));
  INFO("plain rms " << plain_rms << ", roll rms " << Rms(Sound(barrel)));
  REQUIRE(plain_rms > 1e-4);
  CHECK(Rms(Sound(difference)) > 0.2 * plain_rms);  // 0.40 measured
}

TEST_CASE(
    "pen roll: the barrel button pressed and let go mid-stroke on cracked ground switches the "
    "style at once and without a click: at no switch does the sound's largest sample-to-sample "
    "step exceed twice the stroke's own 99th percentile",
    "[kiosk]") {
  Rig rig;
  Choose(rig, "cracked_ground");
  double x = 300.0;
  bool barrel = false;
  std::vector<std::int64_t> switch_blocks;
  const std::int64_t start = rig.blocks;
  for (int i = 0; i < 700; ++i) {
    rig.Block(TabletReading(x += kPxPerReport, true, barrel));
    if (i >= 30 && i % 40 == 0) {
      // Between two position reports, as libinput reports a button: a reading of its own.
      barrel = !barrel;
      auto button = TabletReading(x, true, barrel);
      button.kind = platform::PenReadingKind::kButton;
      switch_blocks.push_back(rig.blocks - start);
      rig.Block(button);
      CHECK(rig.engine.stroke_style() ==
            (barrel ? synth::ProbeStyle::kRoll : synth::ProbeStyle::kScrape));
    } else {
      rig.Block();
    }
  }
  rig.Block(TabletReading(x, false, false));
  const auto sound = Sound(rig.output.buffer());
  // The largest step in each millisecond; the stroke's own: every millisecond away from the
  // switches (20 ms before to 40 ms after) and from the landing.
  constexpr std::size_t kWindow = 48;
  std::vector<double> steps;
  for (std::size_t w = 0; w + kWindow < sound.size(); w += kWindow) {
    double largest = 0.0;
    for (std::size_t i = w + 1; i < w + kWindow; ++i)
      largest = std::max(largest, static_cast<double>(std::fabs(sound[i] - sound[i - 1])));
    steps.push_back(largest);
  }
  const auto window_of = [&](std::int64_t block) {
    return static_cast<std::size_t>(block) * 128 / kWindow;
  };
  std::vector<bool> near(steps.size(), false);
  for (const auto block : switch_blocks) {
    for (std::size_t k = window_of(block) - 20; k < window_of(block) + 40 && k < steps.size(); ++k)
      near[k] = true;
  }
  std::vector<double> own;
  for (std::size_t k = 200; k + 100 < steps.size(); ++k) {
    if (!near[k]) own.push_back(steps[k]);
  }
  REQUIRE(own.size() > 1000);
  std::sort(own.begin(), own.end());
  const double p99 = own[own.size() * 99 / 100];
  REQUIRE(p99 > 1e-4);
  for (std::size_t n = 0; n < switch_blocks.size(); ++n) {
    // From 2 ms before the button's block to 15 ms after it (the glide takes 20 ms).
    double at = 0.0;
    const std::size_t w0 = window_of(switch_blocks[n]);
    for (std::size_t k = w0 - 2; k < w0 + 15; ++k) at = std::max(at, steps[k]);
    INFO("switch " << n << (n % 2 == 0 ? " to roll" : " to scrape"));
    CHECK(at <= 2.0 * p99);
  }
}

TEST_CASE("pen source: a barrel button counts only while the pen is in proximity", "[kiosk]") {
  platform::FakePenSource source(true);
  std::string error;
  REQUIRE(source.Start(&error));
  auto reading = TabletReading(100.0, false, true);
  REQUIRE(source.Push(reading));
  reading.in_proximity = false;
  reading.kind = platform::PenReadingKind::kProximityOut;
  REQUIRE(source.Push(reading));
  platform::PenReading popped;
  REQUIRE(source.Pop(popped));
  CHECK(popped.barrel_button);
  REQUIRE(source.Pop(popped));
  CHECK_FALSE(popped.barrel_button);
}
