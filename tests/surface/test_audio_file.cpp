// Audio reading: real files written with libsndfile in each format, read back through the product's
// reader; every awkward case is either handled as documented or refused.
#include <sndfile.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "support/sound_file.h"
#include "support/temp_dir.h"
#include "surface/audio_file.h"
#include "surface/image_loader.h"

using namespace sas::surface;

namespace {

using sas::test::WriteSound;

std::vector<float> Tone(int rate, double hz, double seconds, double amplitude) {
  std::vector<float> s(static_cast<std::size_t>(rate * seconds));
  for (std::size_t i = 0; i < s.size(); ++i) {
    s[i] = static_cast<float>(
        amplitude * std::sin(2.0 * std::numbers::pi * hz * static_cast<double>(i) / rate));
  }
  return s;
}

double Rms(const std::vector<float>& s, std::size_t from, std::size_t to) {
  double sum = 0.0;
  for (std::size_t i = from; i < to; ++i) sum += static_cast<double>(s[i]) * s[i];
  return std::sqrt(sum / static_cast<double>(to - from));
}

// Zero crossings per second in the middle of the clip (away from the resampler's edges).
double CrossingRateHz(const std::vector<float>& s, double rate) {
  const std::size_t a = s.size() / 4, b = 3 * s.size() / 4;
  int crossings = 0;
  for (std::size_t i = a + 1; i < b; ++i) {
    if ((s[i - 1] < 0.0f) != (s[i] < 0.0f)) ++crossings;
  }
  return crossings / 2.0 / (static_cast<double>(b - a) / rate);
}

}  // namespace

TEST_CASE("WAV, FLAC and OGG recordings read back as the same mono tone at 48 kHz", "[surface]") {
  sas::test::TempDir dir;
  const auto tone = Tone(48000, 440.0, 0.5, 0.5);
  for (const auto& [name, format] :
       std::vector<std::pair<std::string, int>>{{"a.wav", SF_FORMAT_WAV | SF_FORMAT_PCM_16},
                                                {"a.flac", SF_FORMAT_FLAC | SF_FORMAT_PCM_16},
                                                {"a.ogg", SF_FORMAT_OGG | SF_FORMAT_VORBIS}}) {
    const auto clip = ReadAudioFile(WriteSound(dir.file(name), format, 48000, 1, tone));
    INFO(name);
    CHECK(clip.sample_rate_hz == 48000.0);
    CHECK(std::fabs(static_cast<double>(clip.samples.size()) - 24000.0) <= 1024.0);
    CHECK(CrossingRateHz(clip.samples, 48000.0) == Approx(440.0).epsilon(0.01));
    CHECK(Rms(clip.samples, 4000, 20000) == Approx(0.5 / std::sqrt(2.0)).epsilon(0.03));
    CHECK_FALSE(clip.silent);
    CHECK(clip.clipped_fraction == 0.0);
  }
}

TEST_CASE("an 8 kHz recording is resampled to 48 kHz keeping pitch, level and length",
          "[surface]") {
  sas::test::TempDir dir;
  const auto tone = Tone(8000, 1000.0, 1.0, 0.6);
  const auto clip = ReadAudioFile(
      WriteSound(dir.file("low.wav"), SF_FORMAT_WAV | SF_FORMAT_FLOAT, 8000, 1, tone));
  CHECK(clip.source_rate_hz == 8000.0);
  CHECK(clip.sample_rate_hz == 48000.0);
  CHECK(clip.samples.size() == 48000);
  CHECK(CrossingRateHz(clip.samples, 48000.0) == Approx(1000.0).epsilon(0.002));
  CHECK(Rms(clip.samples, 12000, 36000) == Approx(0.6 / std::sqrt(2.0)).epsilon(0.01));
  // Band-limited: every output sample stays within the input's amplitude (plus ripple).
  for (std::size_t i = 1000; i + 1000 < clip.samples.size(); ++i)
    REQUIRE(std::fabs(clip.samples[i]) < 0.62f);
}

TEST_CASE(
    "resampling keeps tones below the lower Nyquist at their level and rejects tones above it by "
    "more than 100 dB",
    "[surface]") {
  // 48 -> 44.1 kHz: 1 kHz and 18 kHz pass (the resampler's pass band ends at 91% of 22.05 kHz);
  // 23 kHz has no place below 22.05 kHz and would alias to 21.1 kHz.
  for (const double hz : {1000.0, 18000.0}) {
    const auto out = Resample(Tone(48000, hz, 1.0, 0.5), 48000.0, 44100.0);
    REQUIRE(out.size() == 44100);
    INFO(hz << " Hz");
    CHECK(20.0 * std::log10(Rms(out, 11025, 33075) / (0.5 / std::sqrt(2.0))) ==
          Approx(0.0).margin(0.01));
  }
  const auto aliased = Resample(Tone(48000, 23000.0, 1.0, 0.5), 48000.0, 44100.0);
  CHECK(20.0 * std::log10(Rms(aliased, 11025, 33075) / (0.5 / std::sqrt(2.0))) < -100.0);
}

