// The textures' levels over a population of visitor strokes (see population_levels.h).
#include "calibration/population_levels.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "kiosk/data_dirs.h"
#include "surface/image_surface.h"
#include "surface/loudness.h"
#include "surface/texture_file.h"

namespace sas::kiosk {
namespace {

std::string StrokeDescription(const VisitorStroke& stroke) {
  const PenStroke& pen = stroke.pen;
  const double length_mm =
      std::hypot((pen.x1 - pen.x0) * kScreenWidthPx, (pen.y1 - pen.y0) * kScreenHeightPx) *
      surface::DisplayGeometry{}.pixel_pitch_mm();
  char text[160];
  std::snprintf(text, sizeof text, "%s %.0f mm/s, pressure %.2f, tilt %.0f°, %.2f s",
                stroke.name.c_str(), length_mm / pen.duration_s, pen.pressure, pen.tilt_deg,
                pen.duration_s);
  return text;
}

}  // namespace

std::vector<std::string> KioskTexturePaths(const std::string& textures) {
  std::vector<std::string> paths;
  for (const auto& key : KioskTextureNames()) {
    paths.push_back((std::filesystem::path(textures) / key / "texture.toml").string());
  }
  return paths;
}

PopulationLevels MeasurePopulation(const std::vector<std::string>& paths, std::size_t t,
                                   const std::vector<VisitorStroke>& strokes,
                                   const KioskConfig& config) {
  LevelMeasurement measurement;
  measurement.strokes = strokes;
  measurement.global_sound_gain_db = config.sound_gain_db;
  measurement.global_haptic_gain_db = config.haptic_gain_db;
  measurement.stroke_cap_lu = config.stroke_cap_lu;
  measurement.strokes_per_visit = kVisitStrokes;
  measurement.whole_strokes = true;
  measurement.felt_figures = true;
  for (std::size_t o = 0; o < paths.size(); ++o) {
    if (o != t) measurement.other_textures.push_back(paths[o]);
  }
  const auto file = surface::LoadTextureFile(paths.at(t));
  const auto levels = MeasureStrokeLevels(paths[t], file.gains, measurement);
  PopulationLevels row;
  row.name = file.name;
  std::vector<double> sound, haptic;
  std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> by_style;
  for (std::size_t i = 0; i < levels.size(); ++i) {
    sound.push_back(levels[i].sound_lufs);
    haptic.push_back(levels[i].haptic_rms_db);
    by_style[strokes[i].name].first.push_back(levels[i].sound_lufs);
    by_style[strokes[i].name].second.push_back(levels[i].haptic_rms_db);
  }
  row.sound_median = Percentile(sound, 0.5);
  row.sound_p5 = Percentile(sound, 0.05);
  row.sound_p95 = Percentile(sound, 0.95);
  const auto loudest = std::max_element(sound.begin(), sound.end());
  row.sound_max = *loudest;
  row.loudest_stroke =
      StrokeDescription(strokes[static_cast<std::size_t>(loudest - sound.begin())]);
  row.momentary_max = surface::kSilenceDb;
  for (std::size_t i = 0; i < levels.size(); ++i) {
    if (levels[i].sound_momentary_max_lufs > row.momentary_max) {
      row.momentary_max = levels[i].sound_momentary_max_lufs;
      row.loudest_moment_stroke = StrokeDescription(strokes[i]);
    }
  }
  row.haptic_median = Percentile(haptic, 0.5);
  row.haptic_p5 = Percentile(haptic, 0.05);
  row.haptic_p95 = Percentile(haptic, 0.95);
  for (const auto& [style, v] : by_style) {
    row.per_style[style] = {Percentile(v.first, 0.5), Percentile(v.second, 0.5)};
  }
  std::vector<double> near, crest, band, above;
  for (const auto& l : levels) {
    near.push_back(l.felt.near_ceiling);
    crest.push_back(l.felt.crest_db);
    band.push_back(l.felt.band_fraction);
    above.push_back(l.felt.above_1k_db);
    row.felt_features.push_back(l.felt.features);
  }
  row.felt_near_ceiling_median = Percentile(near, 0.5);
  row.felt_crest_median = Percentile(crest, 0.5);
  row.felt_band_fraction_median = Percentile(band, 0.5);
  row.felt_above_1k_median = Percentile(above, 0.5);
  // The loudest 5 % by skin-weighted level (at least one stroke).
  std::vector<std::size_t> order(levels.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return levels[a].haptic_rms_db > levels[b].haptic_rms_db;
  });
  const std::size_t loud = std::max<std::size_t>(1, (levels.size() + 19) / 20);
  for (std::size_t k = 0; k < loud; ++k) {
    row.felt_near_ceiling_loudest += levels[order[k]].felt.near_ceiling / static_cast<double>(loud);
  }
  return row;
}

