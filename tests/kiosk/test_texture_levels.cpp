// Loudness and vibration matching of the four kiosk textures (issue 7, noisy room): the same
// visitor strokes (scrape and rub, slow to fast) played on each committed texture through the
// kiosk's own path — KioskEngine on its virtual clock with the kiosk's pen mapping, the
// picture-derived surface and the gains its texture.toml carries (kiosk/texture_levels.h) — must
// give channel 1 loudness (K-weighted, LUFS) and channel 2 vibration strength (RMS of the
// 40–800 Hz transducer signal) within 1 dB across the four textures, as the mean over the strokes
// (each stroke's level in dB counting once): at the texture gains alone and with the kiosk's
// default (deliberately high) gains on top, where the soft limiters start to touch the peaks.
// Stroke by stroke the textures cannot all agree with one gain each (texture_levels.h: their
// levels grow differently with speed and pressure); the test prints that residual spread and
// holds it within kStrokeSpreadLimitDb, so a change that makes one stroke jump shows.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "kiosk/gesture.h"
#include "kiosk/kiosk_config.h"
#include "kiosk/texture_levels.h"
#include "kiosk/virtual_visit.h"
#include "sas/version.h"
#include "surface/texture_file.h"

using sas::kiosk::LevelMeasurement;
using sas::kiosk::MeasureStrokeLevels;
using sas::kiosk::StrokeLevels;

namespace {

const std::vector<std::string> kTextures = {"bubble_wrap", "broken_glass", "wooden_board",
                                            "cracked_ground"};

std::string TexturePath(const std::string& name) {
  return (std::filesystem::path(sas::kSourceDir) / "textures" / name / "texture.toml").string();
}

// The residual stroke-by-stroke spread after calibration is ~10 dB (sound and vibration, README);
// 2 dB above it, so solver changes that move it a little pass and a stroke that jumps does not.
constexpr double kStrokeSpreadLimitDb = 12.0;

struct Spread {
  double sound_db = 0.0;  // spread across the textures of their mean over the strokes
  double haptic_db = 0.0;
  double stroke_sound_db = 0.0;  // largest spread across the textures of one stroke
  double stroke_haptic_db = 0.0;
  double sound_lowest = 1e9;  // quietest texture (mean over the strokes)
  double haptic_lowest = 1e9;
};

// Plays the strokes on each texture and returns the worst stroke's spread across the textures.
Spread MeasureAll(const LevelMeasurement& measurement, const char* label) {
  std::vector<std::vector<StrokeLevels>> levels;  // [texture][stroke]
  for (const auto& name : kTextures) {
    const auto file = sas::surface::LoadTextureFile(TexturePath(name));
    levels.push_back(MeasureStrokeLevels(TexturePath(name), file.gains, measurement));
  }
  Spread spread;
  for (std::size_t s = 0; s < measurement.strokes.size(); ++s) {
    double sound_lo = 1e9, sound_hi = -1e9, haptic_lo = 1e9, haptic_hi = -1e9;
    std::printf("%s %-18s", label, measurement.strokes[s].name.c_str());
    for (std::size_t t = 0; t < kTextures.size(); ++t) {
      const StrokeLevels& l = levels[t][s];
      std::printf("  %s %6.2f/%6.2f", kTextures[t].substr(0, 5).c_str(), l.sound_lufs,
                  l.haptic_rms_db);
      sound_lo = std::min(sound_lo, l.sound_lufs);
      sound_hi = std::max(sound_hi, l.sound_lufs);
      haptic_lo = std::min(haptic_lo, l.haptic_rms_db);
      haptic_hi = std::max(haptic_hi, l.haptic_rms_db);
    }
    std::printf("  spread %.2f / %.2f dB\n", sound_hi - sound_lo, haptic_hi - haptic_lo);
    spread.stroke_sound_db = std::max(spread.stroke_sound_db, sound_hi - sound_lo);
    spread.stroke_haptic_db = std::max(spread.stroke_haptic_db, haptic_hi - haptic_lo);
  }
  double sound_lo = 1e9, sound_hi = -1e9, haptic_lo = 1e9, haptic_hi = -1e9;
  std::printf("%s %-18s", label, "mean");
  for (std::size_t t = 0; t < kTextures.size(); ++t) {
    const auto set = sas::kiosk::Summarise(levels[t]);
    std::printf("  %s %6.2f/%6.2f", kTextures[t].substr(0, 5).c_str(), set.sound_mean_lufs,
                set.haptic_mean_rms_db);
    sound_lo = std::min(sound_lo, set.sound_mean_lufs);
    sound_hi = std::max(sound_hi, set.sound_mean_lufs);
    haptic_lo = std::min(haptic_lo, set.haptic_mean_rms_db);
    haptic_hi = std::max(haptic_hi, set.haptic_mean_rms_db);
  }
  spread.sound_db = sound_hi - sound_lo;
  spread.haptic_db = haptic_hi - haptic_lo;
  spread.sound_lowest = sound_lo;
  spread.haptic_lowest = haptic_lo;
  std::printf("  spread %.2f / %.2f dB\n", spread.sound_db, spread.haptic_db);
  std::printf("%s %-18s", label, "peak dBFS");
  for (std::size_t t = 0; t < kTextures.size(); ++t) {
    const auto set = sas::kiosk::Summarise(levels[t]);
    std::printf("  %s %6.1f/%6.1f", kTextures[t].substr(0, 5).c_str(),
                20.0 * std::log10(set.sound_peak), 20.0 * std::log10(set.haptic_peak));
  }
  std::printf("\n");
  std::printf("%s worst single stroke: sound %.2f dB, vibration %.2f dB\n", label,
              spread.stroke_sound_db, spread.stroke_haptic_db);
  return spread;
}

}  // namespace

