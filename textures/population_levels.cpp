// population_levels: the kiosk textures' loudness and vibration strength over a population of
// visitor strokes (calibration/texture_levels.h, VisitorPopulation), through the kiosk engine with
// all four textures loaded (the per-stroke correction acting as in the kiosk), at each texture's
// [gains] and the kiosk's default global gains.
//
//   population_levels [--textures DIR] [--strokes N] [--seed S] [--train-seed S]
//                     [--duration-scale F] [--docs DIR] [--readme README.md]
//
// Prints, and with --docs writes DIR/population-levels.md: per texture the median stroke loudness
// (LUFS) and transducer level (dB RMS) of whole strokes (landings included), their 5th–95th
// percentile spread, the loudest stroke and the loudest 400 ms over the median, and the medians per
// style; the vibration's figures (felt.h: near the ceiling, crest factor, the skin's band) and how
// well the textures are told apart by vibration alone (a nearest-centroid classifier fitted on a
// second population, --train-seed, and judged on this one); and whether the targets hold.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "calibration/population_levels.h"
#include "calibration/texture_levels.h"
#include "files/kiosk_config.h"
#include "surface/image_surface.h"
#include "tools/command_line.h"

namespace {

// The report: how the population was played, one table row per texture, and the targets.
std::string LevelsMarkdown(const std::vector<sas::kiosk::PopulationLevels>& rows, int count,
                           unsigned seed, double duration_scale,
                           const sas::kiosk::KioskConfig& defaults,
                           const sas::kiosk::FeltClassification& feel, unsigned train_seed) {
  const sas::kiosk::PopulationTargets targets =
      sas::kiosk::CheckPopulationTargets(rows, defaults.haptic_ceiling_db);
  const double mean_sound = targets.mean_sound, mean_haptic = targets.mean_haptic;
  std::ostringstream md;
  char line[1024];
  md << "# Texture levels over a population of visitor strokes\n\n"
        "Written by `population_levels --docs docs` (textures/population_levels.cpp); do not "
        "edit.\n"
     << count << " strokes from seed " << seed
     << " (calibration/texture_levels.h, VisitorPopulation: scrape / rub / roll, 20–400 mm/s "
        "log-uniform, pressure 0.1–0.9, "
     << 0.3 * duration_scale << "–" << 1.5 * duration_scale
     << " s, random places and directions), played on "
        "each texture through the kiosk engine with the four textures loaded (the per-stroke "
        "correction on), in visits of "
     << sas::kiosk::kVisitStrokes
     << " strokes with the kiosk's idle reset between them (the bubbles un-popped, as between "
        "visitors), at the textures' [gains] and the default kiosk gains (+"
     << defaults.sound_gain_db << " dB sound, +" << defaults.haptic_gain_db
     << " dB transducer), each stroke measured whole, from its touch-down (the landing "
        "included) to "
     << sas::kiosk::kGapAfterLiftS
     << " s after its lift: loudness in LUFS (BS.1770, ungated), transducer level as the RMS "
        "of the skin-weighted channel 2 in dB re full scale (calibration/felt.h: the hand's "
        "vibrotactile threshold, Verrillo 1963); the loudest moment is the loudest 400 ms of any stroke (EBU R 128 "
        "momentary loudness, windows every 100 ms).\n\n"
        "| texture | median LUFS (vs mean of medians) | 5–95 % | loudest stroke − median | "
        "loudest moment − median | median transducer dB (vs mean) | 5–95 % | scrape / rub / "
        "roll median LUFS | scrape / rub / roll transducer dB |\n"
        "|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    const auto s = [&](const char* k) {
      return r.per_style.count(k) ? r.per_style.at(k) : std::pair{0.0, 0.0};
    };
    std::snprintf(line, sizeof line,
                  "| %s | %.1f (%+.1f) | %.1f … %.1f | %.1f | %.1f | %.1f (%+.1f) | %.1f … %.1f | "
                  "%.1f / %.1f / %.1f | %.1f / %.1f / %.1f |\n",
                  r.name.c_str(), r.sound_median, r.sound_median - mean_sound, r.sound_p5,
                  r.sound_p95, r.sound_max - r.sound_median, r.momentary_max - r.sound_median,
                  r.haptic_median, r.haptic_median - mean_haptic, r.haptic_p5, r.haptic_p95,
                  s("scrape").first, s("rub").first, s("roll").first, s("scrape").second,
                  s("rub").second, s("roll").second);
    md << line;
  }
  md << "\nThe loudest stroke on each texture, and the stroke with its loudest moment:\n\n";
  for (const auto& r : rows) {
    md << "- " << r.name << ": " << r.loudest_stroke << "; loudest moment "
       << r.loudest_moment_stroke << "\n";
  }
  md << "\n## The vibration\n\nChannel 2 as the transducer gets it (after the final safety "
        "stage), per texture, the medians over the strokes: the share of samples within 1 dB of "
        "the transducer's ceiling (the median stroke; the loudest 5 % of strokes by skin-weighted "
        "level, their mean), the crest factor, the share of the energy within the skin's band "
        "(40–400 Hz) and the energy above 1 kHz relative to the total.\n\n"
        "| texture | near the ceiling, median stroke | near the ceiling, loudest 5 % | crest, dB "
        "| 40–400 Hz | above 1 kHz, dB |\n|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    std::snprintf(line, sizeof line, "| %s | %.2f %% | %.2f %% | %.1f | %.1f %% | %.1f |\n",
                  r.name.c_str(), 100.0 * r.felt_near_ceiling_median,
                  100.0 * r.felt_near_ceiling_loudest, r.felt_crest_median,
                  100.0 * r.felt_band_fraction_median, r.felt_above_1k_median);
    md << line;
  }
  std::snprintf(line, sizeof line,
                "\nTold apart by vibration alone: a 5-nearest-neighbour classifier on %d "
                "level-free features of each stroke's channel 2 (calibration/felt.h: five band "
                "energies of 40–400 Hz, crest factor, envelope spread and range, onsets per "
                "second, kurtosis, spectral flatness, peak and centroid, envelope periodicity, "
                "quiet share) fitted on the %d strokes per texture of seed %u picks the right "
                "texture for **%.1f %%** of these strokes (aim ≥ %.0f %%; one centroid per "
                "texture: %.1f %%). Rows: the texture played; columns: the texture picked.\n\n",
                sas::kiosk::kFeltFeatures, count, train_seed, 100.0 * feel.accuracy,
                100.0 * sas::kiosk::kMinFeltAccuracy, 100.0 * feel.centroid_accuracy);
  md << line << "| played \\ picked |";
  for (const auto& r : rows) md << " " << r.name << " |";
  md << "\n|---|";
  for (std::size_t i = 0; i < rows.size(); ++i) md << "---|";
  md << "\n";
  for (std::size_t t = 0; t < rows.size(); ++t) {
    md << "| " << rows[t].name << " |";
    for (std::size_t p = 0; p < rows.size(); ++p) {
      md << " " << (t < feel.confusion.size() ? feel.confusion[t][p] : 0) << " |";
    }
    md << "\n";
  }
  md << "\nTargets: " << sas::kiosk::DescribeTargets(targets, defaults.haptic_ceiling_db) << ".\n";
  return md.str();
}

