// The spoken cues' voices: the build uses a committed render only while its sentence is the
// string table's (else espeak-ng, said once), the committed renders decode and are normalised like
// every cue, and the voice survey's figures (textures/voice_figures.h) are right on signals whose
// answer is known.
#include <sndfile.h>
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "cue_voice.h"
#include "files/strings.h"
#include "kiosk/staff_cues.h"
#include "support/temp_dir.h"
#include "surface/audio_file.h"
#include "surface/loudness.h"
#include "surface/wav_writer.h"
#include "voice_figures.h"

namespace fs = std::filesystem;
using sas::cues::Speech;

namespace {

Speech Tone(double hz, double seconds, double rate_hz, double amplitude = 0.3) {
  Speech s;
  s.rate_hz = rate_hz;
  s.samples.resize(static_cast<std::size_t>(seconds * rate_hz));
  for (std::size_t i = 0; i < s.samples.size(); ++i) {
    s.samples[i] = static_cast<float>(
        amplitude * std::sin(2.0 * std::numbers::pi * hz * static_cast<double>(i) / rate_hz));
  }
  return s;
}

// The frequency of a clip's strongest zero-crossing rate: enough to tell two tones apart.
double ZeroCrossingHz(const std::vector<float>& x, double rate_hz) {
  std::size_t crossings = 0;
  for (std::size_t i = 1; i < x.size(); ++i) crossings += (x[i - 1] < 0.0f) != (x[i] < 0.0f);
  return 0.5 * static_cast<double>(crossings) * rate_hz / static_cast<double>(x.size());
}

std::string Run(const std::string& command) {
  std::string out;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  REQUIRE(pipe != nullptr);
  char buf[4096];
  while (std::fgets(buf, sizeof buf, pipe) != nullptr) out += buf;
  const int status = pclose(pipe);
  out += "\nexit " + std::to_string(WEXITSTATUS(status));
  return out;
}

}  // namespace

TEST_CASE("a committed render is chosen only while its sentence equals the table's", "[tools]") {
  sas::test::TempDir dir;
  fs::create_directories(dir.path() / "en");
  sas::cues::WriteRender(dir.file("en/count_1.opus"), Tone(440.0, 0.5, 16000.0));
  sas::cues::WriteText(dir.file("en/count_1.txt"), "One.");
  sas::cues::WriteRender(dir.file("en/count_2.opus"), Tone(440.0, 0.5, 16000.0));
  sas::cues::WriteText(dir.file("en/count_2.txt"), "Two.");

  CHECK(sas::cues::ChooseRender(dir.path().string(), "en", "count_1", "One.").use_render);
  const auto changed = sas::cues::ChooseRender(dir.path().string(), "en", "count_2", "Two!");
  CHECK_FALSE(changed.use_render);
  CHECK(changed.why == "sentence changed");
  const auto missing = sas::cues::ChooseRender(dir.path().string(), "en", "count_3", "Three.");
  CHECK_FALSE(missing.use_render);
  CHECK(missing.why == "no render");
  CHECK_FALSE(sas::cues::ChooseRender(dir.path().string(), "de", "count_1", "One.").use_render);
  CHECK_FALSE(sas::cues::ChooseRender("", "en", "count_1", "One.").use_render);
}

