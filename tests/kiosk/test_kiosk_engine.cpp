// The kiosk engine on the virtual clock (as the headless default runs it): pen timing, the
// click-free switch, the voice slot's life and the persisted counters, with the real textures.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <vector>

#include "files/material_file.h"
#include "kiosk/kiosk_engine.h"
#include "kiosk/synthetic_voice.h"
#include "platform/audio/audio_input.h"
#include "sas/version.h"
#include "support/smaps.h"
#include "support/temp_dir.h"
#include "support/true_peak.h"

using sas::kiosk::KioskEngine;
using sas::kiosk::KioskEngineOptions;
using sas::platform::PenReading;
using sas::test::AllDontDump;
using sas::test::VmFlagsOf;

namespace {

constexpr int kFrames = 128;
constexpr double kFs = 48000.0;
constexpr std::int64_t kBlockNs = 2'666'667;  // 128 frames at 48 kHz

KioskEngineOptions Options() {
  KioskEngineOptions options;
  options.virtual_clock = true;
  options.screen_width_px = 1920;
  options.screen_height_px = 1080;
  options.cues_dir = "/nonexistent";  // no spoken cues in the output: only the synth
  options.config.idle_timeout_s = 5.0;
  return options;
}

std::vector<float> RenderBlocks(KioskEngine& engine, int blocks) {
  std::vector<float> out(static_cast<std::size_t>(kFrames * 2 * blocks));
  for (int b = 0; b < blocks; ++b) engine.audio().Render(out.data() + b * kFrames * 2, kFrames, 2);
  return out;
}

double Rms(const std::vector<float>& stereo, std::size_t from, std::size_t to) {
  double sum = 0.0;
  for (std::size_t i = from; i < to; ++i) sum += static_cast<double>(stereo[2 * i]) * stereo[2 * i];
  return std::sqrt(sum / static_cast<double>(to - from));
}

PenReading Pen(std::int64_t t_ns, double x, double y, bool down) {
  PenReading pen;
  pen.time_ns = t_ns;
  pen.x_px = x;
  pen.y_px = y;
  pen.pressure = down ? 0.8 : 0.0;
  pen.tip_down = down;
  pen.origin = sas::platform::PenOrigin::kTablet;
  return pen;
}

// A mono 32-bit float WAV written byte by byte: the product's writer refuses NaN, a hostile file
// need not.
void WriteRawFloatWav(const std::string& path, const std::vector<float>& samples) {
  std::ofstream out(path, std::ios::binary);
  const auto u32 = [&](std::uint32_t v) { out.write(reinterpret_cast<const char*>(&v), 4); };
  const auto u16 = [&](std::uint16_t v) { out.write(reinterpret_cast<const char*>(&v), 2); };
  const auto bytes = static_cast<std::uint32_t>(samples.size() * 4);
  out.write("RIFF", 4);
  u32(36 + bytes);
  out.write("WAVEfmt ", 8);
  u32(16);
  u16(3);  // IEEE float
  u16(1);
  u32(48000);
  u32(48000 * 4);
  u16(4);
  u16(32);
  out.write("data", 4);
  u32(bytes);
  out.write(reinterpret_cast<const char*>(samples.data()), static_cast<std::streamsize>(bytes));
}

}  // namespace

