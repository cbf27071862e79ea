// Sound -> image -> profile (paper figure 3) and sound/vibration -> profile.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "support/temp_dir.h"
#include "surface/image_surface.h"
#include "surface/sound_image.h"

using namespace sas::surface;

namespace {

std::vector<float> Sine(std::size_t n, double period_samples, double amplitude = 0.8) {
  std::vector<float> s(n);
  for (std::size_t i = 0; i < n; ++i) {
    s[i] = static_cast<float>(
        amplitude * std::sin(2.0 * std::numbers::pi * static_cast<double>(i) / period_samples));
  }
  return s;
}

// Sound image -> height field (luminance relief) -> the profile along one row.
std::vector<float> RowOfSoundImage(const GrayImage& image, int row) {
  ReliefOptions options;
  options.source = ReliefSource::kLuminance;
  options.relief_mm = 1.0;
  const auto profile = RowProfile(SurfaceFromImage(image, options).field, row);
  return {profile.heights_m().begin(), profile.heights_m().end()};
}

// Positions of upward crossings of the profile's mean, linearly interpolated.
std::vector<double> UpCrossings(const std::vector<float>& p) {
  double mean = 0.0;
  for (float v : p) mean += v;
  mean /= static_cast<double>(p.size());
  std::vector<double> out;
  for (std::size_t i = 1; i < p.size(); ++i) {
    const double a = p[i - 1] - mean, b = p[i] - mean;
    if (a < 0.0 && b >= 0.0) out.push_back(static_cast<double>(i - 1) + a / (a - b));
  }
  return out;
}

}  // namespace

TEST_CASE(
    "a sine tone keeps its period through sound -> image -> profile, with and without expansion",
    "[surface]") {
  const double period = 48.0;  // 1 kHz at 48 kHz
  const auto tone = Sine(48000, period);
  for (const int expansion : {1, 2, 4}) {
    SoundImageOptions options;
    options.samples_per_row = 480;
    options.row_length_px = 480 * expansion;
    const auto image = SoundToImage(tone, options);
    REQUIRE(image.width == 480 * expansion);
    REQUIRE(image.height == 100);
    for (const int row : {0, 37, 99}) {
      const auto crossings = UpCrossings(RowOfSoundImage(image, row));
      REQUIRE(crossings.size() >= 8);
      for (std::size_t i = 1; i < crossings.size(); ++i) {
        CHECK(std::fabs(crossings[i] - crossings[i - 1] - period * expansion) <= 1.0);
      }
    }
  }
}

TEST_CASE("a click train keeps its click positions through sound -> image -> profile",
          "[surface]") {
  std::vector<float> clicks(4800, 0.0f);
  std::vector<std::size_t> where;
  for (std::size_t i = 37; i < clicks.size(); i += 331) {
    clicks[i] = 0.9f;
    where.push_back(i);
  }
  for (const int expansion : {1, 3}) {
    SoundImageOptions options;
    options.samples_per_row = 1200;
    options.row_length_px = 1200 * expansion;
    const auto image = SoundToImage(clicks, options);
    for (const std::size_t click : where) {
      const int row = static_cast<int>(click / 1200);
      const auto profile = RowOfSoundImage(image, row);
      const auto peak = std::max_element(profile.begin(), profile.end());
      // Expected pixel: the click's sample index within its row, times the expansion, at the centre
      // of the pixels that sample covers.
      const double expected = (static_cast<double>(click % 1200) + 0.5) * expansion - 0.5;
      // Find the local maximum nearest to the expected position.
      const auto lo = static_cast<std::size_t>(std::max(0.0, expected - 3.0 * expansion));
      const auto hi =
          std::min(profile.size() - 1, static_cast<std::size_t>(expected + 3.0 * expansion));
      std::size_t best = lo;
      for (std::size_t x = lo; x <= hi; ++x) {
        if (profile[x] > profile[best]) best = x;
      }
      CHECK(std::fabs(static_cast<double>(best) - expected) <= 1.0);
      CHECK(profile[best] == Approx(*peak));  // every click is as tall as the tallest
    }
  }
}

TEST_CASE("inversion turns each pixel's luminance L into 1 - L", "[surface]") {
  const auto tone = Sine(2000, 50.0);
  SoundImageOptions plain;
  plain.samples_per_row = 500;
  plain.row_length_px = 500;
  SoundImageOptions inverted = plain;
  inverted.invert = true;
  const auto a = SoundToImage(tone, plain), b = SoundToImage(tone, inverted);
  REQUIRE(a.luminance.size() == b.luminance.size());
  for (std::size_t i = 0; i < a.luminance.size(); ++i) {
    REQUIRE(a.luminance[i] + b.luminance[i] == Approx(1.0f).margin(1e-6));
  }
  // The loudest positive sample is white in the plain image, black in the inverted one.
  CHECK(*std::max_element(a.luminance.begin(), a.luminance.end()) == Approx(1.0f));
  CHECK(*std::min_element(b.luminance.begin(), b.luminance.end()) == Approx(0.0f));
}