TEST_CASE("an 8-channel file is mixed down to the mean of its channels and 9 channels are refused",
          "[surface]") {
  sas::test::TempDir dir;
  std::vector<float> frames(8 * 4800);
  for (std::size_t f = 0; f < 4800; ++f) {
    for (std::size_t c = 0; c < 8; ++c)
      frames[f * 8 + c] = 0.05f * static_cast<float>(c);  // mean 0.175
  }
  const auto clip = ReadAudioFile(
      WriteSound(dir.file("eight.wav"), SF_FORMAT_WAV | SF_FORMAT_FLOAT, 48000, 8, frames));
  CHECK(clip.source_channels == 8);
  REQUIRE(clip.samples.size() == 4800);
  for (const float s : clip.samples) REQUIRE(s == Approx(0.175f).epsilon(1e-5));
  std::vector<float> nine(9 * 480, 0.1f);
  CHECK_THROWS_WITH(ReadAudioFile(WriteSound(dir.file("nine.wav"), SF_FORMAT_WAV | SF_FORMAT_PCM_16,
                                             48000, 9, nine)),
                    Catch::Contains("9 channels"));
}

TEST_CASE("a 2-hour file is refused from its header without reading the samples", "[surface]") {
  sas::test::TempDir dir;
  // A real WAV header for 2 h of 48 kHz 16-bit mono, then a sparse hole: 691 MB that take no disk.
  const std::string path = dir.file("long.wav");
  WriteSound(path, SF_FORMAT_WAV | SF_FORMAT_PCM_16, 48000, 1, std::vector<float>(16, 0.1f));
  const std::uint32_t data_bytes = 2u * 3600u * 48000u * 2u;
  {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    const auto put32 = [&f](std::streamoff at, std::uint32_t v) {
      f.seekp(at);
      const char b[4] = {static_cast<char>(v & 0xff), static_cast<char>((v >> 8) & 0xff),
                         static_cast<char>((v >> 16) & 0xff), static_cast<char>(v >> 24)};
      f.write(b, 4);
    };
    put32(4, 36 + data_bytes);  // RIFF size (canonical 44-byte header)
    put32(40, data_bytes);      // data chunk size
  }
  std::filesystem::resize_file(path, 44 + data_bytes);
  AudioReadLimits limits;
  CHECK_THROWS_WITH(ReadAudioFile(path, limits),
                    Catch::Contains("7200 s") && Catch::Contains("limit"));
  // The limit is configurable: a 0.2 s file is refused under a 0.1 s limit.
  const auto short_path = WriteSound(dir.file("short.wav"), SF_FORMAT_WAV | SF_FORMAT_PCM_16, 48000,
                                     1, Tone(48000, 300.0, 0.2, 0.5));
  limits.max_duration_s = 0.1;
  CHECK_THROWS_WITH(ReadAudioFile(short_path, limits), Catch::Contains("limit"));
}

TEST_CASE("empty, zero-byte, missing, non-audio and truncated files give clear errors",
          "[surface]") {
  sas::test::TempDir dir;
  CHECK_THROWS_WITH(ReadAudioFile(dir.file("absent.wav")), Catch::Contains("absent.wav"));
  CHECK_THROWS_WITH(ReadAudioFile(dir.Write("zero.wav", "")), Catch::Contains("zero bytes"));
  CHECK_THROWS_AS(ReadAudioFile(dir.Write("text.wav", "RIFF but not really a wave file")),
                  LoadError);
  // A valid header with no frames.
  {
    SF_INFO info{};
    info.samplerate = 48000;
    info.channels = 1;
    info.format = SF_FORMAT_WAV | SF_FORMAT_PCM_16;
    SNDFILE* f = sf_open(dir.file("empty.wav").c_str(), SFM_WRITE, &info);
    REQUIRE(f != nullptr);
    sf_close(f);
  }
  CHECK_THROWS_WITH(ReadAudioFile(dir.file("empty.wav")), Catch::Contains("no audio frames"));
  // Truncated in the middle of the data: what is there is read, nothing more.
  const auto full = WriteSound(dir.file("full.wav"), SF_FORMAT_WAV | SF_FORMAT_PCM_16, 48000, 1,
                               Tone(48000, 300.0, 0.2, 0.5));
  std::filesystem::resize_file(full, 44 + 2 * 1000);
  const auto clip = ReadAudioFile(full);
  CHECK(clip.samples.size() <= 1000);
  for (const float s : clip.samples) REQUIRE(std::fabs(s) <= 0.51f);
}