TEST_CASE(
    "engine: a pen event is heard one audio buffer plus the safety stage's look-ahead after "
    "it happened, within one buffer + 1 ms",
    "[kiosk]") {
  KioskEngine engine(Options());
  engine.SetAudioRunning(true);
  RenderBlocks(engine, 11);  // silence; the virtual clock is now at the start of block 11
  // The pen event happened a third of the way into block 10's period; the control thread hands it
  // over before block 11 renders, which plays it at the same place in its own period.
  const std::int64_t event_ns = 10 * kBlockNs + kBlockNs / 3;
  engine.OnPen(Pen(event_ns, 960, 540, true));
  const auto out = RenderBlocks(engine, 1);
  int first = -1;
  for (int i = 0; i < kFrames; ++i) {
    if (out[static_cast<std::size_t>(2 * i)] != 0.0f ||
        out[static_cast<std::size_t>(2 * i + 1)] != 0.0f) {
      first = i;
      break;
    }
  }
  // Not before the event's own place in the period plus the safety stage's delay line.
  const int delay = sas::synth::SafetyStage::kDelayFrames;
  CHECK(first >= kFrames / 3 + delay);
  CHECK(first <= kFrames / 3 + delay + 8);
  const auto stats = engine.audio_stats();
  // The pen-to-sample delay is one buffer plus that delay line, to within a frame...
  CHECK(std::abs(static_cast<double>(stats.pen_to_sample_last_ns) - 1e9 * (kFrames + delay) / kFs) <
        1e9 / kFs + 1.0);
  // ...inside the budget of one buffer + 1 ms.
  CHECK(static_cast<double>(stats.pen_to_sample_last_ns) <= 1e9 * kFrames / kFs + 1e6);
  CHECK(stats.commands == 1);
}

TEST_CASE("engine: a texture switch fades the old sound out instead of cutting it", "[kiosk]") {
  KioskEngine engine(Options());
  engine.SetAudioRunning(true);
  engine.OnToken(0, 1);  // broken glass: rings after the pen lifts
  engine.Tick(0);
  RenderBlocks(engine, 200);
  std::int64_t t = 200 * kBlockNs;
  std::vector<float> audio;
  for (int i = 0; i < 120; ++i) {  // a 0.32 s stroke
    engine.OnPen(Pen(t, 600 + 3.0 * i, 500, true));
    const auto block = RenderBlocks(engine, 1);
    audio.insert(audio.end(), block.begin(), block.end());
    t += kBlockNs;
  }
  engine.OnPen(Pen(t, 960, 500, false));
  for (int i = 0; i < 4; ++i) {
    const auto block = RenderBlocks(engine, 1);
    audio.insert(audio.end(), block.begin(), block.end());
    t += kBlockNs;
  }
  const std::size_t switch_frame = audio.size() / 2;
  engine.OnToken(t, 3);  // cracked ground, pen up: the new scene is silent
  engine.Tick(t);
  const auto after = RenderBlocks(engine, 200);  // 0.53 s: past the 0.45 s fade
  audio.insert(audio.end(), after.begin(), after.end());
  const double before_rms = Rms(audio, switch_frame - 480, switch_frame);
  const double just_after_rms = Rms(audio, switch_frame, switch_frame + 480);
  REQUIRE(before_rms > 1e-4);                // the glass was ringing
  CHECK(just_after_rms > 0.4 * before_rms);  // no cut: the old sound is still there...
  const double later_rms = Rms(audio, audio.size() / 2 - 480, audio.size() / 2);
  CHECK(later_rms < 0.02 * before_rms);  // ...and gone once the fade is over
  CHECK(engine.audio_stats().switches >= 2);
}