FeltClassification ClassifyByFeel(const std::vector<PopulationLevels>& train,
                                  const std::vector<PopulationLevels>& test) {
  std::vector<FeltFeatures> x;
  std::vector<int> label;
  for (std::size_t t = 0; t < train.size(); ++t) {
    for (const auto& f : train[t].felt_features) {
      x.push_back(f);
      label.push_back(static_cast<int>(t));
    }
  }
  NearestNeighbours classifier;
  classifier.Fit(x, label);
  NearestCentroid centroid;
  centroid.Fit(x, label);
  FeltClassification result;
  result.confusion.assign(test.size(), std::vector<int>(test.size(), 0));
  int right = 0, centroid_right = 0, all = 0;
  for (std::size_t t = 0; t < test.size(); ++t) {
    for (const auto& f : test[t].felt_features) {
      const int p = classifier.Predict(f);
      if (p >= 0 && static_cast<std::size_t>(p) < test.size()) {
        ++result.confusion[t][static_cast<std::size_t>(p)];
      }
      right += p == static_cast<int>(t) ? 1 : 0;
      centroid_right += centroid.Predict(f) == static_cast<int>(t) ? 1 : 0;
      ++all;
    }
  }
  result.accuracy = all > 0 ? static_cast<double>(right) / all : 0.0;
  result.centroid_accuracy = all > 0 ? static_cast<double>(centroid_right) / all : 0.0;
  return result;
}

std::string DescribeTargets(const PopulationTargets& targets, double haptic_ceiling_db) {
  const auto holds = [](bool ok) { return ok ? "holds" : "does not hold"; };
  char text[1024];
  std::snprintf(text, sizeof text,
                "median loudness within ±%.0f LU of the mean of the textures: %s; median "
                "skin-weighted transducer level within ±%.1f dB: %s; no stroke's loudest 400 ms "
                "more than %.0f LU over its texture's median: %s; every style's median transducer "
                "level within %.0f dB of the transducer ceiling (%.0f dBFS): %s; the transducer "
                "within 1 dB of its ceiling on at most %.0f %% of the median stroke's samples and "
                "%.0f %% of the loudest 5 %%'s, median crest factor at least %.0f dB: %s; at "
                "least %.0f %% of the median stroke's vibration energy within 40-400 Hz and its "
                "energy above 1 kHz at least %.0f dB under the total: %s",
                kSoundSpreadLu, holds(targets.sound), kHapticSpreadDb, holds(targets.haptic),
                kLoudestOverMedianLu, holds(targets.loudest), kFeltBelowCeilingDb,
                haptic_ceiling_db, holds(targets.felt), 100.0 * kMedianNearCeiling,
                100.0 * kLoudestNearCeiling, kMinCrestDb, holds(targets.detail),
                100.0 * kMinSkinBandFraction, kMinAbove1kDb, holds(targets.band));
  return text;
}

PopulationTargets CheckPopulationTargets(const std::vector<PopulationLevels>& textures,
                                         double haptic_ceiling_db) {
  PopulationTargets targets;
  for (const auto& r : textures) {
    targets.mean_sound += r.sound_median / static_cast<double>(textures.size());
    targets.mean_haptic += r.haptic_median / static_cast<double>(textures.size());
  }
  for (const auto& r : textures) {
    targets.sound =
        targets.sound && std::fabs(r.sound_median - targets.mean_sound) <= kSoundSpreadLu;
    targets.haptic =
        targets.haptic && std::fabs(r.haptic_median - targets.mean_haptic) <= kHapticSpreadDb;
    targets.loudest = targets.loudest && r.momentary_max - r.sound_median <= kLoudestOverMedianLu;
    targets.detail = targets.detail && r.felt_near_ceiling_median <= kMedianNearCeiling &&
                     r.felt_near_ceiling_loudest <= kLoudestNearCeiling &&
                     r.felt_crest_median >= kMinCrestDb;
    targets.band = targets.band && r.felt_band_fraction_median >= kMinSkinBandFraction &&
                   r.felt_above_1k_median <= -kMinAbove1kDb;
    for (const char* style : {"scrape", "rub", "roll"}) {
      const auto it = r.per_style.find(style);
      // A style the population does not play cannot be felt: it misses the target.
      targets.felt = targets.felt && it != r.per_style.end() &&
                     it->second.second >= haptic_ceiling_db - kFeltBelowCeilingDb;
    }
  }
  return targets;
}

}  // namespace sas::kiosk