TEST_CASE(
    "cue_maker builds a cue from its committed render when the sentence matches and from "
    "espeak-ng when it changed, and says so once",
    "[tools]") {
  sas::test::TempDir dir;
  // A stand-in for espeak-ng: writes a 1 kHz tone at 22.05 kHz wherever -w says.
  const Speech espeak_tone = Tone(1000.0, 0.6, 22050.0);
  sas::surface::WriteWav(dir.file("espeak.wav"), espeak_tone.samples.data(),
                         espeak_tone.samples.size(), 1, 22050);
  const std::string fake = dir.Write(
      "espeak", "#!/bin/sh\nwhile [ $# -gt 0 ]; do [ \"$1\" = -w ] && cp '" + dir.file("espeak.wav") +
                    "' \"$2\"; shift; done\n");
  chmod(fake.c_str(), 0755);
  // Renders for English: one current, one whose sentence the table has since changed.
  const auto en = sas::kiosk::LoadLanguageTable(SAS_SOURCE_DIR "/textures/strings", "en");
  fs::create_directories(dir.path() / "renders/en");
  sas::cues::WriteRender(dir.file("renders/en/count_3.opus"), Tone(300.0, 0.6, 16000.0));
  sas::cues::WriteText(dir.file("renders/en/count_3.txt"), en.CueText("count_3"));
  sas::cues::WriteRender(dir.file("renders/en/too_loud.opus"), Tone(300.0, 0.6, 16000.0));
  sas::cues::WriteText(dir.file("renders/en/too_loud.txt"), "An older sentence.");

  const std::string out = Run(std::string(CUE_MAKER) + " --espeak " + fake +
                              " --strings " SAS_SOURCE_DIR "/textures/strings --textures-dir " SAS_SOURCE_DIR
                              "/textures --renders " + dir.file("renders") + " --out " +
                              dir.file("cues"));
  INFO(out);
  REQUIRE(out.find("exit 0") != std::string::npos);
  sas::surface::AudioReadLimits limits;
  const auto rendered = sas::surface::ReadAudioFile(dir.file("cues/en/count_3.wav"), limits);
  const auto fell_back = sas::surface::ReadAudioFile(dir.file("cues/en/too_loud.wav"), limits);
  CHECK(std::fabs(ZeroCrossingHz(rendered.samples, 48000.0) - 300.0) < 10.0);
  CHECK(std::fabs(ZeroCrossingHz(fell_back.samples, 48000.0) - 1000.0) < 10.0);
  CHECK(sas::cues::ReadText(dir.file("cues/en/too_loud.txt")) == en.CueText("too_loud"));
  // Every cue was made, at the cues' loudness, whichever voice spoke it.
  for (const char* f : {"cues/en/count_3.wav", "cues/en/too_loud.wav"}) {
    const auto clip = sas::surface::ReadAudioFile(dir.file(f), limits);
    CHECK(std::fabs(sas::surface::KWeightedLoudnessDb(clip.samples, 48000.0, 0,
                                                      clip.samples.size()) -
                    sas::cues::kCueLoudnessLufs) < 0.5);
  }
  // One line names the fallbacks of the language that has renders, and only those.
  CHECK(out.find("en/too_loud (sentence changed)") != std::string::npos);
  CHECK(out.find("en/count_2 (no render)") != std::string::npos);
  CHECK(out.find("en/count_3 (") == std::string::npos);
  CHECK(out.find("de/") == std::string::npos);
  CHECK(out.find("regenerate_voices") == out.rfind("regenerate_voices"));

  CHECK(Run(std::string(CUE_MAKER) + " --help").find("exit 0") != std::string::npos);
  CHECK(Run(std::string(CUE_MAKER) + " --no-such-flag").find("exit 2") != std::string::npos);
  CHECK(Run(std::string(CUE_MAKER) + " --espeak /nonexistent --strings " + dir.file("none") +
            " --textures-dir " + dir.file("none") + " --out " + dir.file("x"))
            .find("exit 1") != std::string::npos);
}

TEST_CASE("the committed renders decode, speak a listed sentence and are normalised like every cue",
          "[tools]") {
  const fs::path renders = SAS_SOURCE_DIR "/textures/voices";
  std::uintmax_t bytes = 0;
  std::size_t count = 0;
  for (const auto& language : fs::directory_iterator(renders)) {
    if (!language.is_directory()) continue;
    for (const auto& file : fs::directory_iterator(language.path())) {
      if (file.path().extension() != ".opus") continue;
      INFO(file.path().string());
      bytes += fs::file_size(file.path());
      ++count;
      fs::path text = file.path();
      text.replace_extension(".txt");
      REQUIRE(fs::is_regular_file(text));
      CHECK_FALSE(sas::cues::ReadText(text.string()).empty());
      const Speech speech = sas::cues::ReadRender(file.path().string());
      CHECK(speech.rate_hz == 16000.0);
      const auto shaped = sas::cues::ShapeCue(speech);
      const double seconds = static_cast<double>(shaped.size()) / sas::cues::kCueRateHz;
      // The bounds a staff recording of the same cue must keep (kiosk/staff_cues.h).
      const auto limits = sas::kiosk::DurationLimitsFor(file.path().stem().string());
      CHECK(seconds >= limits.min_s);
      CHECK(seconds <= limits.max_s);
      const double lufs = sas::surface::KWeightedLoudnessDb(shaped, sas::cues::kCueRateHz, 0,
                                                            shaped.size());
      CHECK(lufs <= sas::cues::kCueLoudnessLufs + 0.5);
      CHECK(lufs >= -30.0);
      float peak = 0.0f;
      for (float v : shaped) peak = std::max(peak, std::fabs(v));
      CHECK(20.0 * std::log10(peak) <= sas::cues::kCuePeakDbfs + 0.01);
    }
  }
  CHECK(count > 0);
  CHECK(bytes <= 3u * 1024u * 1024u);
}