TEST_CASE("engine: a recording becomes the surface, and the idle reset wipes it and the recorder",
          "[kiosk]") {
  sas::platform::FakeAudioInput mic;
  KioskEngine engine(Options());
  engine.SetRecorder(&mic.recorder());
  engine.SetAudioRunning(true);
  std::int64_t t = 0;
  const auto advance = [&](double seconds) {
    for (double s = 0.0; s < seconds; s += kFrames / kFs) {
      engine.Tick(t);
      if (mic.recorder().Recording()) {
        std::vector<float> block(kFrames);
        for (int i = 0; i < kFrames; ++i) {
          const double time_s = static_cast<double>(t) * 1e-9 + i / kFs;
          block[static_cast<std::size_t>(i)] = static_cast<float>(
              0.3 * std::sin(2 * M_PI * 220 * time_s) * std::sin(2 * M_PI * 2 * time_s));
        }
        mic.Feed(block.data(), block.size());
      }
      RenderBlocks(engine, 1);
      t += kBlockNs;
    }
  };
  engine.OnRecordButton(t, true);
  engine.OnRecordButton(t + 1'000'000, false);
  advance(5.5 + 5.2);  // countdown (intro, count, tone), then the whole 5 s take
  REQUIRE(engine.has_voice());
  REQUIRE(engine.surface().voice);
  REQUIRE(engine.voice_image() != nullptr);
  CHECK(mic.recorder().Take().samples.empty());  // the raw take is gone once it is a surface
  // Every buffer the voice became is in memory a core dump leaves out: the sound image, the
  // heights under the pen and the summed-area table (which gives the heights back).
  const auto& luminance = engine.voice_image()->luminance;
  CHECK(AllDontDump(VmFlagsOf(luminance.data(), luminance.size() * sizeof(float))));
  const auto field = engine.current_field();
  const auto view = field->View();
  CHECK(AllDontDump(VmFlagsOf(view.height_m, view.size() * sizeof(float))));
  const auto table_size = static_cast<std::size_t>(view.width + 1) *
                          static_cast<std::size_t>(view.height + 1) * sizeof(double);
  CHECK(AllDontDump(VmFlagsOf(view.summed_area, table_size)));
  advance(5.5);  // nobody touches it
  CHECK_FALSE(engine.has_voice());
  CHECK(engine.voice_image() == nullptr);
  CHECK_FALSE(engine.surface().voice);
  CHECK(engine.surface().texture == engine.default_texture());
}

// The share of a sound image's pixel rows that are flat grey: within 2 % of mid-grey across the
// whole row (silence; a quiet sound still moves some pixel of its row further).
double FlatGreyShare(const sas::surface::GrayImage& image) {
  int flat = 0;
  for (int y = 0; y < image.height; ++y) {
    float deviation = 0.0f;
    for (int x = 0; x < image.width; ++x) {
      deviation = std::max(
          deviation,
          std::fabs(image.luminance[static_cast<std::size_t>(y) * image.width + x] - 0.5f));
    }
    if (deviation < 0.02f) ++flat;
  }
  return static_cast<double>(flat) / std::max(1, image.height);
}

TEST_CASE(
    "engine: a visitor who starts late still fills the voice picture: the silence before the "
    "speech is cut, and the image's rows carry the voice",
    "[kiosk]") {
  sas::platform::FakeAudioInput mic;
  KioskEngine engine(Options());
  engine.SetRecorder(&mic.recorder());
  engine.SetAudioRunning(true);
  // 3 s of a quiet room (-70 dBFS noise), then 2 s of speech: 60 % of the 5 s take is silence.
  std::vector<float> take(static_cast<std::size_t>(3.0 * kFs));
  std::uint32_t noise = 1;
  for (auto& sample : take) {
    noise = noise * 1664525u + 1013904223u;
    sample = 3e-4f * (static_cast<float>(noise >> 8) / 8388608.0f - 1.0f);
  }
  const auto voice = sas::kiosk::SynthesiseVoice(kFs, 2.0);
  take.insert(take.end(), voice.begin(), voice.end());
  std::size_t fed = 0;
  std::int64_t t = 0;
  engine.OnRecordButton(t, true);
  engine.OnRecordButton(t + 1'000'000, false);
  for (double s = 0.0; s < 5.5 + 5.3; s += kFrames / kFs) {
    engine.Tick(t);
    if (mic.recorder().Recording() && fed < take.size()) {
      const std::size_t n = std::min<std::size_t>(kFrames, take.size() - fed);
      mic.Feed(take.data() + fed, n);
      fed += n;
    }
    RenderBlocks(engine, 1);
    t += kBlockNs;
  }
  REQUIRE(engine.has_voice());
  REQUIRE(engine.voice_image() != nullptr);
  // The whole take made into a picture as it was before the cut: most rows are the wait.
  const auto whole =
      sas::surface::SoundToImage(take, sas::kiosk::VoiceImageOptions(kFs, 5.0, take.size()));
  const double before = FlatGreyShare(whole);
  const double after = FlatGreyShare(*engine.voice_image());
  INFO("flat grey rows: whole take " << before << ", the kiosk's picture " << after);
  CHECK(before >= 0.55);
  CHECK(after <= 0.1);
  // The picture still has the screen's height, now in fewer, taller rows.
  CHECK(engine.voice_image()->height >= 1000);
  // Still the voice's memory: kept out of core dumps.
  const auto& luminance = engine.voice_image()->luminance;
  CHECK(AllDontDump(VmFlagsOf(luminance.data(), luminance.size() * sizeof(float))));
}

