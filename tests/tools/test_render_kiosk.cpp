// `render --texture` and `render --voice` against the kiosk itself: the kiosk engine set up as the
// box starts (the shipped kiosk.toml, all four textures loaded, the texture under test as the
// configured default, or a voice recorded through the record button), a pen stroke given as
// screen pixels (the script the calibration and the headless visit use), and the same stroke
// handed to `render` as a gesture in millimetres on the texture's field. What comes out must be
// the same samples: the same relief, bubbles, material, gains and safety stage.
#include <sndfile.h>
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "files/kiosk_config.h"
#include "kiosk/device_configs.h"
#include "kiosk/kiosk_engine.h"
#include "kiosk/synthetic_voice.h"
#include "kiosk/virtual_visit.h"
#include "platform/audio/audio_input.h"
#include "sas/version.h"
#include "support/temp_dir.h"
#include "surface/wav_writer.h"
#include "tools/render_command.h"

namespace {

using sas::kiosk::KioskEngine;
using sas::kiosk::KioskEngineOptions;
using sas::kiosk::PenStroke;
using sas::kiosk::RenderOptions;
using sas::kiosk::VirtualVisit;

constexpr int kWidthPx = 1920;
constexpr int kHeightPx = 1080;
const std::string kShippedConfig = std::string(sas::kSourceDir) + "/install/kiosk.toml";

KioskEngineOptions ShippedKiosk(const std::string& default_texture) {
  KioskEngineOptions options;
  options.config = sas::kiosk::LoadKioskConfig(kShippedConfig);
  options.config.default_texture = default_texture;
  options.screen_width_px = kWidthPx;
  options.screen_height_px = kHeightPx;
  options.virtual_clock = true;
  options.spoken_cues = false;  // render plays no cues
  return options;
}

// The stroke as `render` takes it: its two ends in millimetres on the field under the pen.
std::string GestureCsv(const KioskEngine& engine, const PenStroke& stroke) {
  const double pitch_mm = engine.current_field()->pitch_m() * 1e3;
  double fx0 = 0.0, fy0 = 0.0, fx1 = 0.0, fy1 = 0.0;
  engine.ScreenToField(stroke.x0 * kWidthPx, stroke.y0 * kHeightPx, &fx0, &fy0);
  engine.ScreenToField(stroke.x1 * kWidthPx, stroke.y1 * kHeightPx, &fx1, &fy1);
  char text[400];
  std::snprintf(text, sizeof text,
                "t,x,y,pressure,tilt\n0,%.17g,%.17g,%.17g,%.17g\n%.17g,%.17g,%.17g,%.17g,%.17g\n",
                fx0 * pitch_mm, fy0 * pitch_mm, stroke.pressure, stroke.tilt_deg, stroke.duration_s,
                fx1 * pitch_mm, fy1 * pitch_mm, stroke.pressure, stroke.tilt_deg);
  return text;
}

std::vector<float> RenderCommand(const std::vector<std::string>& args) {
  const sas::kiosk::RenderOptions options = sas::kiosk::ParseRenderArgs(args);
  std::vector<float> audio;
  sas::kiosk::RenderToMemory(options, audio);
  return audio;
}

struct Comparison {
  double peak[2] = {0.0, 0.0};
  double max_difference[2] = {0.0, 0.0};
  std::size_t frames = 0;
  std::size_t first_difference = 0;  // frame of the first sample differing by more than 1e-5
};

Comparison Compare(const std::vector<float>& kiosk, const std::vector<float>& render) {
  Comparison c;
  c.frames = std::min(kiosk.size(), render.size()) / 2;
  for (std::size_t i = 0; i < c.frames * 2; ++i) {
    const int ch = static_cast<int>(i % 2);
    c.peak[ch] = std::max(c.peak[ch], static_cast<double>(std::fabs(kiosk[i])));
    const double difference = std::fabs(kiosk[i] - render[i]);
    if (difference > 1e-5 && c.first_difference == 0) c.first_difference = i / 2 + 1;
    c.max_difference[ch] = std::max(c.max_difference[ch], difference);
  }
  return c;
}

double Db(double linear) {
  return linear > 0.0 ? 20.0 * std::log10(linear) : -999.0;
}

}  // namespace

