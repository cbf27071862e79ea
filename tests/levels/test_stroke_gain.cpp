// Per-stroke loudness matching (levels/stroke_gain.h): the correction for a stroke is the median
// of the textures' levels for it minus the texture's own, interpolated in probe width, log speed
// and pressure and held at the grid's edges; the pen's stroke is tracked from its hover speed at
// touch-down.
#include <catch2/catch.hpp>

#include <cmath>

#include "levels/stroke_gain.h"

using sas::kiosk::InterpolateLevels;
using sas::kiosk::StrokeGainMap;
using sas::kiosk::StrokeTracker;
using sas::surface::StrokeLevelTable;
using sas::synth::ProbeStyle;

namespace {

// Levels = base + 10 log10(speed / 40) + 10 (pressure - 0.3) - 2 width_mm (+ 5 for a rub), on a
// 2 x 2 x 2 grid per style (scrape widths 0.5 / 1.5 mm, rub 2.5 / 5.5 mm).
StrokeLevelTable Table(double base) {
  StrokeLevelTable t;
  t.scrape_widths_mm = {0.5, 1.5};
  t.rub_widths_mm = {2.5, 5.5};
  t.speeds_mm_s = {40.0, 400.0};
  t.pressures = {0.3, 0.6};
  for (int style = 0; style < 2; ++style) {
    for (const double w : t.widths_mm(style)) {
      for (const double v : t.speeds_mm_s) {
        for (const double p : t.pressures) {
          const double level =
              base + 10.0 * std::log10(v / 40.0) + 10.0 * (p - 0.3) - 2.0 * w + 5.0 * style;
          t.sound_lufs.push_back(level);
          t.haptic_rms_db.push_back(level - 1.0);
        }
      }
    }
  }
  return t;
}

}  // namespace

TEST_CASE(
    "table levels interpolate linearly in probe width, log speed and pressure within each style "
    "and "
    "hold at the edges",
    "[kiosk]") {
  const auto t = Table(-40.0);
  // Between the grid points the test law is exactly linear in width, log speed and pressure.
  const auto mid = InterpolateLevels(t, ProbeStyle::kScrape, 1.0, 126.49110640673518, 0.45);
  CHECK(mid.sound_db == Approx(-40.0 + 5.0 + 1.5 - 2.0));
  CHECK(mid.haptic_db == Approx(-41.0 + 5.0 + 1.5 - 2.0));
  CHECK(InterpolateLevels(t, ProbeStyle::kRub, 4.0, 40.0, 0.3).sound_db == Approx(-35.0 - 8.0));
  // Outside the grid: the edge's value (no extrapolation), also for nonsense input; a scrape
  // wider than the scrape widths holds at the widest scrape, not at the rub's levels.
  CHECK(InterpolateLevels(t, ProbeStyle::kScrape, 0.5, 5.0, 0.0).sound_db == Approx(-41.0));
  CHECK(InterpolateLevels(t, ProbeStyle::kScrape, 0.1, 5000.0, 1.0).sound_db ==
        Approx(-40.0 + 13.0 - 1.0));
  CHECK(InterpolateLevels(t, ProbeStyle::kScrape, 2.4, 40.0, 0.3).sound_db == Approx(-43.0));
  CHECK(InterpolateLevels(t, ProbeStyle::kRub, 9.0, 40.0, 0.3).sound_db == Approx(-35.0 - 11.0));
  CHECK(InterpolateLevels(t, ProbeStyle::kScrape, NAN, NAN, NAN).sound_db == Approx(-41.0));
  // Without roll rows a roll takes the scrape's.
  CHECK(InterpolateLevels(t, ProbeStyle::kRoll, 0.5, 40.0, 0.3).sound_db == Approx(-41.0));
  // With them, its own (here 30 dB under the scrape, widths 1 / 3 mm).
  StrokeLevelTable with_roll = t;
  with_roll.roll_widths_mm = {1.0, 3.0};
  const std::size_t per_style = 2 * 2 * 2;
  for (std::size_t i = 0; i < per_style; ++i) {
    with_roll.sound_lufs.push_back(t.sound_lufs[i] - 30.0);
    with_roll.haptic_rms_db.push_back(t.haptic_rms_db[i] - 30.0);
  }
  CHECK(InterpolateLevels(with_roll, ProbeStyle::kRoll, 1.0, 40.0, 0.3).sound_db == Approx(-71.0));
  CHECK(InterpolateLevels(with_roll, ProbeStyle::kRoll, 3.0, 400.0, 0.6).haptic_db ==
        Approx(-41.0 + 13.0 - 3.0 - 30.0));  // the rows of the 1.5 mm scrape, 30 dB down
  CHECK(InterpolateLevels(with_roll, ProbeStyle::kScrape, 0.5, 40.0, 0.3).sound_db ==
        Approx(-41.0));
}