TEST_CASE("engine: strokes per texture survive a restart through the counters file", "[kiosk]") {
  sas::test::TempDir dir;
  auto options = Options();
  options.counters_path = dir.file("counters.toml");
  {
    KioskEngine engine(options);
    engine.SetAudioRunning(true);
    engine.OnToken(0, 0);  // bubble wrap
    for (int stroke = 0; stroke < 3; ++stroke) {
      const std::int64_t t = (stroke + 1) * 100 * kBlockNs;
      engine.OnPen(Pen(t, 500, 500, true));
      engine.OnPen(Pen(t + kBlockNs, 520, 500, true));
      engine.OnPen(Pen(t + 2 * kBlockNs, 540, 500, false));
    }
    std::string error;
    REQUIRE(engine.SaveCounters(&error));
  }
  KioskEngine restarted(options);
  const auto& counters = restarted.session().counters();
  CHECK(counters.strokes_per_texture.at(0) == 3);
  CHECK(counters.sessions == 1);
}

namespace {

// One 0.32 s stroke across wooden board (the default texture) rendered through the engine;
// returns the stereo output during it.
std::vector<float> StrokeOnDefaultTexture(bool low_vibration, double ambient_gain_db = 0.0) {
  KioskEngineOptions options = Options();
  // Quiet enough that the soft limiters stay linear: the gains are then exactly what is heard.
  options.config.sound_gain_db = -20.0;
  options.config.haptic_gain_db = -20.0;
  KioskEngine engine(options);
  engine.SetAudioRunning(true);
  engine.SetLowVibration(low_vibration);
  engine.SetAmbientGainDb(ambient_gain_db);  // the kiosk starts on its attract screen
  RenderBlocks(engine, 200);                 // past the 20 ms ramp and any 0.45 s cross-fade
  std::int64_t t = 200 * kBlockNs;
  std::vector<float> audio;
  for (int i = 0; i < 120; ++i) {
    engine.OnPen(Pen(t, 600 + 3.0 * i, 500, true));
    const auto block = RenderBlocks(engine, 1);
    audio.insert(audio.end(), block.begin(), block.end());
    t += kBlockNs;
  }
  return audio;
}

double ChannelRms(const std::vector<float>& stereo, int channel) {
  double sum = 0.0;
  for (std::size_t i = static_cast<std::size_t>(channel); i < stereo.size(); i += 2) {
    sum += static_cast<double>(stereo[i]) * stereo[i];
  }
  return std::sqrt(sum / static_cast<double>(stereo.size() / 2));
}

}  // namespace

TEST_CASE(
    "engine: staff low-vibration mode lowers the transducer by its configured dB and leaves "
    "the speaker as it was",
    "[kiosk]") {
  const auto normal = StrokeOnDefaultTexture(false);
  const auto gentle = StrokeOnDefaultTexture(true);
  REQUIRE(ChannelRms(normal, 1) > 1e-4);  // the stroke is felt
  const double drop_db = 20.0 * std::log10(ChannelRms(gentle, 1) / ChannelRms(normal, 1));
  CHECK(drop_db == Approx(-Options().config.low_vibration_db).margin(0.5));
  CHECK(ChannelRms(gentle, 0) == Approx(ChannelRms(normal, 0)).epsilon(1e-6));
}