TEST_CASE("render --texture plays what the kiosk engine plays, sample for sample, on every texture",
          "[render]") {
  struct Case {
    const char* texture;
    PenStroke stroke;
  };
  // Places and gestures no calibration uses: a diagonal, a firm press on bubble wrap (its pops),
  // a tilted rub, a light fast scrape.
  const Case cases[] = {
      {"bubble_wrap", {0.31, 0.27, 0.47, 0.61, 0.9, 0.95, 0.0, {}, 0.0}},
      {"broken_glass", {0.62, 0.18, 0.34, 0.36, 0.7, 0.5, 35.0, {}, 0.0}},
      {"wooden_board", {0.12, 0.83, 0.71, 0.77, 0.5, 0.25, 0.0, {}, 0.0}},
      {"cracked_ground", {0.55, 0.52, 0.58, 0.91, 1.1, 0.7, 0.0, {}, 0.0}},
  };
  const double tail_s = 0.5;
  for (const auto& c : cases) {
    DYNAMIC_SECTION(c.texture) {
      KioskEngine engine(ShippedKiosk(c.texture));
      REQUIRE(engine.texture_failures().empty());
      REQUIRE(engine.textures().size() == 4);
      VirtualVisit visit(engine);
      visit.Advance(c.stroke.duration_s + tail_s,
                    sas::kiosk::StraightStroke(c.stroke, 0.0, kWidthPx, kHeightPx));

      sas::test::TempDir dir;
      const std::string gesture = dir.Write("stroke.csv", GestureCsv(engine, c.stroke));
      const std::vector<float> render =
          RenderCommand({"--texture", c.texture, "--config", kShippedConfig, "--gesture", gesture,
                         "--tail-s", std::to_string(tail_s), "--out", dir.file("r.wav")});
      const auto expected_frames =
          static_cast<std::size_t>(std::ceil((c.stroke.duration_s + tail_s) * 48000.0));
      REQUIRE(render.size() == expected_frames * 2);
      REQUIRE(visit.output().size() >= render.size());

      const Comparison cmp = Compare(visit.output(), render);
      INFO(c.texture << ": sound peak " << Db(cmp.peak[0]) << " dBFS, haptic peak "
                     << Db(cmp.peak[1]) << " dBFS; largest difference " << cmp.max_difference[0]
                     << " / " << cmp.max_difference[1] << ", first at frame "
                     << cmp.first_difference);
      // The stroke must be heard, or equality proves nothing.
      CHECK(Db(cmp.peak[0]) > -40.0);
      CHECK(Db(cmp.peak[1]) > -40.0);
      // The pen's millimetres go back to pixels through the kiosk's own cover transform: a
      // rounding of 1e-13 px at most, which no sample may show beyond 1e-5 of full scale.
      CHECK(cmp.max_difference[0] <= 1e-5);
      CHECK(cmp.max_difference[1] <= 1e-5);
    }
  }
}

TEST_CASE("render --voice records the take as the kiosk does and plays its voice surface",
          "[render]") {
  sas::test::TempDir dir;
  const std::vector<float> voice = sas::kiosk::SynthesiseVoice(48000.0, 2.0, 150.0);
  const std::string take = dir.file("take.wav");
  sas::surface::WriteWav(take, voice.data(), voice.size(), 1, 48000);

  // The kiosk: the visitor presses the record button, speaks after the countdown, presses again.
  KioskEngineOptions options = ShippedKiosk("wooden_board");
  KioskEngine engine(options);
  sas::platform::FakeAudioInput microphone(sas::kiosk::RecorderConfigFor(engine.config()));
  engine.SetRecorder(&microphone.recorder());
  microphone.Start();
  VirtualVisit visit(engine);
  visit.SetMicrophone(&microphone);
  visit.SetVoice(voice);
  engine.OnRecordButton(visit.now_ns(), true);
  visit.Advance(0.2);
  engine.OnRecordButton(visit.now_ns(), false);
  for (int i = 0; i < 4000 && visit.voice_left() > 0; ++i) visit.Advance(0.05);
  for (int i = 0; i < 4000 && engine.session().mode() == sas::kiosk::SessionMode::kRecording; ++i) {
    engine.OnRecordButton(visit.now_ns(), true);
    visit.Advance(0.1);
    engine.OnRecordButton(visit.now_ns(), false);
  }
  for (int i = 0; i < 4000 && !engine.surface().voice; ++i) visit.Advance(0.05);
  REQUIRE(engine.has_voice());
  REQUIRE(engine.surface().voice);
  visit.Advance(2.0);  // the cross-fade has run; the kiosk is quiet
  visit.ClearOutput();
  const PenStroke stroke{0.2, 0.35, 0.8, 0.6, 0.8, 0.7, 0.0, {}, 0.0};
  const double tail_s = 0.4;
  visit.Advance(stroke.duration_s + tail_s,
                sas::kiosk::StraightStroke(stroke, visit.now_s(), kWidthPx, kHeightPx));

  const std::string gesture = dir.Write("stroke.csv", GestureCsv(engine, stroke));
  const std::vector<float> render =
      RenderCommand({"--voice", take, "--config", kShippedConfig, "--gesture", gesture, "--tail-s",
                     std::to_string(tail_s), "--out", dir.file("r.wav")});
  const Comparison cmp = Compare(visit.output(), render);
  INFO("sound peak " << Db(cmp.peak[0]) << " dBFS, largest difference " << cmp.max_difference[0]
                     << " / " << cmp.max_difference[1]);
  CHECK(Db(cmp.peak[0]) > -40.0);
  CHECK(cmp.max_difference[0] <= 1e-5);
  CHECK(cmp.max_difference[1] <= 1e-5);
}