TEST_CASE("silence is flagged, clipping is measured, and non-finite float samples are refused",
          "[surface]") {
  sas::test::TempDir dir;
  const auto silent =
      ReadAudioFile(WriteSound(dir.file("silent.wav"), SF_FORMAT_WAV | SF_FORMAT_PCM_16, 48000, 1,
                               std::vector<float>(4800, 0.0f)));
  CHECK(silent.silent);
  CHECK(silent.peak == 0.0f);
  auto loud = Tone(48000, 100.0, 0.1, 3.0);  // written with clipping: a square-ish wave
  const auto clipped = ReadAudioFile(
      WriteSound(dir.file("clipped.wav"), SF_FORMAT_WAV | SF_FORMAT_PCM_16, 48000, 1, loud));
  // |3 sin| >= 1 for all but asin(1/3)/(pi/2) = 21.6 % of the cycle.
  CHECK(clipped.clipped_fraction ==
        Approx(1.0 - 2.0 * std::asin(1.0 / 3.0) / std::numbers::pi).epsilon(0.03));
  CHECK_FALSE(clipped.silent);
  std::vector<float> bad(480, 0.1f);
  bad[100] = std::numeric_limits<float>::quiet_NaN();
  SF_INFO info{};
  info.samplerate = 48000;
  info.channels = 1;
  info.format = SF_FORMAT_WAV | SF_FORMAT_FLOAT;
  SNDFILE* f = sf_open(dir.file("nan.wav").c_str(), SFM_WRITE, &info);
  REQUIRE(f != nullptr);
  sf_writef_float(f, bad.data(), 480);
  sf_close(f);
  CHECK_THROWS_WITH(ReadAudioFile(dir.file("nan.wav")), Catch::Contains("non-finite"));
}

TEST_CASE("sample rates outside the configured range are refused, not misread", "[surface]") {
  sas::test::TempDir dir;
  const auto path = WriteSound(dir.file("r.wav"), SF_FORMAT_WAV | SF_FORMAT_PCM_16, 2000, 1,
                               Tone(2000, 100.0, 1.0, 0.5));
  CHECK_THROWS_WITH(ReadAudioFile(path), Catch::Contains("2000 Hz"));
  AudioReadLimits limits;
  limits.min_rate_hz = 1000.0;
  const auto clip = ReadAudioFile(path, limits);
  CHECK(clip.samples.size() == 48000);
  CHECK(CrossingRateHz(clip.samples, 48000.0) == Approx(100.0).epsilon(0.01));
}

TEST_CASE("a recording too short to give one sample at 48 kHz is refused instead of loading empty",
          "[surface]") {
  // Found by fuzzing (tests/fuzz/regressions/audio_file/): 2 frames at 345 kHz are 0.28 samples at
  // 48 kHz, and the reader used to return a clip with no samples at all.
  sas::test::TempDir dir;
  const auto path = WriteSound(dir.file("blip.wav"), SF_FORMAT_WAV | SF_FORMAT_FLOAT, 345000, 2,
                               {0.5f, -0.5f, 0.25f, -0.25f});
  CHECK_THROWS_WITH(ReadAudioFile(path), Catch::Contains("too short"));
  // Eight frames at 345 kHz still make one sample: loaded, not refused.
  const auto eight = WriteSound(dir.file("eight.wav"), SF_FORMAT_WAV | SF_FORMAT_FLOAT, 345000, 1,
                                std::vector<float>(8, 0.5f));
  CHECK(ReadAudioFile(eight).samples.size() == 1);
}

TEST_CASE(
    "float samples far beyond full scale are clipped to full scale and counted, never infinite",
    "[surface]") {
  sas::test::TempDir dir;
  std::vector<float> huge(4800);
  for (std::size_t i = 0; i < huge.size(); ++i) huge[i] = (i % 3 == 0) ? 3e38f : -3e38f;
  for (const int rate : {48000, 44100}) {
    const auto clip = ReadAudioFile(WriteSound(dir.file("huge" + std::to_string(rate) + ".wav"),
                                               SF_FORMAT_WAV | SF_FORMAT_FLOAT, rate, 1, huge));
    REQUIRE_FALSE(clip.samples.empty());
    CHECK(clip.clipped_fraction == 1.0);
    bool all_finite = true;
    for (const float s : clip.samples) all_finite = all_finite && std::isfinite(s);
    CHECK(all_finite);
    if (rate == 48000) {  // no resampling: exactly full scale
      CHECK(clip.peak == 1.0f);
    } else {  // the band-limited resampler may ring a little past full scale, never far
      CHECK(clip.peak < 2.0f);
    }
  }
}