TEST_CASE(
    "the correction brings each texture to the median of the textures' levels moved within reach "
    "of every texture, leaves out a table on another grid and stops at its limit",
    "[kiosk]") {
  const auto a = Table(-40.0), b = Table(-30.0), c = Table(-36.0);
  auto other_grid = Table(-20.0);
  other_grid.speeds_mm_s = {50.0, 400.0};
  const StrokeGainMap map({&a, &b, &c, nullptr, &other_grid});
  CHECK(map.matched_textures() == 3);
  // Median of -40, -30, -36 is -36 (at every grid point: the tables differ by constants).
  CHECK(map.Correction(0, ProbeStyle::kScrape, 1.0, 100.0, 0.5).sound_db == Approx(4.0));
  CHECK(map.Correction(1, ProbeStyle::kRub, 3.0, 100.0, 0.5).haptic_db == Approx(-6.0));
  CHECK(map.Correction(2, ProbeStyle::kScrape, 0.7, 300.0, 0.4).sound_db ==
        Approx(0.0).margin(1e-12));
  // No table, another grid, an unknown texture: no correction.
  CHECK(map.Correction(3, ProbeStyle::kScrape, 1.0, 100.0, 0.5).sound_db == 0.0);
  CHECK(map.Correction(4, ProbeStyle::kScrape, 1.0, 100.0, 0.5).sound_db == 0.0);
  CHECK(map.Correction(-1, ProbeStyle::kScrape, 1.0, 100.0, 0.5).sound_db == 0.0);
  // The median, moved so that a texture far off can still reach it within the limit (18 dB) ...
  CHECK(sas::kiosk::ReferenceLevel({-40.0, -30.0, -36.0}) == Approx(-36.0));
  CHECK(sas::kiosk::ReferenceLevel({-40.0, -30.0, -60.0, -36.0}) == Approx(-42.0));
  // ... and halfway between the extremes when they are more than twice the limit apart.
  CHECK(sas::kiosk::ReferenceLevel({-40.0, -30.0, -90.0, -36.0}) == Approx(-60.0));
  const auto silent = Table(-90.0);
  const StrokeGainMap limited({&a, &b, &silent});
  CHECK(limited.Correction(2, ProbeStyle::kScrape, 1.0, 100.0, 0.5).sound_db ==
        Approx(sas::kiosk::kMaxStrokeCorrectionDb));
  CHECK(limited.Correction(1, ProbeStyle::kScrape, 1.0, 100.0, 0.5).sound_db ==
        Approx(-sas::kiosk::kMaxStrokeCorrectionDb));
}

TEST_CASE(
    "between grid points the sound correction takes the power average of a texture's levels (a "
    "loud regime dominates a near-silent one) and the vibration correction the dB average",
    "[kiosk]") {
  // Two textures at -30 dB everywhere and one that sticks, quiet (-45 dB), at the slow speed and
  // is at -30 at the fast one: the reference (median, within reach of all) is -30 everywhere.
  const auto flat = [](double level) {
    StrokeLevelTable t = Table(0.0);
    for (auto& v : t.sound_lufs) v = level;
    for (auto& v : t.haptic_rms_db) v = level;
    return t;
  };
  const StrokeLevelTable steady = flat(-30.0);
  StrokeLevelTable sticking = flat(-30.0);
  for (int style = 0; style < 2; ++style) {
    for (std::size_t w = 0; w < 2; ++w) {
      for (std::size_t p = 0; p < 2; ++p) {
        sticking.sound_lufs[sticking.Index(style, w, 0, p)] = -45.0;
        sticking.haptic_rms_db[sticking.Index(style, w, 0, p)] = -45.0;
      }
    }
  }
  const StrokeGainMap map({&steady, &sticking, &steady});
  // Halfway in log speed between 40 and 400 mm/s. Sound: the level is the mean of the powers,
  // 10 log10((10^-4.5 + 10^-3) / 2) = -32.8 dB, so the correction is +2.8 dB, not the +7.5 dB the
  // dB mean (-37.5) would give; vibration keeps the dB mean.
  const double mid = std::sqrt(40.0 * 400.0);
  const auto c = map.Correction(1, ProbeStyle::kRub, 4.0, mid, 0.45);
  CHECK(c.sound_db ==
        Approx(-30.0 - 10.0 * std::log10(0.5 * (std::pow(10.0, -4.5) + 1e-3))).margin(1e-9));
  CHECK(c.haptic_db == Approx(7.5).margin(1e-9));
  // At the grid points both blends give the table's own levels: +15 dB and 0 dB.
  CHECK(map.Correction(1, ProbeStyle::kRub, 4.0, 40.0, 0.45).sound_db == Approx(15.0).margin(1e-9));
  CHECK(map.Correction(1, ProbeStyle::kRub, 4.0, 400.0, 0.45).sound_db == Approx(0.0).margin(1e-9));
  // The steady textures need nothing anywhere.
  CHECK(map.Correction(0, ProbeStyle::kRub, 4.0, mid, 0.45).sound_db == Approx(0.0).margin(1e-9));
}

TEST_CASE(
    "the stroke tracker takes the hover speed at touch-down, smooths while down and holds while "
    "up",
    "[kiosk]") {
  StrokeTracker tracker;
  CHECK_FALSE(tracker.valid());
  tracker.Update(false, true, 150.0, 0.0, 0.005);  // hovering: nothing yet
  CHECK_FALSE(tracker.valid());
  tracker.Update(true, true, 150.0, 0.4, 0.005);  // touch-down: the hover's speed, this pressure
  CHECK(tracker.valid());
  CHECK(tracker.speed_mm_s() == 150.0);
  CHECK(tracker.pressure() == 0.4);
  for (int i = 0; i < 200; ++i) tracker.Update(true, true, 300.0, 0.6, 0.005);  // 1 s
  CHECK(tracker.speed_mm_s() == Approx(300.0).epsilon(1e-6));
  CHECK(tracker.pressure() == Approx(0.6).epsilon(1e-6));
  tracker.Update(true, true, 20000.0, 0.6, 0.005);  // a jump, not a stroke: ignored
  CHECK(tracker.speed_mm_s() == Approx(300.0).epsilon(1e-6));
  tracker.Update(false, true, 50.0, 0.0, 0.005);  // lifted: held
  CHECK(tracker.speed_mm_s() == Approx(300.0).epsilon(1e-6));
  tracker.Update(true, false, 0.0, 0.3, 0.2);  // touch-down without a recent report: speed held
  CHECK(tracker.speed_mm_s() == Approx(300.0).epsilon(1e-6));
  CHECK(tracker.pressure() == 0.3);
}
