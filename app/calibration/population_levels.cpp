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
  return row;
}

std::string DescribeTargets(const PopulationTargets& targets, double haptic_ceiling_db) {
  const auto holds = [](bool ok) { return ok ? "holds" : "does not hold"; };
  char text[512];
  std::snprintf(text, sizeof text,
                "median loudness within ±%.0f LU of the mean of the textures: %s; median "
                "transducer level within ±%.1f dB: %s; no stroke's loudest 400 ms more than %.0f "
                "LU over its texture's median: %s; every style's median transducer level within "
                "%.0f dB of the "
                "transducer ceiling (%.0f dBFS): %s",
                kSoundSpreadLu, holds(targets.sound), kHapticSpreadDb, holds(targets.haptic),
                kLoudestOverMedianLu, holds(targets.loudest), kFeltBelowCeilingDb,
                haptic_ceiling_db, holds(targets.felt));
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