TEST_CASE(
    "the four textures are matched within 1 dB in loudness and vibration over the visitor "
    "strokes through the kiosk engine",
    "[kiosk][render]") {
  const Spread spread = MeasureAll(LevelMeasurement{}, "texture gains:");
  CHECK(spread.sound_db <= 1.0);
  CHECK(spread.haptic_db <= 1.0);
  CHECK(spread.stroke_sound_db <= kStrokeSpreadLimitDb);
  CHECK(spread.stroke_haptic_db <= kStrokeSpreadLimitDb);
  // And near the level the calibration aimed for (so the gains are not all matched at silence).
  CHECK(spread.sound_lowest >= sas::kiosk::kTargetSoundLufs - 1.0);
  CHECK(spread.haptic_lowest >= sas::kiosk::kTargetHapticRmsDb - 1.0);
}

// The same check a second time is too slow for the sanitizer build (~10x slower) and exercises no
// other code, so that build leaves it out.
#if !defined(__SANITIZE_ADDRESS__)
TEST_CASE(
    "with the kiosk's default gains the four textures stay matched within 1 dB over the "
    "visitor strokes through the kiosk engine",
    "[kiosk][render]") {
  const sas::kiosk::KioskConfig defaults;
  LevelMeasurement measurement;
  measurement.global_sound_gain_db = defaults.sound_gain_db;
  measurement.global_haptic_gain_db = defaults.haptic_gain_db;
  const Spread spread = MeasureAll(measurement, "kiosk defaults:");
  CHECK(spread.sound_db <= 1.0);
  CHECK(spread.haptic_db <= 1.0);
  CHECK(spread.stroke_sound_db <= kStrokeSpreadLimitDb);
  CHECK(spread.stroke_haptic_db <= kStrokeSpreadLimitDb);
}
#endif

TEST_CASE("the calibration strokes are three scrapes and three rubs that never pop a bubble",
          "[kiosk]") {
  const sas::kiosk::GestureMapping mapping;  // the kiosk engine's pen mapping
  const auto bubble_wrap = sas::surface::LoadTextureFile(TexturePath("bubble_wrap"));
  REQUIRE(bubble_wrap.bubbles);
  int scrapes = 0, rubs = 0;
  for (const auto& stroke : sas::kiosk::CalibrationStrokes()) {
    const auto style = sas::kiosk::StyleFromWidth(
        sas::kiosk::WidthFromTiltMm(stroke.pen.tilt_deg, mapping), mapping);
    scrapes += style == sas::synth::ProbeStyle::kScrape ? 1 : 0;
    rubs += style == sas::synth::ProbeStyle::kRub ? 1 : 0;
    // A pen's full pressure scale is ~4 N of tip force on a bubble (kiosk_engine.cpp).
    CHECK(stroke.pen.pressure * 4.0 < bubble_wrap.bubbles->pop_force_n);
    // On the screen from start to end.
    for (const double f : {stroke.pen.x0, stroke.pen.x1, stroke.pen.y0, stroke.pen.y1}) {
      CHECK(f > 0.0);
      CHECK(f < 1.0);
    }
  }
  CHECK(scrapes == 3);
  CHECK(rubs == 3);
}

TEST_CASE("a straight pen stroke runs from its start to its end point and then lifts the pen",
          "[kiosk]") {
  const sas::kiosk::PenStroke stroke{0.1, 0.2, 0.5, 0.6, 0.4, 0.5, 30.0, {}};
  const auto pen = sas::kiosk::StraightStroke(stroke, 1.0, 1000, 500);
  const auto start = pen(1.0);
  const auto middle = pen(1.2);
  const auto lifted = pen(1.41);
  REQUIRE(start);
  REQUIRE(middle);
  REQUIRE(lifted);
  CHECK(start->tip_down);
  CHECK(start->x_px == Approx(100.0));
  CHECK(start->y_px == Approx(100.0));
  CHECK(middle->tip_down);
  CHECK(middle->pressure == Approx(0.5));
  CHECK(middle->tilt_deg == Approx(30.0));
  CHECK(middle->x_px == Approx(300.0));
  CHECK(middle->y_px == Approx(200.0));
  CHECK_FALSE(lifted->tip_down);
  CHECK(lifted->pressure == 0.0);
  CHECK(lifted->x_px == Approx(500.0));
  CHECK(lifted->y_px == Approx(300.0));
}
