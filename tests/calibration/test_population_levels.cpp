// The kiosk textures' levels over the visitor population (calibration/population_levels.h): the
// 200 strokes docs/population-levels.md reports (seed 2026), played through the kiosk engine on the
// committed textures at the default kiosk configuration, must meet the level-matching targets:
// each texture's median loudness within 1 LU and median transducer level within 1.5 dB of the
// four textures' means, no stroke's loudest 400 ms (momentary loudness) more than 10 LU over its
// texture's median, and every style's median transducer level within 15 dB of the ceiling. Every
// stroke is measured whole, landing and lift included.
// Full-length strokes: the loudest-stroke target is about the stroke leveller catching short loud
// strokes, which a shortened population would judge differently (~35 s on the build machine).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "calibration/population_levels.h"
#include "calibration/texture_levels.h"
#include "files/kiosk_config.h"
#include "sas/version.h"

using sas::kiosk::PopulationLevels;

namespace {

std::vector<std::string> Paths() {
  return sas::kiosk::KioskTexturePaths(
      (std::filesystem::path(sas::kSourceDir) / "textures").string());
}

}  // namespace

#if defined(__SANITIZE_ADDRESS__)
// The sanitizer build (~10x slower) plays a few strokes of the population on each texture: the
// measuring path runs and gives finite figures; the targets are the normal build's.
TEST_CASE("visitor population: a few strokes measure on every texture", "[calibration]") {
  const auto strokes = sas::kiosk::VisitorPopulation(6, 2026, 0.5);
  const sas::kiosk::KioskConfig defaults;
  const auto paths = Paths();
  for (std::size_t t = 0; t < paths.size(); ++t) {
    const PopulationLevels r = sas::kiosk::MeasurePopulation(paths, t, strokes, defaults);
    CHECK(std::isfinite(r.sound_median));
    CHECK(std::isfinite(r.haptic_median));
    CHECK(r.momentary_max >= r.sound_median);
  }
}
#else
TEST_CASE("visitor population: every texture meets the level-matching targets", "[calibration]") {
  const auto strokes = sas::kiosk::VisitorPopulation(200, 2026);
  const sas::kiosk::KioskConfig defaults;
  const auto paths = Paths();
  std::vector<PopulationLevels> rows;
  for (std::size_t t = 0; t < paths.size(); ++t) {
    rows.push_back(sas::kiosk::MeasurePopulation(paths, t, strokes, defaults));
  }
  const sas::kiosk::PopulationTargets targets =
      sas::kiosk::CheckPopulationTargets(rows, defaults.haptic_ceiling_db);
  int open = 0;
  const auto target = [&](bool holds, const std::string& key) {
    INFO(key);
    CHECK(holds);
    if (!holds) ++open;
  };
  for (const auto& r : rows) {
    INFO(r.name << ": median " << r.sound_median << " LUFS (mean of the four " << targets.mean_sound
                << "), loudest " << r.sound_max << " LUFS, loudest moment " << r.momentary_max
                << " LUFS (" << r.loudest_moment_stroke << "), transducer " << r.haptic_median
                << " dB (mean " << targets.mean_haptic << ")");
    target(std::fabs(r.sound_median - targets.mean_sound) <= sas::kiosk::kSoundSpreadLu,
           "sound/" + r.name);
    target(std::fabs(r.haptic_median - targets.mean_haptic) <= sas::kiosk::kHapticSpreadDb,
           "haptic/" + r.name);
    target(r.momentary_max - r.sound_median <= sas::kiosk::kLoudestOverMedianLu,
           "loudest/" + r.name);
    // A stroke's loudest 400 ms is at least as loud as the stroke as a whole.
    CHECK(r.momentary_max >= r.sound_max - 0.5);
    INFO("vibration: near the ceiling " << r.felt_near_ceiling_median << " (median stroke), "
                                        << r.felt_near_ceiling_loudest << " (loudest 5 %), crest "
                                        << r.felt_crest_median << " dB, 40-400 Hz share "
                                        << r.felt_band_fraction_median << ", above 1 kHz "
                                        << r.felt_above_1k_median << " dB");
    target(r.felt_near_ceiling_median <= sas::kiosk::kMedianNearCeiling &&
               r.felt_near_ceiling_loudest <= sas::kiosk::kLoudestNearCeiling &&
               r.felt_crest_median >= sas::kiosk::kMinCrestDb,
           "detail/" + r.name);
    target(r.felt_band_fraction_median >= sas::kiosk::kMinSkinBandFraction &&
               r.felt_above_1k_median <= -sas::kiosk::kMinAbove1kDb,
           "band/" + r.name);
    for (const char* style : {"scrape", "rub", "roll"}) {
      INFO(style);
      REQUIRE(r.per_style.count(style) == 1);
      target(r.per_style.at(style).second >=
                 defaults.haptic_ceiling_db - sas::kiosk::kFeltBelowCeilingDb,
             std::string("felt/") + r.name + "/" + style);
    }
  }
  // The judge the document uses agrees: it fails exactly when a target above does.
  CHECK(targets.all() == (open == 0));

  // Told apart by vibration alone: fitted on another population (seed 1), judged on this one.
  const auto train_strokes = sas::kiosk::VisitorPopulation(200, 1);
  std::vector<PopulationLevels> train;
  for (std::size_t t = 0; t < paths.size(); ++t) {
    train.push_back(sas::kiosk::MeasurePopulation(paths, t, train_strokes, defaults));
  }
  const auto feel = sas::kiosk::ClassifyByFeel(train, rows);
  INFO("right texture by vibration alone: " << feel.accuracy << " (one centroid per texture: "
                                             << feel.centroid_accuracy << ")");
  CHECK(feel.accuracy >= sas::kiosk::kMinFeltAccuracy);
}
#endif