TEST_CASE(
    "engine: an ambient gain set on the attract screen raises the next visitor's sound by "
    "that much and leaves the transducer alone",
    "[kiosk]") {
  const auto quiet_room = StrokeOnDefaultTexture(false, 0.0);
  const auto busy_room = StrokeOnDefaultTexture(false, 6.0);
  REQUIRE(ChannelRms(quiet_room, 0) > 1e-4);
  const double rise_db = 20.0 * std::log10(ChannelRms(busy_room, 0) / ChannelRms(quiet_room, 0));
  CHECK(rise_db == Approx(6.0).margin(0.5));
  CHECK(ChannelRms(busy_room, 1) == Approx(ChannelRms(quiet_room, 1)).epsilon(1e-6));
}

TEST_CASE(
    "engine: nothing reaches either output above its ceiling, whatever the source - cue "
    "files of 1e30 and NaN, the staff sweep in low-vibration mode, the test tone, the "
    "loudest strokes at the largest gains on the loudest material the loader accepts",
    "[kiosk][safety]") {
  // The wooden board's material with its first mode made as loud and long as the loader lets a
  // material be: light, undamped, full gain, ringing above -6 dBFS for just under the 2 s bound.
  sas::test::TempDir materials;
  {
    std::ifstream in(std::string(sas::kSourceDir) + "/textures/materials/wood.toml");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string mode = "{ frequency_hz = 323, decay_s = 0.0984, mass_kg = 0.417, gain = 0.53 }";
    const auto at = text.find(mode);
    REQUIRE(at != std::string::npos);
    text.replace(at, mode.size(), "{ frequency_hz = 323, decay_s = 0.8, mass_kg = 0.001, gain = 1.0 }");
    const auto loud = sas::kiosk::ParseMaterial(text, "wood.toml", "wood");  // accepted...
    const double ring = sas::kiosk::RingDownSeconds(loud.params);
    INFO("ring-down " << ring << " s");
    REQUIRE(ring > 1.5);  // ...and near the bound
    REQUIRE(ring <= sas::kiosk::kRingDownMaxSeconds);
    materials.Write("wood.toml", text);
  }
  sas::test::TempDir cues;
  // Hostile cue files where the kiosk looks for the texture names.
  std::vector<float> huge(48000, 1e30f), nan(48000, std::nanf(""));
  for (std::size_t i = 0; i < huge.size(); i += 2) huge[i] = -1e30f;
  for (const char* key : {"bubble_wrap", "broken_glass", "cracked_ground", "wooden_board"}) {
    WriteRawFloatWav(cues.file(std::string(key) + "_name.wav"), huge);
    WriteRawFloatWav(cues.file(std::string(key) + "_description.wav"), nan);
  }
  KioskEngineOptions options = Options();
  options.cues_dir = cues.path();
  options.materials_dir = materials.path().string();
  options.config.sound_gain_db = 40.0;  // every gain at its largest accepted value
  options.config.haptic_gain_db = 40.0;
  options.config.sound_ceiling_db = -6.0;
  options.config.haptic_ceiling_db = -20.0;
  options.config.low_vibration_db = 12.0;
  KioskEngine engine(options);
  bool loud_wood = false;  // the board plays the loud material
  for (const auto& texture : engine.textures()) {
    if (texture.key == "wooden_board") {
      loud_wood = texture.material.params.resonator.modes[0].mass_kg == 0.001;
    }
  }
  REQUIRE(loud_wood);
  engine.SetAudioRunning(true);
  const double speaker = std::pow(10.0, -6.0 / 20.0);
  double transducer = std::pow(10.0, -20.0 / 20.0);

  std::vector<float> audio;
  const auto play = [&](int blocks) {
    const auto out = RenderBlocks(engine, blocks);
    audio.insert(audio.end(), out.begin(), out.end());
  };
  std::int64_t t = 0;
  for (int token = 0; token < 4; ++token) {  // each switch speaks the (hostile) texture name
    engine.OnToken(t, token);
    engine.Tick(t);
    play(40);
    t += 40 * kBlockNs;
    for (int i = 0; i < 150; ++i) {  // a hard, fast scrape at full pressure
      PenReading pen = Pen(t, 300 + 8.0 * i, 300 + 2.0 * i, true);
      pen.pressure = 1.0;
      pen.tilt_x_deg = 0.0;
      engine.OnPen(pen);
      play(1);
      t += kBlockNs;
    }
    engine.OnPen(Pen(t, 1500, 600, false));
    play(40);
    t += 40 * kBlockNs;
  }
  engine.PlayTestTone();
  play(400);
  INFO("speaker ceiling " << speaker << ", transducer " << transducer);
  CHECK(engine.cues_loaded() == 0);  // the hostile cue files were refused at load
  for (const float v : audio) REQUIRE(std::isfinite(v));
  CHECK(sas::test::TruePeak(audio, 2, 0) <= speaker);
  CHECK(sas::test::TruePeak(audio, 2, 1) <= transducer);

  // Low-vibration mode lowers the transducer's ceiling: the full-scale staff sweep stays under it.
  engine.SetLowVibration(true);
  transducer *= std::pow(10.0, -12.0 / 20.0);
  audio.clear();
  RenderBlocks(engine, 1);  // the mode reaches the audio side at the next block
  engine.PlayTransducerSweep();
  play(900);
  CHECK(sas::test::TruePeak(audio, 2, 1) <= transducer);
  double peak = 0.0;
  for (std::size_t i = 1; i < audio.size(); i += 2)
    peak = std::max(peak, double(std::fabs(audio[i])));
  CHECK(peak <= transducer);
  CHECK(peak > 0.5 * transducer);  // the sweep did play, limited to the ceiling
}