TEST_CASE("interlacing puts the first half of the recording on even rows, the second on odd rows",
          "[surface]") {
  // Each chunk of 100 samples holds a constant equal to its index: rows show which chunk they hold.
  const int chunks = 10;
  std::vector<float> steps(static_cast<std::size_t>(chunks * 100));
  for (std::size_t i = 0; i < steps.size(); ++i) steps[i] = static_cast<float>(i / 100) / 10.0f;
  SoundImageOptions options;
  options.samples_per_row = 100;
  options.row_length_px = 100;
  const auto plain = SoundToImage(steps, options);
  options.interlace = true;
  const auto laced = SoundToImage(steps, options);
  const auto chunk_of = [](const GrayImage& image, int row) {
    // luminance = 0.5 + 0.5 * value / peak, peak = 0.9
    return static_cast<int>(std::lround((image.at(50, row) - 0.5) * 2.0 * 0.9 * 10.0));
  };
  for (int row = 0; row < chunks; ++row) {
    CHECK(chunk_of(plain, row) == row);
    const int expected = row % 2 == 0 ? row / 2 : chunks / 2 + row / 2;
    CHECK(chunk_of(laced, row) == expected);
  }
}

TEST_CASE("row height repeats each row, and recordings longer than 5 s are cut to 5 s",
          "[surface]") {
  SoundImageOptions options;
  options.samples_per_row = 4800;
  options.row_length_px = 960;
  options.row_height_px = 3;
  const auto image = SoundToImage(Sine(48000 * 8, 100.0), options);
  CHECK(image.height == 50 * 3);  // 5 s of 0.1 s rows
  for (int x = 0; x < image.width; ++x) {
    REQUIRE(image.at(x, 0) == image.at(x, 1));
    REQUIRE(image.at(x, 0) == image.at(x, 2));
  }
  CHECK_THROWS_AS(SoundToImage({}, options), std::invalid_argument);
  options.row_length_px = 0;
  CHECK_THROWS_AS(SoundToImage(Sine(100, 10.0), options), std::invalid_argument);
}

TEST_CASE("level_quantile maps that share of the samples' level to white and clips above it",
          "[surface]") {
  // 1000 samples, |s| = 0.001 ... 1.0 evenly, alternating in sign: the 60 % level is 0.6.
  std::vector<float> ramp(1000);
  for (std::size_t i = 0; i < ramp.size(); ++i) {
    const float magnitude = static_cast<float>(i + 1) / 1000.0f;
    ramp[i] = i % 2 == 0 ? magnitude : -magnitude;
  }
  SoundImageOptions options;
  options.samples_per_row = 1000;
  options.row_length_px = 1000;  // one pixel per sample
  const auto peak = SoundToImage(ramp, options);
  options.level_quantile = 0.6;
  const auto level = SoundToImage(ramp, options);
  // Default: the peak is white, half the peak a quarter above mid-grey.
  CHECK(peak.at(999, 0) == Approx(0.0).margin(1e-6));  // i = 999 is odd: -1.0
  CHECK(peak.at(998, 0) == Approx(0.5 + 0.5 * 0.999).margin(1e-6));
  CHECK(peak.at(298, 0) == Approx(0.5 + 0.5 * 0.299).margin(1e-6));
  // 0.6: 0.299 reads as 0.299 / 0.6 of full scale (to the histogram's 1/4096 of the peak), and
  // everything louder than 0.6 is white or black.
  CHECK(level.at(298, 0) == Approx(0.5 + 0.5 * 0.299 / 0.6).margin(2e-3));
  CHECK(level.at(598, 0) == Approx(0.5 + 0.5 * 0.599 / 0.6).margin(2e-3));
  CHECK(level.at(800, 0) == 1.0f);
  CHECK(level.at(801, 0) == 0.0f);
  // Out of (0, 1]: refused.
  for (const double bad : {0.0, -0.5, 1.5, std::nan("")}) {
    options.level_quantile = bad;
    CHECK_THROWS_AS(SoundToImage(ramp, options), std::invalid_argument);
  }
}