TEST_CASE("visitor population: the targets catch a texture that misses one", "[calibration]") {
  // Four textures at the same levels hold every target; moving one texture's figures past each
  // bound in turn breaks that target alone.
  PopulationLevels even;
  even.sound_median = -26.0;
  even.sound_max = -18.0;
  even.momentary_max = -17.0;
  even.haptic_median = -12.0;
  even.per_style = {{"scrape", {-26.0, -14.0}}, {"rub", {-25.0, -10.0}}, {"roll", {-26.0, -12.0}}};
  even.felt_near_ceiling_median = 0.002;
  even.felt_near_ceiling_loudest = 0.02;
  even.felt_crest_median = 14.0;
  even.felt_band_fraction_median = 0.9;
  even.felt_above_1k_median = -50.0;
  const std::vector<PopulationLevels> four(4, even);
  CHECK(sas::kiosk::CheckPopulationTargets(four, 0.0).all());
  {
    auto rows = four;
    rows[2].sound_median -= 1.5;  // 1.125 LU under the mean
    rows[2].sound_max -= 1.5;
    rows[2].momentary_max -= 1.5;
    const auto t = sas::kiosk::CheckPopulationTargets(rows, 0.0);
    CHECK_FALSE(t.sound);
    CHECK((t.haptic && t.loudest && t.felt));
  }
  {
    auto rows = four;
    rows[0].haptic_median += 2.5;  // 1.875 dB over the mean
    const auto t = sas::kiosk::CheckPopulationTargets(rows, 0.0);
    CHECK_FALSE(t.haptic);
    CHECK((t.sound && t.loudest && t.felt));
  }
  {
    auto rows = four;
    rows[1].momentary_max = rows[1].sound_median + 10.5;
    const auto t = sas::kiosk::CheckPopulationTargets(rows, 0.0);
    CHECK_FALSE(t.loudest);
    CHECK((t.sound && t.haptic && t.felt));
  }
  {
    auto rows = four;
    rows[3].per_style["roll"].second = -24.5;
    const auto t = sas::kiosk::CheckPopulationTargets(rows, 0.0);
    CHECK_FALSE(t.felt);
    CHECK((t.sound && t.haptic && t.loudest));
  }
  {
    auto rows = four;
    rows[3].per_style.erase("rub");  // a style never played is not felt
    CHECK_FALSE(sas::kiosk::CheckPopulationTargets(rows, 0.0).felt);
  }
  // The vibration's detail: near the ceiling (median stroke, loudest 5 %) and the crest factor.
  for (int which = 0; which < 3; ++which) {
    auto rows = four;
    if (which == 0) rows[1].felt_near_ceiling_median = 0.011;
    if (which == 1) rows[1].felt_near_ceiling_loudest = 0.051;
    if (which == 2) rows[1].felt_crest_median = 9.9;
    const auto t = sas::kiosk::CheckPopulationTargets(rows, 0.0);
    INFO(which);
    CHECK_FALSE(t.detail);
    CHECK((t.sound && t.haptic && t.loudest && t.felt && t.band));
  }
  // The skin's band: the share within 40-400 Hz, and what is left above 1 kHz.
  for (int which = 0; which < 2; ++which) {
    auto rows = four;
    if (which == 0) rows[2].felt_band_fraction_median = 0.69;
    if (which == 1) rows[2].felt_above_1k_median = -29.0;
    const auto t = sas::kiosk::CheckPopulationTargets(rows, 0.0);
    INFO(which);
    CHECK_FALSE(t.band);
    CHECK((t.sound && t.haptic && t.loudest && t.felt && t.detail));
  }
}