TEST_CASE("engine: the staff's exposure figure is the mean square of what went to the speaker",
          "[kiosk][safety]") {
  KioskEngine engine(Options());
  engine.SetAudioRunning(true);
  std::vector<float> audio;
  std::int64_t t = 0;
  engine.Tick(t);
  for (int i = 0; i < 300; ++i) {  // a stroke at full pressure
    engine.OnPen(Pen(t, 400 + 4.0 * i, 500, true));
    engine.Tick(t);
    const auto block = RenderBlocks(engine, 1);
    audio.insert(audio.end(), block.begin(), block.end());
    t += kBlockNs;
  }
  engine.OnPen(Pen(t, 1600, 500, false));
  const auto tail = RenderBlocks(engine, 50);
  audio.insert(audio.end(), tail.begin(), tail.end());
  t += 50 * kBlockNs;
  engine.Tick(t);
  double sum = 0.0;
  for (std::size_t i = 0; i < audio.size(); i += 2) sum += double(audio[i]) * audio[i];
  const double expected_db = 10.0 * std::log10(sum / static_cast<double>(audio.size() / 2));
  REQUIRE(engine.exposure().LastHourDb());
  CHECK(*engine.exposure().LastHourDb() == Approx(expected_db).margin(0.01));
  CHECK(expected_db > -80.0);                // the stroke was heard
  REQUIRE(engine.exposure().LastVisitDb());  // the visit is still going on (no idle yet)
}

namespace {

// The speaker (channel 0) RMS of the staff test tone (1 s) and then the transducer (channel 1)
// RMS of the staff sweep (2 s), each over a steady 0.5 s (one clip plays at a time).
std::pair<double, double> StaffSignalsRms(KioskEngine& engine) {
  engine.SetAudioRunning(true);
  const auto rms = [&](int channel) {
    RenderBlocks(engine, 4);
    channel == 0 ? engine.PlayTestTone() : engine.PlayTransducerSweep();
    const auto out = RenderBlocks(engine, 300);  // 0.8 s
    double sum = 0.0;
    const std::size_t from = 9600, to = 33600;  // 0.2 .. 0.7 s
    for (std::size_t i = from; i < to; ++i) {
      const double x = out[2 * i + static_cast<std::size_t>(channel)];
      sum += x * x;
    }
    RenderBlocks(engine, 600);  // let the clip end
    return std::sqrt(sum / static_cast<double>(to - from));
  };
  const double speaker = rms(0);
  return {speaker, rms(1)};
}

}  // namespace