TEST_CASE("level_quantile counts the active speech only: pauses around a take leave its level",
          "[surface]") {
  // A 0.25 s syllable (a 200 Hz tone under a sin² envelope) alone, and after 0.75 s of silence
  // or of faint noise 70 dB under it: one row, one pixel per sample, so sample j of the syllable
  // is pixel j, or 6000 + j after the pause.
  constexpr int kRate = 8000, kBurst = 2000, kPause = 6000;
  std::vector<float> burst(kBurst);
  for (int i = 0; i < kBurst; ++i) {
    const double envelope = std::pow(std::sin(std::numbers::pi * i / kBurst), 2.0);
    burst[static_cast<std::size_t>(i)] =
        static_cast<float>(0.8 * envelope * std::sin(2.0 * std::numbers::pi * 200.0 * i / kRate));
  }
  const auto image = [&](const std::vector<float>& take) {
    SoundImageOptions options;
    options.sample_rate_hz = kRate;
    options.samples_per_row = static_cast<int>(take.size());
    options.row_length_px = static_cast<int>(take.size());
    options.level_quantile = 0.9;
    return SoundToImage(take, options);
  };
  const auto alone = image(burst);
  for (const float pause_level : {0.0f, 2.5e-4f}) {
    std::vector<float> take(kPause);
    for (std::size_t i = 0; i < take.size(); ++i) take[i] = i % 2 == 0 ? pause_level : -pause_level;
    take.insert(take.end(), burst.begin(), burst.end());
    const auto waited = image(take);
    INFO("pause level " << pause_level);
    int compared = 0;
    for (int j = 0; j < kBurst; ++j) {
      // Below the level (not clipped) in the take alone: the same grey after the pause.
      const float a = alone.at(j, 0);
      if (a <= 0.02f || a >= 0.98f) continue;
      REQUIRE(waited.at(kPause + j, 0) == Approx(a).margin(2e-3));
      ++compared;
    }
    CHECK(compared > kBurst / 2);
  }
}

TEST_CASE(
    "trimming to speech cuts the silence around a take and shortens only the pauses longer than "
    "the longest kept",
    "[surface]") {
  constexpr double kRate = 48000.0;
  const auto seconds = [](double s) { return static_cast<std::size_t>(s * kRate); };
  // 1 s silence, 0.5 s tone, 0.1 s pause, 0.5 s tone, 1.5 s pause, 0.5 s tone, 1 s silence.
  std::vector<float> take;
  const auto silence = [&](double s) { take.insert(take.end(), seconds(s), 0.0f); };
  const auto tone = [&](double s) {
    const auto t = Sine(seconds(s), 96.0, 0.5);
    take.insert(take.end(), t.begin(), t.end());
  };
  silence(1.0);
  tone(0.5);
  silence(0.1);
  tone(0.5);
  silence(1.5);
  tone(0.5);
  silence(1.0);
  const SpeechTrimOptions options;  // 50 ms margins, pauses kept up to 0.25 s
  const auto speech = TrimToSpeech(take, kRate, options);
  // Kept: the three tones, the short pause whole, the long one cut to 0.25 s, the two margins.
  const double expected_s = 1.5 + 0.1 + 0.25 + 2 * 0.05;
  CHECK(static_cast<double>(speech.size()) / kRate == Approx(expected_s).margin(0.005));
  // The first and last kept samples are the margins' silence, the tone follows right after.
  CHECK(speech.front() == 0.0f);
  CHECK(speech.back() == 0.0f);
  float peak = 0.0f;
  for (std::size_t i = seconds(0.05); i < seconds(0.1); ++i)
    peak = std::max(peak, std::fabs(speech[i]));
  CHECK(peak > 0.4f);
  // Nothing but silence: nothing to show.
  CHECK(TrimToSpeech(std::vector<float>(seconds(1.0), 0.0f), kRate).empty());
  CHECK(TrimToSpeech({}, kRate).empty());
  CHECK_THROWS_AS(TrimToSpeech(take, 0.0), std::invalid_argument);
}

TEST_CASE("silence becomes a uniform mid-grey image, not amplified noise", "[surface]") {
  const auto image = SoundToImage(std::vector<float>(9600, 0.0f), {});
  for (const float l : image.luminance) REQUIRE(l == 0.5f);
}

