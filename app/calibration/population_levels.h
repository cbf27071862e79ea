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
//   detail   the transducer's detail is not clipped away (felt.h's figures of channel 2): the
//            median stroke has at most kMedianNearCeiling of its samples within 1 dB of the
//            ceiling, the loudest 5 % of strokes (by skin-weighted level) at most
//            kLoudestNearCeiling on average, and the median crest factor is at least kMinCrestDb
//   band     the median stroke has at least kMinSkinBandFraction of its vibration energy within
//            40-400 Hz (the skin's band) and its energy above 1 kHz at least kMinAbove1kDb under
//            the total
// Transducer levels are skin-weighted (felt.h).

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
// The vibration lives well under the ceiling, so that the texture's detail keeps its envelope
// (detail, below); 24 dB under it is still strongly felt: a transducer that reaches only 1 g at
// its ceiling gives such a stroke ~0.6 m/s² RMS, ~28 dB over the Pacinian threshold (~0.1 µm at
// 250 Hz, 0.025 m/s²: Verrillo 1963).
inline constexpr double kFeltBelowCeilingDb = 24.0;
inline constexpr double kMedianNearCeiling = 0.01;
inline constexpr double kLoudestNearCeiling = 0.05;
inline constexpr double kMinCrestDb = 10.0;
inline constexpr double kMinSkinBandFraction = 0.7;
inline constexpr double kMinAbove1kDb = 30.0;

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
  // Channel 2 over the strokes (felt.h): medians of the per-stroke figures, the loudest 5 %'s mean
  // fraction of samples near the ceiling, and every stroke's classifier features in order.
  double felt_near_ceiling_median = 0.0, felt_near_ceiling_loudest = 0.0;
  double felt_crest_median = 0.0, felt_band_fraction_median = 0.0, felt_above_1k_median = 0.0;
  std::vector<FeltFeatures> felt_features;
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
  bool sound = true, haptic = true, loudest = true, felt = true, detail = true, band = true;
  bool all() const { return sound && haptic && loudest && felt && detail && band; }
};
PopulationTargets CheckPopulationTargets(const std::vector<PopulationLevels>& textures,
                                         double haptic_ceiling_db);
// The textures told apart by their vibration alone: a NearestNeighbours (felt.h) fitted on the
// `train` population's strokes, labelled by texture (the rows' order), predicts the texture of
// each of the `test` population's strokes. confusion[true][predicted] counts strokes.
struct FeltClassification {
  double accuracy = 0.0;             // NearestNeighbours (k 5)
  double centroid_accuracy = 0.0;    // NearestCentroid, for comparison
  std::vector<std::vector<int>> confusion;  // NearestNeighbours'
};
inline constexpr double kMinFeltAccuracy = 0.9;
FeltClassification ClassifyByFeel(const std::vector<PopulationLevels>& train,
                                  const std::vector<PopulationLevels>& test);

// The four targets in words, each with "holds" or "does not hold", joined by "; ": the one
// sentence the document and the headless visit both print.
std::string DescribeTargets(const PopulationTargets& targets, double haptic_ceiling_db);

}  // namespace sas::kiosk
