// Loudness and vibration matching of the four kiosk textures (for a noisy room): the same
// visitor stroke played on each committed texture through the kiosk's own path — KioskEngine on its
// virtual clock with the kiosk's pen mapping, the picture-derived surface, all four textures loaded
// as in the kiosk (so each stroke gets its per-stroke correction, levels/stroke_gain.h) and the
// gains their texture.toml carry (calibration/texture_levels.h) — should give channel 1 loudness
// (K-weighted, LUFS) and channel 2 vibration strength (skin-weighted RMS of the transducer signal)
// within 1 dB across the four textures, stroke by stroke. It does for the calibration grid's
// strokes at their calibration places (the table's own points); held-out strokes (other widths,
// speeds, pressures, directions and places) do not reach it: each test's name states the bound it
// holds, measured.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "calibration/texture_levels.h"
#include "files/kiosk_config.h"
#include "kiosk/gesture.h"
#include "kiosk/virtual_visit.h"
#include "levels/stroke_gain.h"
#include "sas/version.h"
#include "surface/image_surface.h"
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

constexpr double kMatchDb = 1.0;
#if defined(__SANITIZE_ADDRESS__)
// The tables come from the normal build. Broken glass's slow, light scrape sticks and slips, and
// the felt channel carries that motion, whose realisation moves with the arithmetic's last bits:
// the sanitizer build's code measured 1.36 dB at 40 mm/s, p0.3 (the normal build 0.01 dB).
constexpr double kHapticMatchDb = 2.0;
#else
constexpr double kHapticMatchDb = kMatchDb;
#endif
// With the kiosk's default gains (+12 dB) the narrow point's fast firm scrapes drive every
// texture's soft limiter to 0 dBFS peaks, and the limiter takes more off the peakier textures
// (bubble wrap at 350 mm/s, p0.6: -11.3 LUFS against broken glass's -6.7): 4.56 dB measured.
// The table is measured at the texture gains alone, below the knee, and does not see that.
constexpr double kLimitedMatchDb = 5.0;
// The transducer's default gain drives the strong strokes into its limiter, which flattens the
// textures whose vibration is peakiest (the felt cracks and bubbles: crest factors of 13-17 dB
// over the visitor population) the most: 10.03 dB measured (the narrowest scrape at 80 mm/s,
// p0.6, broken glass against cracked ground), plus 0.5 dB.
constexpr double kLimitedHapticMatchDb = 10.5;
// The grid check plays a prefix of the calibration's sequence (a stroke's level holds a little of
// the ring of the stroke before it, so only the calibration's own order reproduces its levels):
// the narrowest scrape's 12 points, 144 strokes per texture, in ~15 s; the sanitizer build (~10x
// slower) its first 2 points.
#if defined(__SANITIZE_ADDRESS__)
constexpr std::size_t kGridPoints = 2;
#else
constexpr std::size_t kGridPoints = 12;
#endif

// Held-out strokes: between and beyond the grid's points (calibration/texture_levels.h: widths
// 0.3/0.9/1.9 mm scrape and 2.1/4/6 mm rub, 40/80/160/350 mm/s, pressure 0.3/0.45/0.6), each
// played at kHeldOutPlaces places no calibration stroke uses (places from 100000 on; every place
// in a new direction). 24 places keep the mean's sampling error near 1 dB for the most
// place-dependent texture and channel (broken glass's vibration: a standard deviation of 5-8 dB
// from place to place, cracks crossed or not).
constexpr int kHeldOutPlaces = 24;
std::vector<sas::kiosk::VisitorStroke> HeldOutStrokes() {
  struct Held {
    const char* name;
    double speed_mm_s, pressure, tilt_deg;
  };
  const Held held[] = {
      {"held scrape 55 p0.45", 55.0, 0.45, 2.0},    {"held rub 120 p0.40", 120.0, 0.40, 40.0},
      {"held scrape 250 p0.50", 250.0, 0.50, 12.0}, {"held rub 110 p0.55", 110.0, 0.55, 58.0},
      {"held scrape 110 p0.22", 110.0, 0.22, 8.0},  {"held scrape 200 p0.55", 200.0, 0.55, 0.0},
      {"held rub 60 p0.25", 60.0, 0.25, 25.0},      {"held rub 250 p0.35", 250.0, 0.35, 45.0}};
  std::vector<sas::kiosk::VisitorStroke> strokes;
  int place = 100000;
  for (const auto& h : held) {
    for (int i = 0; i < kHeldOutPlaces; ++i) {
      strokes.push_back(
          sas::kiosk::PlacedStroke(h.name, place++, h.speed_mm_s, h.pressure, h.tilt_deg));
    }
  }
  return strokes;
}