TEST_CASE("sound -> profile maps 1000 ms to 1000 mm and follows the envelope", "[surface]") {
  AudioClip clip;
  clip.sample_rate_hz = 48000.0;
  clip.samples.assign(48000, 0.0f);
  // A burst of tone from 250 ms to 500 ms.
  for (std::size_t i = 12000; i < 24000; ++i) {
    clip.samples[i] =
        static_cast<float>(0.5 * std::sin(2.0 * std::numbers::pi * static_cast<double>(i) / 48.0));
  }
  SoundProfileOptions options;
  options.pitch_mm = 1.0;
  options.amplitude_mm = 0.4;
  const auto profile = SoundToProfile(clip, options);
  CHECK(profile.width() == 1000);
  CHECK(profile.height() == 1);
  CHECK(profile.pitch_m() == Approx(1e-3));
  CHECK(profile.at(100, 0) == 0.0f);  // silence is flat
  CHECK(profile.at(375, 0) == Approx(0.4e-3).epsilon(0.02));
  CHECK(profile.at(700, 0) == 0.0f);
  // Edges within the 5 ms envelope window of 250 mm and 500 mm.
  int rise = 0, fall = 0;
  for (int x = 1; x < 1000; ++x) {
    if (profile.at(x - 1, 0) < 0.2e-3f && profile.at(x, 0) >= 0.2e-3f) rise = x;
    if (profile.at(x - 1, 0) >= 0.2e-3f && profile.at(x, 0) < 0.2e-3f) fall = x;
  }
  CHECK(std::abs(rise - 250) <= 3);
  CHECK(std::abs(fall - 500) <= 3);
}

TEST_CASE("a CSV scan becomes a profile in true millimetres, resampled to the pitch", "[surface]") {
  VibrationOptions options;
  options.csv_pitch_mm = 0.5;
  const auto two_column = VibrationProfileFromCsv(
      "position_mm,height_mm\n# comment\n0,0\n1,0.2\n2,0\n", "scan.csv", options);
  REQUIRE(two_column.width() == 5);
  CHECK(two_column.at(1, 0) == Approx(0.1e-3));
  CHECK(two_column.at(2, 0) == Approx(0.2e-3));
  CHECK(two_column.at(4, 0) == Approx(0.0).margin(1e-12));
  const auto one_column = VibrationProfileFromCsv("0.0\n0.3\n0.1\n", "heights.csv", options);
  REQUIRE(one_column.width() == 3);
  CHECK(one_column.at(1, 0) == Approx(0.3e-3));
}

TEST_CASE("bad CSV scans are refused with file and line", "[surface]") {
  CHECK_THROWS_WITH(VibrationProfileFromCsv("0,1\n1,2\nx,y\n", "bad.csv"),
                    Catch::Contains("bad.csv:3"));
  CHECK_THROWS_WITH(VibrationProfileFromCsv("0,1\n2,2\n1,0\n", "order.csv"),
                    Catch::Contains("order.csv:3") && Catch::Contains("increase"));
  CHECK_THROWS_WITH(VibrationProfileFromCsv("0,1\n1\n", "mixed.csv"),
                    Catch::Contains("mixed.csv:2"));
  CHECK_THROWS_AS(VibrationProfileFromCsv("", "empty.csv"), LoadError);
  CHECK_THROWS_AS(VibrationProfileFromCsv("1\n", "one.csv"), LoadError);
  CHECK_THROWS_AS(VibrationProfileFromCsv("0\nnan\n", "nan.csv"), LoadError);
  CHECK_THROWS_AS(VibrationProfileFromCsv("0\n1e300\n", "huge.csv"), LoadError);
  sas::test::TempDir dir;
  CHECK_THROWS_WITH(VibrationProfileFromFile(dir.file("absent.csv")),
                    Catch::Contains("absent.csv"));
}

TEST_CASE("a voice recording becomes a height field whose rows are the recording's luminance rows",
          "[surface]") {
  AudioClip clip;
  clip.sample_rate_hz = 48000.0;
  clip.samples.resize(48000 * 2);
  for (std::size_t i = 0; i < clip.samples.size(); ++i) {
    clip.samples[i] =
        static_cast<float>(0.3 * std::sin(2.0 * std::numbers::pi * static_cast<double>(i) / 96.0));
  }
  clip.peak = 0.3f;
  SoundImageOptions options;
  options.samples_per_row = 1920;
  options.row_length_px = 1920;
  options.row_height_px = 4;
  const auto field = SoundToHeightField(clip, options, 0.5, 0.1534);
  CHECK(field.width() == 1920);
  CHECK(field.height() == 50 * 4);  // 2 s of 40 ms rows, each 4 px high
  CHECK(field.pitch_m() == Approx(0.1534e-3));
  // Heights span 0..relief: luminance 0.5 +- 0.5 sin.
  const auto [lo, hi] = std::minmax_element(field.heights_m().begin(), field.heights_m().end());
  CHECK(*hi == Approx(0.5e-3).epsilon(1e-3));
  CHECK(*lo == Approx(0.0).margin(1e-6));
  clip.silent = true;
  CHECK_THROWS_AS(SoundToHeightField(clip, options, 0.5, 0.1534), std::invalid_argument);
}