TEST_CASE("engine: staff volume and vibration steps change the output and survive a restart",
          "[kiosk]") {
  sas::test::TempDir dir;
  auto options = Options();
  const auto [speaker_ref, transducer_ref] = [&] {
    KioskEngine reference(options);  // no staff file: the configured gains alone
    return StaffSignalsRms(reference);
  }();
  REQUIRE(speaker_ref > 0.05);
  REQUIRE(transducer_ref > 0.05);
  options.staff_settings_path = dir.file("staff.toml");
  {
    KioskEngine engine(options);
    CHECK(engine.staff_settings() == sas::kiosk::StaffSettings{});
    engine.StepVolume(-1);
    engine.StepVolume(-1);     // -6 dB
    engine.StepVibration(-1);  // -3 dB
    engine.SetLowVibration(true);
    const auto [speaker, transducer] = StaffSignalsRms(engine);
    CHECK(20.0 * std::log10(speaker / speaker_ref) == Approx(-6.0).margin(0.1));
    // -3 dB, and low vibration's lowered ceiling limits the sweep's peaks further.
    CHECK(20.0 * std::log10(transducer / transducer_ref) < -3.0 + 0.1);
  }
  // Only the state folder's own file was written (the staff's configuration is never touched).
  std::vector<std::string> written;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    written.push_back(entry.path().filename().string());
  }
  CHECK(written == std::vector<std::string>{"staff.toml"});
  KioskEngine restarted(options);
  CHECK(restarted.staff_settings().volume_db == -6.0);
  CHECK(restarted.staff_settings().vibration_db == -3.0);
  CHECK(restarted.low_vibration());
  restarted.SetLowVibration(false);
  const auto [speaker, transducer] = StaffSignalsRms(restarted);
  CHECK(20.0 * std::log10(speaker / speaker_ref) == Approx(-6.0).margin(0.1));
  CHECK(20.0 * std::log10(transducer / transducer_ref) == Approx(-3.0).margin(0.1));
}

TEST_CASE(
    "engine: the configured transducer profile reaches ch 2: an LRA's staff sweep is drawn down "
    "at its resonance and driven harder below it",
    "[kiosk]") {
  auto options = Options();
  options.texture_paths = {std::string(sas::kSourceDir) + "/textures/wooden_board/texture.toml"};
  options.config.transducer_resonance_hz = 175.0;
  options.config.transducer_q = 10.0;
  KioskEngine engine(options);
  engine.SetAudioRunning(true);
  RenderBlocks(engine, 4);
  engine.PlayTransducerSweep();
  const auto out = RenderBlocks(engine, 760);  // 2.03 s
  // The sweep runs 40 -> 400 Hz in 2 s, exponentially (f = 40 Hz * 10^(t / 2 s)), at -6 dBFS:
  // uncompensated, an RMS of 0.5 / sqrt(2) anywhere in its middle.
  const auto db_over_sweep = [&](double from_s, double to_s) {
    double sum = 0.0;
    const auto from = static_cast<std::size_t>(from_s * kFs);
    const auto to = static_cast<std::size_t>(to_s * kFs);
    for (std::size_t i = from; i < to; ++i) sum += double(out[2 * i + 1]) * out[2 * i + 1];
    const double rms = std::sqrt(sum / static_cast<double>(to - from));
    return 20.0 * std::log10(rms / (0.5 / std::sqrt(2.0)));
  };
  // 170-180 Hz: the compensation takes out the LRA's resonant gain, -17 to -20 dB there.
  const double at_resonance_db = db_over_sweep(1.255, 1.30);
  // 46-56 Hz: +20 dB asked for, up to the ceiling (0 dBFS against the sweep's -6 dBFS).
  const double below_db = db_over_sweep(0.1, 0.3);
  INFO("at the resonance " << at_resonance_db << " dB, below it " << below_db << " dB");
  CHECK(at_resonance_db < -12.0);
  CHECK(below_db > 3.0);
  double peak = 0.0;
  for (std::size_t i = 1; i < out.size(); i += 2) peak = std::max(peak, double(std::fabs(out[i])));
  CHECK(peak <= 1.0);
}
