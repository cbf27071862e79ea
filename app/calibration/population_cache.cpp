// The shipped textures' population medians, cached (see population_cache.h).
#include "calibration/population_cache.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "calibration/population_levels.h"
#include "calibration/texture_levels.h"
#include "files/atomic_file.h"
#include "files/kiosk_config.h"
#include "files/material_file.h"

namespace sas::kiosk {
namespace {

namespace fs = std::filesystem;

// Changes when the file's layout or the meaning of its figures does.
constexpr const char* kFormat = "shipped-levels v1";

struct Fnv1a {
  std::uint64_t h = 1469598103934665603ull;
  void Add(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) {
      h ^= p[i];
      h *= 1099511628211ull;
    }
  }
  void Add(const std::string& s) {
    Add(s.data(), s.size());
    Add("\0", 1);  // "ab"+"c" and "a"+"bc" differ
  }
  void AddFile(const fs::path& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw std::runtime_error("cannot read " + path.string());
    std::vector<char> buffer(1 << 16);
    std::uint64_t size = 0;
    while (file) {
      file.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      const auto got = static_cast<std::size_t>(file.gcount());
      Add(buffer.data(), got);
      size += got;
    }
    Add(&size, sizeof size);
  }
};

// Every regular file under `dir`, by relative name then content, in name order.
void AddFolder(Fnv1a& hash, const fs::path& dir) {
  std::vector<fs::path> files;
  std::error_code error;
  for (fs::recursive_directory_iterator it(dir, error), end; !error && it != end;
       it.increment(error)) {
    if (it->is_regular_file(error)) files.push_back(it->path());
  }
  if (error) throw std::runtime_error("cannot list " + dir.string() + ": " + error.message());
  std::sort(files.begin(), files.end());
  for (const auto& file : files) {
    hash.Add(file.lexically_relative(dir).string());
    hash.AddFile(file);
  }
}

std::string Hex(std::uint64_t v) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
  return text;
}

std::string ProgramName() {
  std::error_code error;
  const auto exe = fs::read_symlink("/proc/self/exe", error);
  std::string name = error ? std::string("program") : exe.filename().string();
  for (auto& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') c = '_';
  }
  return name;
}

// The file's medians when it holds `key` for exactly these textures, else false.
bool ReadCache(const std::string& path, const std::string& key,
               const std::vector<std::string>& names, ShippedMedians* out) {
  std::ifstream file(path);
  if (!file) return false;
  std::string line;
  bool keyed = false;
  ShippedMedians read;
  while (std::getline(file, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string word;
    fields >> word;
    if (word == "key") {
      std::string format, version, value;
      fields >> format >> version >> value;
      keyed = format + " " + version == kFormat && value == key;
    } else if (word == "texture") {
      std::string name;
      double sound = NAN, haptic = NAN;
      fields >> name >> sound >> haptic;
      if (!fields || !std::isfinite(sound) || !std::isfinite(haptic)) return false;
      read.names.push_back(name);
      read.sound.push_back(sound);
      read.haptic.push_back(haptic);
    } else {
      return false;
    }
  }
  if (!keyed || read.names != names) return false;
  *out = read;
  return true;
}

}  // namespace

std::string CacheDir() {
  if (const char* dir = std::getenv("SAS_CACHE_DIR"); dir != nullptr && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg != nullptr && *xdg) {
    return (fs::path(xdg) / "sketch-a-scratch").string();
  }
  if (const char* home = std::getenv("HOME"); home != nullptr && *home) {
    return (fs::path(home) / ".cache" / "sketch-a-scratch").string();
  }
  return {};
}

std::string ShippedLevelsKey(const std::vector<std::string>& shipped, int strokes, unsigned seed) {
  Fnv1a hash;
  hash.Add(kFormat);
  // The program that measures: its code, compiled-in defaults and version in one.
  hash.AddFile("/proc/self/exe");
  hash.Add("strokes " + std::to_string(strokes) + " seed " + std::to_string(seed));
  for (const auto& toml : shipped) {
    const fs::path folder = fs::path(toml).parent_path();
    hash.Add(folder.filename().string());
    AddFolder(hash, folder);
  }
  // The material files the textures may take theirs from, in search order.
  for (const auto& dir : MaterialSearchDirs("")) {
    std::error_code error;
    if (!fs::is_directory(dir, error)) continue;
    hash.Add(dir);
    AddFolder(hash, dir);
  }
  return Hex(hash.h);
}

ShippedMedians ShippedPopulationMedians(const std::vector<std::string>& shipped, int strokes,
                                        unsigned seed, const std::string& cache_dir) {
  std::vector<std::string> names;
  for (const auto& toml : shipped) names.push_back(fs::path(toml).parent_path().filename().string());
  std::string key, path;
  if (!cache_dir.empty()) {
    key = ShippedLevelsKey(shipped, strokes, seed);
    path = (fs::path(cache_dir) / ("shipped-levels-" + ProgramName() + "-" +
                                   std::to_string(strokes) + "-" + std::to_string(seed) + ".txt"))
               .string();
    ShippedMedians cached;
    if (ReadCache(path, key, names, &cached)) {
      cached.from_cache = true;
      cached.cache_file = path;
      return cached;
    }
  }
  ShippedMedians measured;
  measured.names = names;
  const auto population = VisitorPopulation(strokes, seed);
  const KioskConfig defaults;
  for (std::size_t t = 0; t < shipped.size(); ++t) {
    const auto levels = MeasurePopulation(shipped, t, population, defaults);
    measured.sound.push_back(levels.sound_median);
    measured.haptic.push_back(levels.haptic_median);
  }
  if (!cache_dir.empty()) {
    std::string text = "# The shipped textures' medians over " + std::to_string(strokes) +
                       " visitor strokes (seed " + std::to_string(seed) +
                       "), measured by sketch-a-scratch; safe to delete.\n";
    text += "key " + std::string(kFormat) + " " + key + "\n";
    for (std::size_t t = 0; t < names.size(); ++t) {
      char row[160];
      // %.17g: read back to the same double, so a cached trim equals a measured one exactly.
      std::snprintf(row, sizeof row, "texture %s %.17g %.17g\n", names[t].c_str(),
                    measured.sound[t], measured.haptic[t]);
      text += row;
    }
    std::error_code error;
    fs::create_directories(cache_dir, error);
    std::string why;
    if (!error && AtomicWriteFile(path, text, &why)) measured.cache_file = path;
  }
  return measured;
}

}  // namespace sas::kiosk