std::string CalibrationStroke(std::size_t point, int places) {
  return sas::kiosk::CalibrationStrokes()[point * static_cast<std::size_t>(places)].name;
}

struct Spread {
  std::vector<double> sound_db, haptic_db;        // each stroke's spread (mean over its places)
  std::vector<double> sound_level, haptic_level;  // and its level, mean over the textures
  double stroke_sound_db = 0.0;   // largest spread across the textures of one stroke (mean over
  double stroke_haptic_db = 0.0;  // its places)
  double place_sound_db = 0.0;    // largest spread across the textures of one stroke at one place
  double place_haptic_db = 0.0;
};

void Range(const std::vector<std::vector<StrokeLevels>>& levels, std::size_t s, double* sound_db,
           double* haptic_db) {
  double sound_lo = 1e9, sound_hi = -1e9, haptic_lo = 1e9, haptic_hi = -1e9;
  for (const auto& texture : levels) {
    sound_lo = std::min(sound_lo, texture[s].sound_lufs);
    sound_hi = std::max(sound_hi, texture[s].sound_lufs);
    haptic_lo = std::min(haptic_lo, texture[s].haptic_rms_db);
    haptic_hi = std::max(haptic_hi, texture[s].haptic_rms_db);
  }
  *sound_db = sound_hi - sound_lo;
  *haptic_db = haptic_hi - haptic_lo;
}

// Plays the strokes on each texture (all four loaded, as in the kiosk), takes the mean level of
// each run of `places` strokes (one stroke at its places) and returns the worst stroke's spread
// across the textures, and the worst single place's.
Spread MeasureAll(LevelMeasurement measurement, int places, const char* label) {
  std::vector<std::vector<StrokeLevels>> levels, means;  // [texture][stroke]
  for (const auto& name : kTextures) {
    const auto file = sas::surface::LoadTextureFile(TexturePath(name));
    measurement.other_textures.clear();
    for (const auto& other : kTextures) {
      if (other != name) measurement.other_textures.push_back(TexturePath(other));
    }
    // The matching as the tables make it: a texture's trims (bubble wrap's, for the pops the grid
    // leaves out) is a deliberate offset, judged over the visitor population instead.
    sas::surface::TextureGains gains = file.gains;
    gains.sound_trim_db = 0.0;
    gains.haptic_trim_db = 0.0;
    levels.push_back(MeasureStrokeLevels(TexturePath(name), gains, measurement));
    means.push_back(sas::kiosk::MeanOverPlaces(levels.back(), places));
  }
  Spread spread;
  for (std::size_t s = 0; s < means.front().size(); ++s) {
    const auto& stroke = measurement.strokes[s * static_cast<std::size_t>(places)];
    std::printf("%s %-22s", label, stroke.name.c_str());
    for (std::size_t t = 0; t < kTextures.size(); ++t) {
      std::printf("  %s %6.2f/%6.2f", kTextures[t].substr(0, 5).c_str(), means[t][s].sound_lufs,
                  means[t][s].haptic_rms_db);
    }
    double sound_db = 0.0, haptic_db = 0.0, place_sound_db = 0.0, place_haptic_db = 0.0;
    Range(means, s, &sound_db, &haptic_db);
    for (std::size_t i = 0; i < static_cast<std::size_t>(places); ++i) {
      double a = 0.0, b = 0.0;
      Range(levels, s * static_cast<std::size_t>(places) + i, &a, &b);
      place_sound_db = std::max(place_sound_db, a);
      place_haptic_db = std::max(place_haptic_db, b);
    }
    std::printf("  spread %.2f / %.2f dB (one place: up to %.2f / %.2f)\n", sound_db, haptic_db,
                place_sound_db, place_haptic_db);
    spread.sound_db.push_back(sound_db);
    spread.haptic_db.push_back(haptic_db);
    double sound_level = 0.0, haptic_level = 0.0;
    for (std::size_t t = 0; t < kTextures.size(); ++t) {
      sound_level += means[t][s].sound_lufs / static_cast<double>(kTextures.size());
      haptic_level += means[t][s].haptic_rms_db / static_cast<double>(kTextures.size());
    }
    spread.sound_level.push_back(sound_level);
    spread.haptic_level.push_back(haptic_level);
    spread.stroke_sound_db = std::max(spread.stroke_sound_db, sound_db);
    spread.stroke_haptic_db = std::max(spread.stroke_haptic_db, haptic_db);
    spread.place_sound_db = std::max(spread.place_sound_db, place_sound_db);
    spread.place_haptic_db = std::max(spread.place_haptic_db, place_haptic_db);
  }
  std::printf("%s %-22s", label, "peak dBFS");
  for (std::size_t t = 0; t < kTextures.size(); ++t) {
    const auto set = sas::kiosk::Summarise(levels[t]);
    std::printf("  %s %6.1f/%6.1f", kTextures[t].substr(0, 5).c_str(),
                20.0 * std::log10(set.sound_peak), 20.0 * std::log10(set.haptic_peak));
  }
  std::printf("\n%s worst stroke (mean over its %d places): sound %.2f dB, vibration %.2f dB\n",
              label, places, spread.stroke_sound_db, spread.stroke_haptic_db);
  std::printf("%s worst stroke at one place: sound %.2f dB, vibration %.2f dB\n", label,
              spread.place_sound_db, spread.place_haptic_db);
  return spread;
}

}  // namespace