// The README's short table (between its population-levels markers): what staff and installers
// read of the level matching, written with the document so the two never disagree.
std::string ReadmeBlock(const std::vector<sas::kiosk::PopulationLevels>& rows, int count,
                        const sas::kiosk::KioskConfig& defaults) {
  const sas::kiosk::PopulationTargets targets =
      sas::kiosk::CheckPopulationTargets(rows, defaults.haptic_ceiling_db);
  std::ostringstream md;
  md << "Measured by `population_levels` on " << count
     << " generated visitor strokes per texture (scrape, rub and roll, slow to fast, light to "
        "firm) at the default gains; details in `docs/population-levels.md`.\n\n"
        "| texture | median loudness | loudest moment | median vibration |\n"
        "|---|---|---|---|\n";
  char line[256];
  for (const auto& r : rows) {
    std::snprintf(line, sizeof line,
                  "| %s | %.1f LUFS (%+.1f LU from the mean) | %.1f LU over the median | %.1f dB "
                  "(%+.1f dB) |\n",
                  r.name.c_str(), r.sound_median, r.sound_median - targets.mean_sound,
                  r.momentary_max - r.sound_median, r.haptic_median,
                  r.haptic_median - targets.mean_haptic);
    md << line;
  }
  md << "\nThe aims: medians within ±" << sas::kiosk::kSoundSpreadLu << " LU and ±"
     << sas::kiosk::kHapticSpreadDb << " dB of the mean, no stroke over "
     << sas::kiosk::kLoudestOverMedianLu
     << " LU above its texture's median in any 400 ms, landings included: "
     << (targets.all() ? "all met" : "**not all met**") << ".\n";
  return md.str();
}

// Replaces the text between the README's markers with `block`.
void WriteReadme(const std::string& path, const std::string& block) {
  const std::string begin = "<!-- population-levels: written by population_levels --readme -->\n";
  const std::string end = "<!-- population-levels end -->";
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::string readme = text.str();
  const auto from = readme.find(begin);
  const auto to = readme.find(end);
  if (!in || from == std::string::npos || to == std::string::npos || to < from) {
    throw std::runtime_error(path + " has no population-levels markers");
  }
  readme.replace(from + begin.size(), to - from - begin.size(), block);
  std::ofstream out(path);
  out << readme;
  if (!out) throw std::runtime_error("cannot write " + path);
}

