#pragma once
// The kiosk textures' levels over a population of visitor strokes (VisitorPopulation, played
// through the kiosk engine as visits: texture_levels.h) and the level-matching targets they are
// held to. Used by textures/population_levels (docs/population-levels.md) and the calibration
// tests, so the document and the test judge the same figures the same way. Offline only.
//
// Targets, per texture, at the kiosk's default gains:
//   sound    the median stroke loudness (LUFS) within kSoundSpreadLu of the four textures' mean
//   haptic   the median transducer level (dB RMS) within kHapticSpreadDb of their mean
//   loudest  no stroke's loudest 400 ms (momentary loudness) over its texture's median by more
//            than kLoudestOverMedianLu
// Every stroke is measured whole, from its touch-down (the landing) to just after its lift: a
// pen's landing is part of its stroke, and the loudest moment of a visit can be one.
//   felt     every style's (scrape, rub, roll) median transducer level within kFeltBelowCeilingDb
//            of the transducer's ceiling

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "calibration/texture_levels.h"
#include "files/kiosk_config.h"

namespace sas::kiosk {

inline constexpr double kSoundSpreadLu = 1.0;
inline constexpr double kHapticSpreadDb = 1.5;
inline constexpr double kLoudestOverMedianLu = 10.0;
inline constexpr double kFeltBelowCeilingDb = 15.0;

// One texture's figures over the population: medians and spreads of the stroke levels, and the
// medians per style (sound LUFS, transducer dB).
struct PopulationLevels {
  std::string name;
  double sound_median = 0.0, sound_p5 = 0.0, sound_p95 = 0.0, sound_max = 0.0;
  double haptic_median = 0.0, haptic_p5 = 0.0, haptic_p95 = 0.0;
  // The loudest stroke, told as a visitor made it ("roll 312 mm/s, pressure 0.84, 0.41 s"), so
  // whoever tunes the levels sees which strokes stand out.
  std::string loudest_stroke;
  // The loudest 400 ms of any stroke (LUFS, momentary) and that stroke.
  double momentary_max = 0.0;
  std::string loudest_moment_stroke;
  std::map<std::string, std::pair<double, double>> per_style;
};

// The kiosk textures' files under `textures` (one folder per kiosk texture), in the kiosk's order.
std::vector<std::string> KioskTexturePaths(const std::string& textures);

// Plays `strokes` on texture `paths[t]` with the others loaded, as the kiosk holds them all, in
// visits of kVisitStrokes, at the texture files' gains and `config`'s global gains and leveller.
PopulationLevels MeasurePopulation(const std::vector<std::string>& paths, std::size_t t,
                                   const std::vector<VisitorStroke>& strokes,
                                   const KioskConfig& config);

struct PopulationTargets {
  double mean_sound = 0.0, mean_haptic = 0.0;  // the means of the textures' medians
  bool sound = true, haptic = true, loudest = true, felt = true;
  bool all() const { return sound && haptic && loudest && felt; }
};
PopulationTargets CheckPopulationTargets(const std::vector<PopulationLevels>& textures,
                                         double haptic_ceiling_db);
// The four targets in words, each with "holds" or "does not hold", joined by "; ": the one
// sentence the document and the headless visit both print.
std::string DescribeTargets(const PopulationTargets& targets, double haptic_ceiling_db);

}  // namespace sas::kiosk