TEST_CASE("the voice figures are right on signals with a known answer", "[tools]") {
  const double fs_hz = 16000.0;
  SECTION("band edge of a flat comb up to 4 kHz") {
    std::vector<float> x(static_cast<std::size_t>(fs_hz));
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> phase(0.0, 2.0 * std::numbers::pi);
    for (double f = 100.0; f <= 4000.0; f += 50.0) {
      const double p = phase(rng);
      for (std::size_t i = 0; i < x.size(); ++i) {
        x[i] += static_cast<float>(0.01 * std::sin(2.0 * std::numbers::pi * f * double(i) / fs_hz + p));
      }
    }
    CHECK(std::fabs(sas::cues::BandEdgeHz(x, fs_hz) - 4000.0) <= 100.0);
  }
  SECTION("F0 of a steady pulse train and the range of a one-octave glide") {
    // A voice-like source: each period a pulse ringing at 800 Hz (bandwidth 160 Hz).
    auto pulses = [&](double f_from, double f_to, double seconds) {
      std::vector<float> x(static_cast<std::size_t>(seconds * fs_hz));
      double phase = 0.0;
      for (std::size_t i = 0; i < x.size(); ++i) {
        const double f = f_from * std::pow(f_to / f_from, double(i) / double(x.size()));
        phase += f / fs_hz;
        const double t = (phase - std::floor(phase)) / f;  // seconds since the pulse
        x[i] = static_cast<float>(0.5 * std::exp(-t * 500.0) * std::cos(2.0 * std::numbers::pi * 800.0 * t));
      }
      return x;
    };
    // Steady: a period of exactly 100 samples (160 Hz), so every pulse starts on a sample and
    // the train is strictly periodic (the glide's sub-sample onsets jitter its high band).
    std::vector<float> steady(static_cast<std::size_t>(fs_hz));
    for (std::size_t i = 0; i < steady.size(); ++i) {
      const double t = static_cast<double>(i % 100) / fs_hz;
      steady[i] = static_cast<float>(0.5 * std::exp(-t * 500.0) * std::cos(2.0 * std::numbers::pi * 800.0 * t));
    }
    const auto f0 = sas::cues::PitchTrack(steady, fs_hz);
    std::vector<double> voiced;
    for (double f : f0) if (f > 0.0) voiced.push_back(f);
    REQUIRE(voiced.size() > f0.size() * 9 / 10);
    for (double f : voiced) CHECK(std::fabs(f - 160.0) < 1.0);
    // A strict line spectrum: nearly no flatness between its harmonics.
    CHECK(sas::cues::VoicedFlatness(steady, fs_hz, f0) < 0.05);

    sas::cues::VoiceFigures glide;
    const auto x = pulses(100.0, 200.0, 2.0);
    for (double f : sas::cues::PitchTrack(x, fs_hz)) if (f > 0.0) glide.f0_hz.push_back(f);
    glide.frames = glide.voiced_frames = static_cast<double>(glide.f0_hz.size());
    const auto s = sas::cues::Summarise({glide});
    // 5th to 95th percentile of a uniform-in-log glide over 12 semitones: 10.8 st.
    CHECK(std::fabs(s.f0_range_st - 10.8) < 0.5);
    CHECK(std::fabs(s.f0_median_hz - 141.4) < 3.0);
  }
  SECTION("flatness of white noise and silence is unvoiced") {
    std::vector<float> noise(static_cast<std::size_t>(fs_hz));
    std::mt19937 rng(2);
    std::normal_distribution<float> g(0.0f, 0.1f);
    for (auto& v : noise) v = g(rng);
    const std::vector<double> all_voiced(90, 100.0);
    // The flatness of one periodogram of white noise is about exp(-Euler's gamma) = 0.56.
    CHECK(std::fabs(sas::cues::VoicedFlatness(noise, fs_hz, all_voiced) - 0.56) < 0.06);
    const std::vector<float> silence(static_cast<std::size_t>(fs_hz), 0.0f);
    for (double f : sas::cues::PitchTrack(silence, fs_hz)) CHECK(f == 0.0);
  }
  SECTION("true peak between the samples") {
    // A quarter-rate sine sampled at 45 degrees: samples at 0.707 of a 0.5 peak.
    std::vector<float> x(48000);
    for (std::size_t i = 0; i < x.size(); ++i) {
      x[i] = static_cast<float>(0.5 * std::sin(std::numbers::pi / 2.0 * double(i) + std::numbers::pi / 4.0));
    }
    CHECK(std::fabs(sas::cues::TruePeakDbtp(x, 48000.0) - 20.0 * std::log10(0.5)) < 0.3);
  }
  SECTION("words and word errors") {
    CHECK(sas::cues::Words("Scratch the picture, with the pen!") ==
          std::vector<std::string>{"scratch", "the", "picture", "with", "the", "pen"});
    CHECK(sas::cues::WordEdits(sas::cues::Words("scratch the picture"),
                               sas::cues::Words("scratch a picture now")) == 2);
    CHECK(sas::cues::WordEdits(sas::cues::Words("one two three"), {}) == 3);
  }
}