void WriteDocs(const std::string& docs, const std::string& md) {
  std::filesystem::create_directories(docs);
  std::ofstream out(std::filesystem::path(docs) / "population-levels.md");
  out << md;
  if (!out) throw std::runtime_error("cannot write " + docs + "/population-levels.md");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Texture loudness over a population of visitor strokes", "population_levels"};
  std::string textures = "textures";
  std::string docs;
  int count = 200;
  unsigned seed = 2026;
  app.add_option("--textures", textures, "the kiosk textures' folder (default textures)");
  app.add_option("--strokes", count, "population size (default 200)")->check(CLI::Range(3, 5000));
  app.add_option("--seed", seed, "population seed (default 2026)");
  unsigned train_seed = 1;
  app.add_option("--train-seed", train_seed,
                 "seed of the population the vibration classifier is fitted on (default 1)");
  app.add_option("--docs", docs, "write population-levels.md here");
  std::string readme;
  app.add_option("--readme", readme,
                 "rewrite the figures between this README's population-levels markers");
  std::string config_path;
  app.add_option("--config", config_path,
                 "a kiosk configuration file whose gains and leveller to play at (default: the "
                 "built-in defaults, which the document is about)");
  std::string features_path;
  app.add_option("--features", features_path,
                 "write every stroke's vibration features here as CSV (texture, stroke, "
                 "features), for whoever tunes the textures' feel");
  double duration_scale = 1.0;
  app.add_option("--duration-scale", duration_scale,
                 "shorten every stroke by this factor (a quick run; default 1)")
      ->check(CLI::Range(0.1, 1.0));
  if (const int code = sas::kiosk::ParseProgramCommandLine(app, argc, argv); code >= 0) return code;
  try {
    const auto strokes = sas::kiosk::VisitorPopulation(count, seed, duration_scale);
    const sas::kiosk::KioskConfig defaults =
        config_path.empty() ? sas::kiosk::KioskConfig{} : sas::kiosk::LoadKioskConfig(config_path);
    const std::vector<std::string> paths = sas::kiosk::KioskTexturePaths(textures);
    std::vector<sas::kiosk::PopulationLevels> rows;
    for (std::size_t t = 0; t < paths.size(); ++t) {
      rows.push_back(sas::kiosk::MeasurePopulation(paths, t, strokes, defaults));
      std::fprintf(stderr, "%s measured\n", rows.back().name.c_str());
    }
    const auto train_strokes = sas::kiosk::VisitorPopulation(count, train_seed, duration_scale);
    std::vector<sas::kiosk::PopulationLevels> train;
    for (std::size_t t = 0; t < paths.size(); ++t) {
      train.push_back(sas::kiosk::MeasurePopulation(paths, t, train_strokes, defaults));
    }
    const auto feel = sas::kiosk::ClassifyByFeel(train, rows);
    if (!features_path.empty()) {
      std::ofstream csv(features_path);
      csv << "texture,style,speed_mm_s,pressure,bands_40_63,bands_63_100,bands_100_160,"
             "bands_160_250,bands_250_400,crest_db,envelope_spread_db,onsets_per_s,log_kurtosis,"
             "flatness,envelope_range_db,periodicity,quiet_share,peak_log2_hz,centroid_log2_hz\n";
      for (const auto& r : rows) {
        for (std::size_t i = 0; i < r.felt_features.size() && i < strokes.size(); ++i) {
          const auto& pen = strokes[i].pen;
          const double length_mm = std::hypot((pen.x1 - pen.x0) * sas::kiosk::kScreenWidthPx,
                                              (pen.y1 - pen.y0) * sas::kiosk::kScreenHeightPx) *
                                   sas::surface::DisplayGeometry{}.pixel_pitch_mm();
          csv << r.name << "," << strokes[i].name << "," << length_mm / pen.duration_s << ","
              << pen.pressure;
          for (const double v : r.felt_features[i]) csv << "," << v;
          csv << "\n";
        }
      }
      if (!csv) throw std::runtime_error("cannot write " + features_path);
    }
    const std::string md =
        LevelsMarkdown(rows, count, seed, duration_scale, defaults, feel, train_seed);
    std::printf("%s", md.c_str());
    if (!docs.empty()) WriteDocs(docs, md);
    if (!readme.empty()) WriteReadme(readme, ReadmeBlock(rows, count, defaults));
  } catch (const std::exception& error) {
    std::fprintf(stderr, "population_levels: %s\n", error.what());
    return 1;
  }
  return 0;
}
