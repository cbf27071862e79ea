// curator_levels_check: a curator's texture, shown on token N in place of that token's shipped
// texture, over the visitor population the tests hold out (seed 2026, not the one `texture new`
// trims on): its median loudness must lie within kSoundSpreadLu of the shipped four textures'
// mean, each measured as docs/population-levels.md measures them (calibration/population_levels.h,
// the kiosk's default gains). Prints both figures; exit 1 when it does not.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "calibration/population_cache.h"
#include "calibration/population_levels.h"
#include "calibration/texture_levels.h"
#include "kiosk/data_dirs.h"
#include "tools/command_line.h"

int main(int argc, char** argv) {
  CLI::App app{"Checks a curator's texture's level against the shipped textures' mean",
               "curator_levels_check"};
  std::string texture;
  int token = 3;
  int strokes = 200;
  app.add_option("texture", texture, "its texture.toml")->required();
  app.add_option("--token", token, "the token it replaces (1-4, default 3)")->check(CLI::Range(1, 4));
  app.add_option("--strokes", strokes, "population size (default 200)")->check(CLI::Range(10, 5000));
  if (const int code = sas::kiosk::ParseProgramCommandLine(app, argc, argv); code >= 0) return code;
  try {
    const auto population = sas::kiosk::VisitorPopulation(strokes, 2026);
    const sas::kiosk::KioskConfig defaults;
    const std::vector<std::string> shipped = sas::kiosk::FindTextureFiles();
    // The shipped textures' medians are this program's own measure, cached under its own key.
    const auto medians = sas::kiosk::ShippedPopulationMedians(shipped, strokes, 2026,
                                                              sas::kiosk::CacheDir());
    double mean = 0.0;
    for (const double median : medians.sound) mean += median / static_cast<double>(shipped.size());
    std::printf("the shipped textures' medians: %s\n",
                medians.from_cache ? ("from the cache " + medians.cache_file).c_str() : "measured");
    std::vector<std::string> kiosk = shipped;
    const auto at = static_cast<std::size_t>(token - 1);
    kiosk[at] = texture;
    const double median =
        sas::kiosk::MeasurePopulation(kiosk, at, population, defaults).sound_median;
    std::printf("curator texture on token %d: median %.2f LUFS over %d visitor strokes (seed 2026); "
                "the shipped textures' mean %.2f LUFS; %+.2f LU (bound +-%.1f)\n",
                token, median, strokes, mean, median - mean, sas::kiosk::kSoundSpreadLu);
    return std::fabs(median - mean) <= sas::kiosk::kSoundSpreadLu ? 0 : 1;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "curator_levels_check: %s\n", error.what());
    return 1;
  }
}
