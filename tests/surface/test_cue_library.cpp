// Spoken cues: the files generated at build time (textures/cue_maker with espeak-ng)
// are all there, 48 kHz mono, audible, never clipped and a sentence long; and the kiosk's
// CueLibrary loads them into RAM, resamples what is not at the device rate, and names whatever
// is missing instead of failing.
#include <sndfile.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "support/temp_dir.h"
#include "surface/cue_library.h"
#include "surface/loudness.h"
#include "surface/wav_writer.h"

using sas::surface::CueLibrary;
using sas::surface::ExpectedCueFiles;

namespace {

const std::vector<std::string> kTextures = {"bubble_wrap", "broken_glass", "wooden_board",
                                            "cracked_ground"};

std::vector<float> Tone(double seconds, double fs) {
  std::vector<float> x(static_cast<std::size_t>(seconds * fs));
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] = static_cast<float>(0.3 * std::sin(2.0 * std::numbers::pi * 440.0 * double(i) / fs));
  }
  return x;
}

}  // namespace

TEST_CASE("shaping a cue trims the silence around the speech but not at a lone click in it",
          "[surface]") {
  constexpr double kRate = 48000.0;
  // 0.3 s of a 300 Hz tone, then 0.6 s of silence with one click at -30 dB re the tone's peak
  // (above the trim floor on its own, but alone): a codec's or a recorder's stray sample.
  std::vector<float> x(static_cast<std::size_t>(0.9 * kRate), 0.0f);
  for (std::size_t i = 0; i < static_cast<std::size_t>(0.3 * kRate); ++i) {
    x[i] = static_cast<float>(0.5 * std::sin(2.0 * std::numbers::pi * 300.0 * static_cast<double>(i) / kRate));
  }
  x[static_cast<std::size_t>(0.85 * kRate)] = 0.5f * 0.0316f;
  const auto shaped = sas::surface::ShapeCue(x, kRate);
  const double seconds = static_cast<double>(shaped.samples.size()) / kRate;
  INFO(seconds << " s");
  CHECK(seconds == Approx(0.3 + sas::surface::kCueMarginS).margin(0.002));
  // A sustained sound at the same level is kept: 50 ms of it at the end.
  for (std::size_t i = static_cast<std::size_t>(0.8 * kRate); i < static_cast<std::size_t>(0.85 * kRate); ++i) {
    x[i] = static_cast<float>(0.5 * 0.0316 * std::sin(2.0 * std::numbers::pi * 300.0 * static_cast<double>(i) / kRate));
  }
  const auto kept = sas::surface::ShapeCue(x, kRate);
  CHECK(static_cast<double>(kept.samples.size()) / kRate > 0.85);
}

TEST_CASE("the cue library loads every cue into RAM and names the missing ones", "[surface]") {
  sas::test::TempDir dir;
  const auto at_48k = Tone(0.5, 48000.0);
  const auto at_22k = Tone(0.5, 22050.0);
  sas::surface::WriteWav(dir.file("wooden_board_name.wav"), at_48k.data(), at_48k.size(), 1, 48000);
  sas::surface::WriteWav(dir.file("too_quiet.wav"), at_22k.data(), at_22k.size(), 1, 22050);
  const std::vector<float> silence(24000, 0.0f);
  sas::surface::WriteWav(dir.file("too_loud.wav"), silence.data(), silence.size(), 1, 48000);
  dir.Write("voice_ready.wav", "not a wav file");

  const CueLibrary library = CueLibrary::Load(dir.path().string(), {"wooden_board"}, 48000.0);
  REQUIRE(library.TextureName("wooden_board") != nullptr);
  CHECK(library.TextureName("wooden_board")->size() == at_48k.size());
  REQUIRE(library.Find("too_quiet") != nullptr);
  CHECK(std::fabs(static_cast<double>(library.Find("too_quiet")->size()) - 24000.0) <= 2.0);
  CHECK(library.TextureDescription("wooden_board") == nullptr);
  CHECK(library.Find("too_loud") == nullptr);  // silent: useless to a visitor
  CHECK(library.Find("voice_ready") == nullptr);
  CHECK(library.size() == 2);
  // 12 expected files (2 for the texture, 10 messages), 2 loaded: 10 problems, each naming its
  // file.
  REQUIRE(library.problems().size() == 10);
  std::string all;
  for (const auto& p : library.problems()) all += p + "\n";
  CHECK_THAT(all, Catch::Contains("wooden_board_description.wav: missing") &&
                      Catch::Contains("too_loud.wav: silent") &&
                      Catch::Contains("voice_ready.wav") &&
                      Catch::Contains("record_countdown.wav: missing") &&
                      Catch::Contains("no_microphone.wav: missing") &&
                      Catch::Contains("count_2.wav: missing") &&
                      Catch::Contains("invitation.wav: missing"));
}

#if defined(SAS_CUES_DIR)
TEST_CASE(
    "every generated spoken cue in every language exists and is 48 kHz mono, audible, unclipped "
    "and 0.15 to 20 s long",
    "[surface]") {
  const auto files = ExpectedCueFiles(kTextures);
  CHECK(files.size() == 18);
  for (const char* language : {"en", "de", "fr", "it", "es"}) {
    const std::string dir = std::string(SAS_CUES_DIR) + "/" + language;
    for (const auto& file : files) {
      const std::string path = dir + "/" + file;
      INFO(path);
      SF_INFO info{};
      SNDFILE* sf = sf_open(path.c_str(), SFM_READ, &info);
      REQUIRE(sf != nullptr);
      std::vector<float> x(static_cast<std::size_t>(info.frames * info.channels));
      const sf_count_t read = sf_readf_float(sf, x.data(), info.frames);
      sf_close(sf);
      REQUIRE(read == info.frames);
      CHECK(info.samplerate == 48000);
      CHECK(info.channels == 1);
      // A count ("Two.") is short; the invitation is the longest sentence (each kind has tighter
      // bounds of its own, which staff recordings keep too: kiosk/staff_cues.h).
      const double seconds = static_cast<double>(info.frames) / 48000.0;
      CHECK(seconds >= 0.15);
      CHECK(seconds <= 20.0);
      float peak = 0.0f;
      for (float v : x) peak = std::max(peak, std::fabs(v));
      CHECK(peak > 0.1f);   // audible: within 20 dB of full scale
      CHECK(peak < 0.95f);  // never clipped (normalised to a -1 dBFS peak at most)
      const double lufs = sas::surface::KWeightedLoudnessDb(x, 48000.0, 0, x.size());
      CHECK(lufs <= -22.5);  // normalised to -23 LUFS (or less, where the peak limit wins)
      CHECK(lufs >= -30.0);
    }
    const CueLibrary library = CueLibrary::Load(dir, kTextures);
    CHECK(library.problems().empty());
    CHECK(library.size() == files.size());
  }
}
#endif