// The first kGridPoints grid points at their calibration places, in the calibration's order.
LevelMeasurement GridPrefix() {
  const auto places = static_cast<std::size_t>(sas::kiosk::CalibrationGrid{}.places);
  const auto& calibration = sas::kiosk::CalibrationStrokes();
  LevelMeasurement measurement;
  measurement.strokes.assign(calibration.begin(),
                             calibration.begin() + static_cast<std::ptrdiff_t>(std::min(
                                                       calibration.size(), kGridPoints * places)));
  return measurement;
}

// Whether the committed tables ask for more than the largest correction for grid point `k`
// (sound or vibration) on some texture: only when the textures span more than twice the limit
// there (broken glass rubbed slowly sticks and stays ~25 dB below the others; its vibration,
// cracks only, no mode below 3 kHz, is capped by kMaxHapticGainDb).
void ClampedPoints(std::vector<bool>* sound, std::vector<bool>* haptic,
                   std::vector<double>* sound_reference = nullptr,
                   std::vector<double>* haptic_reference = nullptr) {
  std::vector<sas::surface::StrokeLevelTable> tables;
  for (const auto& name : kTextures) {
    const auto file = sas::surface::LoadTextureFile(TexturePath(name));
    REQUIRE(file.levels);
    tables.push_back(*file.levels);
  }
  const std::size_t points = tables.front().sound_lufs.size();
  sound->assign(points, false);
  haptic->assign(points, false);
  for (std::size_t k = 0; k < points; ++k) {
    std::vector<double> sound_levels, haptic_levels;
    for (const auto& t : tables) {
      sound_levels.push_back(t.sound_lufs[k]);
      haptic_levels.push_back(t.haptic_rms_db[k]);
    }
    const double sound_mean = sas::kiosk::ReferenceLevel(sound_levels);
    const double haptic_mean = sas::kiosk::ReferenceLevel(haptic_levels);
    if (sound_reference) sound_reference->push_back(sound_mean);
    if (haptic_reference) haptic_reference->push_back(haptic_mean);
    for (const auto& t : tables) {
      if (std::fabs(sound_mean - t.sound_lufs[k]) > sas::kiosk::kMaxStrokeCorrectionDb + 1e-9) {
        (*sound)[k] = true;
      }
      if (std::fabs(haptic_mean - t.haptic_rms_db[k]) > sas::kiosk::kMaxStrokeCorrectionDb + 1e-9) {
        (*haptic)[k] = true;
      }
    }
  }
}

