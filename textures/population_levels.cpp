// population_levels: the kiosk textures' loudness and vibration strength over a population of
// visitor strokes (calibration/texture_levels.h, VisitorPopulation), through the kiosk engine with
// all four textures loaded (the per-stroke correction acting as in the kiosk), at each texture's
// [gains] and the kiosk's default global gains.
//
//   population_levels [--textures DIR] [--strokes N] [--seed S] [--docs DIR]
//
// Prints, and with --docs writes DIR/population-levels.md: per texture the median stroke loudness
// (LUFS) and transducer level (dB RMS), their 5th–95th percentile spread, the loudest stroke over
// the median, and the medians per style; and whether the level-matching targets hold.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "calibration/texture_levels.h"
#include "files/kiosk_config.h"
#include "kiosk/kiosk_engine.h"
#include "surface/texture_file.h"

namespace {

// One texture's figures over the population: medians and spreads of the stroke levels, and the
// medians per style.
struct TextureLevels {
  std::string name;
  double sound_median, sound_p5, sound_p95, sound_max;
  double haptic_median, haptic_p5, haptic_p95;
  std::map<std::string, std::pair<double, double>> per_style;  // median sound, haptic
};

std::vector<std::string> KioskTexturePaths(const std::string& textures) {
  std::vector<std::string> paths;
  for (const auto& key : sas::kiosk::KioskTextureNames()) {
    paths.push_back((std::filesystem::path(textures) / key / "texture.toml").string());
  }
  return paths;
}

// Plays every stroke on texture `t` with the other three loaded, as the kiosk holds them all.
TextureLevels MeasureTexture(const std::vector<std::string>& paths, std::size_t t,
                             const std::vector<sas::kiosk::VisitorStroke>& strokes,
                             const sas::kiosk::KioskConfig& defaults) {
  sas::kiosk::LevelMeasurement measurement;
  measurement.strokes = strokes;
  measurement.global_sound_gain_db = defaults.sound_gain_db;
  measurement.global_haptic_gain_db = defaults.haptic_gain_db;
  measurement.stroke_cap_lu = defaults.stroke_cap_lu;
  measurement.strokes_per_visit = sas::kiosk::kVisitStrokes;
  for (std::size_t o = 0; o < paths.size(); ++o) {
    if (o != t) measurement.other_textures.push_back(paths[o]);
  }
  const auto file = sas::surface::LoadTextureFile(paths[t]);
  const auto levels = sas::kiosk::MeasureStrokeLevels(paths[t], file.gains, measurement);
  TextureLevels row;
  row.name = file.name;
  std::vector<double> sound, haptic;
  std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> by_style;
  for (std::size_t i = 0; i < levels.size(); ++i) {
    sound.push_back(levels[i].sound_lufs);
    haptic.push_back(levels[i].haptic_rms_db);
    by_style[strokes[i].name].first.push_back(levels[i].sound_lufs);
    by_style[strokes[i].name].second.push_back(levels[i].haptic_rms_db);
  }
  row.sound_median = sas::kiosk::Percentile(sound, 0.5);
  row.sound_p5 = sas::kiosk::Percentile(sound, 0.05);
  row.sound_p95 = sas::kiosk::Percentile(sound, 0.95);
  row.sound_max = *std::max_element(sound.begin(), sound.end());
  row.haptic_median = sas::kiosk::Percentile(haptic, 0.5);
  row.haptic_p5 = sas::kiosk::Percentile(haptic, 0.05);
  row.haptic_p95 = sas::kiosk::Percentile(haptic, 0.95);
  for (const auto& [style, v] : by_style) {
    row.per_style[style] = {sas::kiosk::Percentile(v.first, 0.5),
                            sas::kiosk::Percentile(v.second, 0.5)};
  }
  return row;
}

std::string HoldsText(bool ok) {
  return ok ? "holds" : "does not hold";
}

// The report: how the population was played, one table row per texture, and the targets.
std::string LevelsMarkdown(const std::vector<TextureLevels>& rows, int count, unsigned seed,
                           const sas::kiosk::KioskConfig& defaults) {
  double mean_sound = 0.0, mean_haptic = 0.0;
  for (const auto& r : rows) {
    mean_sound += r.sound_median / static_cast<double>(rows.size());
    mean_haptic += r.haptic_median / static_cast<double>(rows.size());
  }
  std::ostringstream md;
  char line[512];
  md << "# Texture levels over a population of visitor strokes\n\n"
        "Written by `population_levels --docs docs` (textures/population_levels.cpp); do not "
        "edit.\n"
     << count << " strokes from seed " << seed
     << " (calibration/texture_levels.h, VisitorPopulation: scrape / rub / roll, 20–400 mm/s "
        "log-uniform, pressure 0.1–0.9, 0.3–1.5 s, random places and directions), played on "
        "each texture through the kiosk engine with the four textures loaded (the per-stroke "
        "correction on), in visits of "
     << sas::kiosk::kVisitStrokes
     << " strokes with the kiosk's idle reset between them (the bubbles un-popped, as between "
        "visitors), at the textures' [gains] and the default kiosk gains (+"
     << defaults.sound_gain_db << " dB sound, +" << defaults.haptic_gain_db
     << " dB transducer), measured from 0.1 s after touch-down: loudness in LUFS (BS.1770, "
        "ungated), transducer level in dB RMS (40–800 Hz).\n\n"
        "| texture | median LUFS (vs mean of medians) | 5–95 % | loudest − median | median "
        "transducer dB (vs mean) | 5–95 % | scrape / rub / roll median LUFS | scrape / rub / "
        "roll transducer dB |\n|---|---|---|---|---|---|---|---|\n";
  bool sound_ok = true, haptic_ok = true, blast_ok = true, felt_ok = true;
  for (const auto& r : rows) {
    const auto s = [&](const char* k) {
      return r.per_style.count(k) ? r.per_style.at(k) : std::pair{0.0, 0.0};
    };
    std::snprintf(line, sizeof line,
                  "| %s | %.1f (%+.1f) | %.1f … %.1f | %.1f | %.1f (%+.1f) | %.1f … %.1f | "
                  "%.1f / %.1f / %.1f | %.1f / %.1f / %.1f |\n",
                  r.name.c_str(), r.sound_median, r.sound_median - mean_sound, r.sound_p5,
                  r.sound_p95, r.sound_max - r.sound_median, r.haptic_median,
                  r.haptic_median - mean_haptic, r.haptic_p5, r.haptic_p95, s("scrape").first,
                  s("rub").first, s("roll").first, s("scrape").second, s("rub").second,
                  s("roll").second);
    md << line;
    sound_ok = sound_ok && std::fabs(r.sound_median - mean_sound) <= 1.0;
    haptic_ok = haptic_ok && std::fabs(r.haptic_median - mean_haptic) <= 1.5;
    blast_ok = blast_ok && r.sound_max - r.sound_median <= 10.0;
    for (const char* style : {"scrape", "rub", "roll"}) {
      felt_ok = felt_ok && s(style).second >= defaults.haptic_ceiling_db - 15.0;
    }
  }
  md << "\nTargets: median loudness within ±1 LU of the mean of the four: **" << HoldsText(sound_ok)
     << "**; median transducer level within ±1.5 dB: **" << HoldsText(haptic_ok)
     << "**; no stroke more than 10 LU over its "
     << "texture's median: **" << HoldsText(blast_ok)
     << "**; every style's median transducer level within 15 dB of the transducer ceiling ("
     << defaults.haptic_ceiling_db << " dBFS): **" << HoldsText(felt_ok) << "**.\n";
  return md.str();
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
  app.add_option("--docs", docs, "write population-levels.md here");
  CLI11_PARSE(app, argc, argv);
  try {
    const auto strokes = sas::kiosk::VisitorPopulation(count, seed);
    const sas::kiosk::KioskConfig defaults;
    const std::vector<std::string> paths = KioskTexturePaths(textures);
    std::vector<TextureLevels> rows;
    for (std::size_t t = 0; t < paths.size(); ++t) {
      rows.push_back(MeasureTexture(paths, t, strokes, defaults));
      std::fprintf(stderr, "%s measured\n", rows.back().name.c_str());
    }
    const std::string md = LevelsMarkdown(rows, count, seed, defaults);
    std::printf("%s", md.c_str());
    if (!docs.empty()) WriteDocs(docs, md);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "population_levels: %s\n", error.what());
    return 1;
  }
  return 0;
}