TEST_CASE("render names what the kiosk would refuse or the command cannot mean", "[render]") {
  sas::test::TempDir dir;
  const std::string silent = dir.file("silent.wav");
  const std::vector<float> zeros(48000, 0.0f);
  sas::surface::WriteWav(silent, zeros.data(), zeros.size(), 1, 48000);
  std::vector<float> audio;
  const auto render = [&](const std::vector<std::string>& args) {
    sas::kiosk::RenderToMemory(sas::kiosk::ParseRenderArgs(args), audio);
  };
  CHECK_THROWS_WITH(render({"--voice", silent, "--out", "x.wav"}), Catch::Contains("silent"));
  CHECK_THROWS_WITH(render({"--texture", dir.path().string(), "--out", "x.wav"}),
                    Catch::Contains("texture.toml"));
  CHECK_THROWS_WITH(render({"--texture", "velvet", "--out", "x.wav"}),
                    Catch::Contains("broken_glass"));
  // A texture under --profile would be its generator's height map: only by asking for it.
  CHECK_THROWS_WITH(render({"--profile", "broken_glass", "--out", "x.wav"}),
                    Catch::Contains("--true-height"));
  CHECK_THROWS_WITH(sas::kiosk::ParseRenderArgs(
                        {"--texture", "bubble_wrap", "--material", "wood", "--out", "x.wav"}),
                    Catch::Contains("own material"));
  CHECK_THROWS_WITH(sas::kiosk::ParseRenderArgs(
                        {"--texture", "bubble_wrap", "--profile", "flat", "--out", "x.wav"}),
                    Catch::Contains("give one"));
  CHECK_THROWS_WITH(sas::kiosk::ParseRenderArgs({"--true-height", "--out", "x.wav"}),
                    Catch::Contains("--texture"));
  CHECK_THROWS_WITH(sas::kiosk::ParseRenderArgs({"--config", "k.toml", "--out", "x.wav"}),
                    Catch::Contains("--config"));
}

TEST_CASE("render --texture plays the picture's relief and --true-height the generator's map",
          "[render]") {
  sas::test::TempDir dir;
  const std::string gesture =
      dir.Write("g.csv", "t,x,y,pressure,tilt\n0,40,40,0.6,0\n0.6,100,60,0.6,0\n");
  const std::vector<float> kiosk =
      RenderCommand({"--texture", "wooden_board", "--gesture", gesture, "--out", "k.wav"});
  const std::vector<float> bare = RenderCommand(
      {"--texture", "wooden_board", "--true-height", "--gesture", gesture, "--out", "b.wav"});
  REQUIRE(kiosk.size() == bare.size());
  const Comparison cmp = Compare(kiosk, bare);
  INFO("largest difference " << cmp.max_difference[0] << " at peak " << cmp.peak[0]);
  CHECK(cmp.max_difference[0] > 0.1 * cmp.peak[0]);
}

TEST_CASE("render --texture bubble_wrap pops bubbles under a firm press and none under a light one",
          "[render]") {
  sas::test::TempDir dir;
  const auto run = [&](double pressure) {
    char csv[160];
    std::snprintf(csv, sizeof csv, "t,x,y,pressure,tilt\n0,40,40,%g,0\n1,80,60,%g,0\n", pressure,
                  pressure);
    RenderOptions options =
        sas::kiosk::ParseRenderArgs({"--texture", "bubble_wrap", "--gesture",
                                     dir.Write("g.csv", csv), "--tail-s", "0.2", "--out", "b.wav"});
    std::vector<float> audio;
    const auto summary = sas::kiosk::RenderToMemory(options, audio);
    return std::make_pair(summary, sas::kiosk::FormatSummary(options, summary));
  };
  const auto [firm, firm_text] = run(0.95);
  CHECK(firm.popped_bubbles >= 1);
  CHECK_THAT(firm_text, Catch::Contains("bubbles popped"));
  const auto [light, light_text] = run(0.2);
  CHECK(light.popped_bubbles == 0);
  CHECK_THAT(light_text, !Catch::Contains("popped"));
}