TEST_CASE(
    "each calibration-grid stroke of the narrowest scrape at its calibration places has the same "
    "loudness and vibration strength within 1 dB on the four textures where its correction is "
    "within the 18 dB limit",
    "[kiosk][render]") {
  const int places = sas::kiosk::CalibrationGrid{}.places;
  const LevelMeasurement measurement = GridPrefix();
  const std::size_t count =
      sas::kiosk::CalibrationStrokes().size() / static_cast<std::size_t>(places);
  std::vector<std::size_t> points;
  for (std::size_t k = 0; k < std::min(count, kGridPoints); ++k) points.push_back(k);
  const Spread spread = MeasureAll(measurement, places, "grid:");
  std::vector<bool> sound_clamped, haptic_clamped;
  std::vector<double> sound_reference, haptic_reference;
  ClampedPoints(&sound_clamped, &haptic_clamped, &sound_reference, &haptic_reference);
  REQUIRE(sound_clamped.size() == count);
  REQUIRE(spread.sound_db.size() == points.size());
  int checked = 0;
  for (std::size_t j = 0; j < points.size(); ++j) {
    const std::size_t k = points[j];
    INFO("grid point " << k << ": " << CalibrationStroke(k, places));
    // At the level the tables ask for (the textures' median there: not matched at silence).
    CHECK(spread.sound_level[j] == Approx(sound_reference[k]).margin(0.5));
    CHECK(spread.haptic_level[j] == Approx(haptic_reference[k]).margin(0.5));
    if (!sound_clamped[k]) {
      CHECK(spread.sound_db[j] <= kMatchDb);
      ++checked;
    } else {
      std::printf("grid: point %zu sound: a texture needs more than 18 dB, not checked\n", k);
    }
    if (!haptic_clamped[k]) {
      CHECK(spread.haptic_db[j] <= kHapticMatchDb);
      ++checked;
    } else {
      std::printf("grid: point %zu vibration: a texture needs more than 18 dB, not checked\n", k);
    }
  }
  // Every point checked (the limit only excuses textures more than 36 dB apart: none of the
  // prefix's with the committed textures).
  CHECK(checked >= static_cast<int>(points.size()));
}

// The held-out strokes and the default gains are too slow for the sanitizer build (~10x slower)
// and exercise no other code than the grid check, so that build leaves them out.
#if !defined(__SANITIZE_ADDRESS__)
// Held-out strokes are not matched within 1 dB. Measured (mean over 24 places, sound / vibration):
// rubs at pressure 0.35-0.55 1.7-2.9 / 0.2 dB; scrapes 3.9-6.8 / 2.7-4.2 dB; below the grid's
// pressures (0.22, 0.25) 3.5 / 20.1 dB and 2.1 / 3.1 dB. The largest misses are broken glass's:
// its sound is the nib's quiet sliding noise with loud crack-edge impacts on top, so a stroke's
// level depends on how many cracks it crosses (the 250 mm/s scrape, 1.4 mm wide: 6.8 dB below the
// others), and its vibration comes only from cracks crossed (the light 110 mm/s scrape: 20 dB
// above). At a single place the same stroke differs by up to 20 / 26 dB. The bounds are the
// measured worst plus ~0.5 dB, so a change that makes a stroke jump still shows.
// docs/engineering.md, "Textures, loudness matching and spoken cues".
constexpr double kHeldOutSoundLimitDb = 7.3;
constexpr double kHeldOutHapticLimitDb = 20.6;

TEST_CASE(
    "each held-out stroke (mean over 24 new places) is within 7.3 dB in loudness and 20.6 dB in "
    "vibration on the four textures through the kiosk engine (1 dB not reached)",
    "[kiosk][render]") {
  LevelMeasurement measurement;
  measurement.strokes = HeldOutStrokes();
  const Spread spread = MeasureAll(measurement, kHeldOutPlaces, "held out:");
  REQUIRE(spread.sound_db.size() == 8);
  CHECK(spread.stroke_sound_db <= kHeldOutSoundLimitDb);
  CHECK(spread.stroke_haptic_db <= kHeldOutHapticLimitDb);
}

TEST_CASE(
    "with the kiosk's default gains the grid strokes stay within 5 dB (vibration 10.5) where the "
    "correction is "
    "within its limit (the soft limiters compress the peakier textures' loudest strokes more) and "
    "the held-out strokes within their bounds",
    "[kiosk][render]") {
  const sas::kiosk::KioskConfig defaults;
  LevelMeasurement measurement = GridPrefix();
  measurement.global_sound_gain_db = defaults.sound_gain_db;
  measurement.global_haptic_gain_db = defaults.haptic_gain_db;
  const int places = sas::kiosk::CalibrationGrid{}.places;
  const Spread grid = MeasureAll(measurement, places, "defaults:");
  std::vector<bool> sound_clamped, haptic_clamped;
  ClampedPoints(&sound_clamped, &haptic_clamped);
  for (std::size_t k = 0; k < grid.sound_db.size(); ++k) {
    INFO("grid point " << k << ": " << CalibrationStroke(k, places));
    if (!sound_clamped[k]) CHECK(grid.sound_db[k] <= kLimitedMatchDb);
    if (!haptic_clamped[k]) CHECK(grid.haptic_db[k] <= kLimitedHapticMatchDb);
  }
  measurement.strokes = HeldOutStrokes();
  const Spread held = MeasureAll(measurement, kHeldOutPlaces, "defaults held out:");
  CHECK(held.stroke_sound_db <= kHeldOutSoundLimitDb);
  CHECK(held.stroke_haptic_db <= kHeldOutHapticLimitDb);
}
#endif

