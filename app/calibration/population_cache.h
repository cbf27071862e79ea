#pragma once
// The shipped textures' medians over a visitor population, kept between runs: `texture new` trims
// a curator's texture against them and `texture check` prints its level against them, and measuring
// them plays hundreds of strokes per texture (minutes), while they change only with the program or
// the shipped files. A cached set is used only when its key matches; the key covers everything the
// medians depend on: the measuring program's own bytes (its DSP, the engine, the default kiosk
// gains, its version), every file of the shipped textures' folders, the material files, the
// population's size and seed. Anything else, or an unreadable or damaged file, measures afresh.
//
// The cache lives in <cache_dir>/shipped-levels-<program>-<strokes>-<seed>.txt (one file per
// population, replaced when its key changes); CacheDir() says where.

#include <string>
#include <vector>

namespace sas::kiosk {

struct ShippedMedians {
  std::vector<std::string> names;         // the textures' folder names, token order
  std::vector<double> sound, haptic;      // their population medians (LUFS, dB)
  bool from_cache = false;
  std::string cache_file;                 // read or written ("" when no cache)
};

// $SAS_CACHE_DIR, else $XDG_CACHE_HOME/sketch-a-scratch, else $HOME/.cache/sketch-a-scratch;
// "" when none is set (no caching).
std::string CacheDir();

// The key of the medians of `shipped` (their texture.toml files) over VisitorPopulation(strokes,
// seed): a 64-bit FNV-1a hash in hex. Throws when a shipped file cannot be read.
std::string ShippedLevelsKey(const std::vector<std::string>& shipped, int strokes, unsigned seed);

// The medians of each of `shipped` (loaded together, as the kiosk holds them) over
// VisitorPopulation(strokes, seed) at the kiosk's default gains (MeasurePopulation): from
// `cache_dir` when its file holds this key, else measured and written there (a cache that cannot
// be written is left alone). cache_dir "": always measured.
ShippedMedians ShippedPopulationMedians(const std::vector<std::string>& shipped, int strokes,
                                        unsigned seed, const std::string& cache_dir);

}  // namespace sas::kiosk