TEST_CASE(
    "the calibration strokes are the grid's scrapes then rubs then rolls in table order, on the "
    "screen, and "
    "never pop a bubble, and so are the held-out strokes",
    "[kiosk]") {
  const sas::kiosk::GestureMapping mapping;  // the kiosk engine's pen mapping
  const auto bubble_wrap = sas::surface::LoadTextureFile(TexturePath("bubble_wrap"));
  REQUIRE(bubble_wrap.bubbles);
  const sas::kiosk::CalibrationGrid grid;
  const auto& calibration = sas::kiosk::CalibrationStrokes();
  const std::size_t per_width = grid.speeds_mm_s.size() * grid.pressures.size();
  const std::size_t per_style = grid.scrape_widths_mm.size() * per_width;
  const auto places = static_cast<std::size_t>(grid.places);
  REQUIRE(grid.rub_widths_mm.size() == grid.scrape_widths_mm.size());
  REQUIRE(grid.roll_widths_mm.size() == 1);
  REQUIRE(calibration.size() == (2 * per_style + per_width) * places);
  const double pitch_mm = sas::surface::DisplayGeometry{}.pixel_pitch_mm();
  std::size_t k = 0;
  for (const auto& stroke : calibration) {  // [style][width][speed][pressure][place]
    const std::size_t point = k / places;
    const std::size_t style = std::min<std::size_t>(point / per_style, 2);
    const double width_mm = sas::kiosk::WidthFromTiltMm(stroke.pen.tilt_deg, mapping);
    if (style == 2) {  // roll: forced, at any tilt
      CHECK(stroke.pen.style == sas::synth::ProbeStyle::kRoll);
    } else {
      CHECK_FALSE(stroke.pen.style.has_value());
      CHECK(sas::kiosk::StyleFromWidth(width_mm, mapping) ==
            (style == 1 ? sas::synth::ProbeStyle::kRub : sas::synth::ProbeStyle::kScrape));
    }
    const auto& widths = style == 0   ? grid.scrape_widths_mm
                         : style == 1 ? grid.rub_widths_mm
                                      : grid.roll_widths_mm;
    CHECK(width_mm == Approx(widths[(point % per_style) / per_width]));
    const double length_mm = std::hypot((stroke.pen.x1 - stroke.pen.x0) * 1920.0,
                                        (stroke.pen.y1 - stroke.pen.y0) * 1080.0) *
                             pitch_mm;
    CHECK(length_mm / stroke.pen.duration_s ==
          Approx(grid.speeds_mm_s[(point % per_width) / grid.pressures.size()]));
    CHECK(stroke.pen.pressure == grid.pressures[point % grid.pressures.size()]);
    ++k;
  }
  auto all = calibration;
  const auto held = HeldOutStrokes();
  all.insert(all.end(), held.begin(), held.end());
  for (const auto& stroke : all) {
    // A pen's full pressure scale is ~4 N of tip force on a bubble (kiosk_engine.cpp).
    CHECK(stroke.pen.pressure * 4.0 < bubble_wrap.bubbles->pop_force_n);
    // On the screen from start to end.
    for (const double f : {stroke.pen.x0, stroke.pen.x1, stroke.pen.y0, stroke.pen.y1}) {
      CHECK(f > 0.0);
      CHECK(f < 1.0);
    }
  }
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
  CHECK(start->reading.tip_down);
  CHECK(start->reading.x_px == Approx(100.0));
  CHECK(start->reading.y_px == Approx(100.0));
  CHECK(middle->reading.tip_down);
  CHECK(middle->reading.pressure == Approx(0.5));
  CHECK(middle->reading.HasTilt());
  CHECK(middle->reading.TiltDeg() == Approx(30.0));
  CHECK(middle->reading.x_px == Approx(300.0));
  CHECK(middle->reading.y_px == Approx(200.0));
  CHECK_FALSE(lifted->reading.tip_down);
  CHECK(lifted->reading.pressure == 0.0);
  CHECK(lifted->reading.x_px == Approx(500.0));
  CHECK(lifted->reading.y_px == Approx(300.0));
}
