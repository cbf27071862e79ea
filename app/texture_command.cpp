// `sketch-a-scratch texture ...` (see texture_command.h).
#include "texture_command.h"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <toml++/toml.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "common/text.h"
#include "calibration/population_cache.h"
#include "calibration/population_levels.h"
#include "calibration/texture_levels.h"
#include "cue_voice.h"
#include "files/atomic_file.h"
#include "files/kiosk_config.h"
#include "files/material_file.h"
#include "files/strings.h"
#include "headless_demo.h"
#include "kiosk/data_dirs.h"
#include "kiosk/staff_cues.h"
#include "platform/log/log.h"
#include "surface/image_loader.h"
#include "surface/image_surface.h"
#include "surface/texture_file.h"
#include "surface/texture_set.h"
#include "surface/wav_writer.h"
#include "tools/command_line.h"

namespace sas::app {
namespace {

using text::Fixed;
using text::Joined;

namespace fs = std::filesystem;
using kiosk::kExitOk;
using kiosk::kExitRuntimeError;
using kiosk::kExitUsage;

// The kiosk's screen: a texture's picture is made to it (the engine scales any other to cover).
constexpr int kPictureWidthPx = 1920;
constexpr int kPictureHeightPx = 1080;
// A photo much smaller than the screen is blown up: its relief is then the blur's edges, not the
// subject's. Three times up is where that starts to show on the 13.3-inch display.
constexpr int kMinPhotoWidthPx = 640;
constexpr int kMinPhotoHeightPx = 360;
// A folder's picture (replaced by hand after `new`) at least half the screen each way.
constexpr int kMinPictureWidthPx = 960;
constexpr int kMinPictureHeightPx = 540;
// A scan shorter than this is no texture: it repeats every few samples across the screen.
constexpr std::size_t kMinScanSamples = 8;
constexpr double kMaxScanHeightMm = 50.0;
// The visitor population the trim is calibrated on; the tests judge another seed (2026).
constexpr unsigned kTrimSeed = 1;

bool IsKey(const std::string& name) {
  return !name.empty() && name.size() <= 64 && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
  });
}

// The kiosk's languages: the configured one, then the visitor's choices.
std::vector<std::string> KioskLanguagesOf(const kiosk::KioskConfig& config) {
  std::vector<std::string> codes = {config.language};
  for (const auto& code : config.visitor_languages) {
    if (std::find(codes.begin(), codes.end(), code) == codes.end()) codes.push_back(code);
  }
  return codes;
}

// The configuration a command works for: --config, else the box's when there is one, else the
// built-in defaults (all five languages).
kiosk::KioskConfig ConfigFor(const std::string& path) {
  std::error_code error;
  if (path.empty()) {
    const std::string box = "/etc/sketch-a-scratch/kiosk.toml";
    if (fs::is_regular_file(box, error)) return kiosk::LoadKioskConfig(box);
    return {};
  }
  return kiosk::LoadKioskConfig(path);
}

// "lang=text" of --name / --description.
bool SplitLanguageText(const std::string& item, std::string* code, std::string* text) {
  const auto eq = item.find('=');
  if (eq == std::string::npos) return false;
  *code = item.substr(0, eq);
  *text = item.substr(eq + 1);
  return !code->empty() && !text->empty();
}

std::string TomlString(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

// "<path>:<line>:<col>: <rest>" (the texture file's loader) -> "<path>:<line>: <rest>".
std::string WithoutColumn(const std::string& message, const std::string& path) {
  if (message.rfind(path + ":", 0) != 0) return message;
  std::size_t at = path.size() + 1;
  std::size_t line_end = at;
  while (line_end < message.size() && std::isdigit(static_cast<unsigned char>(message[line_end])))
    ++line_end;
  if (line_end == at || line_end >= message.size() || message[line_end] != ':') return message;
  std::size_t col_end = line_end + 1;
  while (col_end < message.size() && std::isdigit(static_cast<unsigned char>(message[col_end])))
    ++col_end;
  if (col_end > line_end + 1 && col_end < message.size() && message[col_end] == ':')
    return message.substr(0, line_end) + message.substr(col_end);
  return message;
}

// --------------------------------------------------------------------------- the picture

// The middle of `photo` at the screen's aspect, scaled to the screen.
cv::Mat ToScreen(const cv::Mat& photo) {
  const double aspect = static_cast<double>(kPictureWidthPx) / kPictureHeightPx;
  int w = photo.cols, h = photo.rows;
  if (static_cast<double>(w) / h > aspect) {
    w = static_cast<int>(std::lround(h * aspect));
  } else {
    h = static_cast<int>(std::lround(w / aspect));
  }
  const cv::Rect middle((photo.cols - w) / 2, (photo.rows - h) / 2, w, h);
  cv::Mat out;
  cv::resize(photo(middle), out, cv::Size(kPictureWidthPx, kPictureHeightPx), 0, 0,
             w >= kPictureWidthPx ? cv::INTER_AREA : cv::INTER_CUBIC);
  return out;
}

void WritePng(const fs::path& path, const cv::Mat& image) {
  const std::vector<int> png = {cv::IMWRITE_PNG_COMPRESSION, 6};
  if (!cv::imwrite(path.string(), image, png)) {
    throw std::runtime_error("cannot write " + path.string());
  }
}

// The relief the kiosk will derive from the picture, as the 16-bit height map beside it (65535 =
// `scale_mm`): what `check` and a curator's eye judge the texture by.
void WriteDerivedHeightMap(const fs::path& folder, const surface::TextureFile& texture) {
  surface::ReliefOptions relief;
  relief.relief_mm = texture.relief_mm;
  if (texture.relief_from_brightness) relief.source = surface::ReliefSource::kLuminance;
  const auto field =
      surface::SurfaceFromImage(surface::LoadGrayImage(texture.picture_path), relief).field;
  cv::Mat height16(field.height(), field.width(), CV_16UC1);
  for (int y = 0; y < field.height(); ++y) {
    for (int x = 0; x < field.width(); ++x) {
      const double v = std::clamp(field.at(x, y) * 1e3 / texture.height_scale_mm, 0.0, 1.0);
      height16.at<std::uint16_t>(y, x) = static_cast<std::uint16_t>(std::lround(v * 65535.0));
    }
  }
  WritePng(folder / "height.png", height16);
}

}  // namespace

// --------------------------------------------------------------------------- scans

ScanGrid ReadScanCsv(const std::string& path, std::vector<std::string>* problems) {
  ScanGrid grid;
  std::ifstream in(path);
  if (!in) {
    problems->push_back(path + ":1: height: cannot be read");
    return grid;
  }
  int line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    for (char& c : line) {
      if (c == ',' || c == ';' || c == '\t' || c == '\r') c = ' ';
    }
    std::istringstream words(line);
    std::vector<double> row;
    bool bad = false;
    int column = 0;
    for (std::string word; words >> word;) {
      ++column;
      char* end = nullptr;
      const double value = std::strtod(word.c_str(), &end);
      const std::string where = path + ":" + std::to_string(line_number) + ": height: ";
      if (end == word.c_str() || *end != '\0' || !std::isfinite(value)) {
        problems->push_back(where + "'" + word + "' (value " + std::to_string(column) +
                            ") is not a finite number of millimetres");
        bad = true;
      } else if (std::fabs(value) > kMaxScanHeightMm) {
        problems->push_back(where + word + " mm (value " + std::to_string(column) +
                            ") is beyond +-" + Fixed(kMaxScanHeightMm, 0) + " mm");
        bad = true;
      }
      row.push_back(value);
    }
    if (row.empty() || bad) continue;
    if (!grid.rows.empty() && row.size() != grid.rows.front().size()) {
      problems->push_back(path + ":" + std::to_string(line_number) + ": height: " +
                          std::to_string(row.size()) + " values, the first row had " +
                          std::to_string(grid.rows.front().size()));
      continue;
    }
    grid.rows.push_back(std::move(row));
  }
  if (problems->empty() && (grid.rows.empty() || grid.rows.front().size() < kMinScanSamples)) {
    problems->push_back(path + ":" + std::to_string(std::max(line_number, 1)) +
                        ": height: a scan needs at least " + std::to_string(kMinScanSamples) +
                        " heights along its line");
  }
  return grid;
}

namespace {

// A scan's heights across the whole screen at `step_mm` per sample, mirrored at its ends so the
// surface has no step where it repeats; a line scan runs across every row. Values 0..1 over the
// scan's range, which is returned in `range_mm`.
cv::Mat ScanToScreen(const ScanGrid& grid, double step_mm, double* range_mm) {
  const double pitch_mm = surface::DisplayGeometry{}.pixel_pitch_mm();
  double lo = grid.rows[0][0], hi = lo;
  for (const auto& row : grid.rows) {
    for (const double v : row) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  *range_mm = hi - lo;
  const double span = hi > lo ? hi - lo : 1.0;
  const auto mirrored = [](double index, std::size_t n) {
    if (n < 2) return 0.0;
    const double period = 2.0 * static_cast<double>(n - 1);
    double u = std::fmod(index, period);
    if (u > static_cast<double>(n - 1)) u = period - u;
    return u;
  };
  const std::size_t cols = grid.rows[0].size(), rows = grid.rows.size();
  cv::Mat out(kPictureHeightPx, kPictureWidthPx, CV_8UC1);
  for (int y = 0; y < kPictureHeightPx; ++y) {
    const double v = mirrored(y * pitch_mm / step_mm, rows);
    const auto r0 = static_cast<std::size_t>(v);
    const std::size_t r1 = std::min(r0 + 1, rows - 1);
    const double fr = v - static_cast<double>(r0);
    for (int x = 0; x < kPictureWidthPx; ++x) {
      const double u = mirrored(x * pitch_mm / step_mm, cols);
      const auto c0 = static_cast<std::size_t>(u);
      const std::size_t c1 = std::min(c0 + 1, cols - 1);
      const double fc = u - static_cast<double>(c0);
      const double top = grid.rows[r0][c0] * (1.0 - fc) + grid.rows[r0][c1] * fc;
      const double bottom = grid.rows[r1][c0] * (1.0 - fc) + grid.rows[r1][c1] * fc;
      const double h = (top * (1.0 - fr) + bottom * fr - lo) / span;
      out.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(std::lround(255.0 * h));
    }
  }
  return out;
}

// A grey PNG (or any image OpenCV reads) of heights: 8 or 16 bits, its brightness the height
// (black 0, the format's white the full scale). As 0..1 floats; empty, with `why`, when it is no
// height map: unreadable, in colour (grey stored as RGB is taken), too small, or another depth.
cv::Mat ReadHeightMap(const std::string& path, std::string* why) {
  const cv::Mat raw = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (raw.empty()) {
    *why = "not a PNG, JPEG or TIFF image OpenCV can read";
    return {};
  }
  if (raw.depth() != CV_8U && raw.depth() != CV_16U) {
    *why = "a height map has 8 or 16 bits per sample";
    return {};
  }
  std::vector<cv::Mat> planes;
  cv::split(raw, planes);
  if (planes.size() >= 3) {
    // Grey saved as RGB is grey; colour is no height (which channel would it be?).
    if (cv::countNonZero(planes[0] != planes[1]) > 0 || cv::countNonZero(planes[1] != planes[2]) > 0) {
      *why = "in colour: a height map is grey, its brightness the height";
      return {};
    }
  }
  if (raw.cols < kMinPhotoWidthPx || raw.rows < kMinPhotoHeightPx) {
    *why = std::to_string(raw.cols) + " x " + std::to_string(raw.rows) +
           " px is too small (at least " + std::to_string(kMinPhotoWidthPx) + " x " +
           std::to_string(kMinPhotoHeightPx) + "): blown up, its relief would be the blur's";
    return {};
  }
  // 8 bits to 16 exactly (x 257: 255 -> 65535), then one scale for both, so that the same map
  // at either depth gives the same picture to the last bit. An alpha plane is left out.
  cv::Mat sixteen = planes[0];
  if (raw.depth() == CV_8U) planes[0].convertTo(sixteen, CV_16U, 257.0);
  cv::Mat heights;
  sixteen.convertTo(heights, CV_32F, 1.0 / 65535.0);
  return heights;
}

// The map's middle at the screen's aspect, scaled to the screen, as an 8-bit picture spanning its
// heights (the kiosk reads the relief from the picture's brightness, as for a scan); `range`: the
// part of the full scale they span.
cv::Mat HeightMapToScreen(const cv::Mat& heights, double* range) {
  const cv::Mat screen = ToScreen(heights);
  double lo = 0.0, hi = 0.0;
  cv::minMaxLoc(screen, &lo, &hi);
  *range = hi - lo;
  cv::Mat out;
  screen.convertTo(out, CV_8U, hi > lo ? 255.0 / (hi - lo) : 0.0,
                   hi > lo ? -255.0 * lo / (hi - lo) : 0.0);
  return out;
}

// --------------------------------------------------------------------------- texture.toml

struct NewTexture {
  std::string key;
  std::string material;
  std::map<std::string, std::string> names, descriptions;  // "en" included
  double relief_mm = 0.4;
  double height_scale_mm = 0.4;
  bool brightness = false;
  bool scan = false;
  std::string source;  // for the header comment
  surface::TextureGains gains;
  std::string levels_toml;
  std::string gains_note;
  surface::TextureProbeDefaults probe;
};

std::string TextureToml(const NewTexture& t) {
  std::string out = "# " + t.key + ": made by `sketch-a-scratch texture new` from " + t.source +
                    ".\n# Check it with `sketch-a-scratch texture check <folder>`; make it again "
                    "rather than editing [gains] and [levels].\n";
  out += "name = " + TomlString(t.names.at("en")) + "\n";
  out += "description = " + TomlString(t.descriptions.at("en")) + "\n";
  out += "material = " + TomlString(t.material) + "\n";
  out += "picture = \"picture.png\"\nheight_map = \"height.png\"\n";
  out += "height_scale_mm = " + Fixed(t.height_scale_mm, 4) + "\n";
  out += "relief_mm = " + Fixed(t.relief_mm, 4) + "\n";
  out += std::string("relief_from = \"") + (t.brightness ? "brightness" : "edges") + "\"\n";
  if (t.scan) out += "scan = \"scan.csv\"\n";
  for (const auto& [table, texts] : {std::pair{"names", &t.names},
                                     std::pair{"descriptions", &t.descriptions}}) {
    out += std::string("\n[") + table + "]\n";
    for (const auto& [code, text] : *texts) {
      if (code != "en") out += code + " = " + TomlString(text) + "\n";
    }
  }
  out += "\n[gains]\n" + t.gains_note;
  out += "sound_gain_db = " + Fixed(t.gains.sound_gain_db, 2) + "\n";
  out += "haptic_gain_db = " + Fixed(t.gains.haptic_gain_db, 2) + "\n";
  out += "sound_trim_db = " + Fixed(t.gains.sound_trim_db, 2) + "\n";
  out += "haptic_trim_db = " + Fixed(t.gains.haptic_trim_db, 2) + "\n";
  out += t.levels_toml;
  out += "\n[probe]\nwidth_mm = " + Fixed(t.probe.width_mm, 3) +
         "\npenetration_mm = " + Fixed(t.probe.penetration_mm, 3) + "\nstyle = \"" +
         std::string(synth::ProbeStyleName(t.probe.style)) + "\"\n";
  return out;
}

void WriteFile(const fs::path& path, const std::string& text) {
  std::ofstream file(path, std::ios::binary);
  file << text;
  if (!file) throw std::runtime_error("cannot write " + path.string());
}

// The population's medians of every shipped texture (the four loaded together, as
// docs/population-levels.md measures them) and of `path` shown on `token` (1-4) in place of that
// token's shipped texture, as the kiosk will hold it (the per-stroke matching refers to the
// loaded textures' levels); token 0: the mean of its medians on each of the four tokens. The new
// texture's row is last.
// The shipped rows hold only their medians, from the cache in `cache_dir` when it has them
// (population_cache.h; "": measured); what was done is said on `out`.
std::vector<kiosk::PopulationLevels> MeasureAgainstShipped(const std::string& path, int strokes,
                                                           unsigned seed, bool shipped_too,
                                                           int token, const std::string& cache_dir,
                                                           std::FILE* out) {
  const std::vector<std::string> shipped = kiosk::FindTextureFiles();
  const auto population = kiosk::VisitorPopulation(strokes, seed);
  const kiosk::KioskConfig defaults;
  std::vector<kiosk::PopulationLevels> rows;
  if (shipped_too) {
    const auto medians = kiosk::ShippedPopulationMedians(shipped, strokes, seed, cache_dir);
    for (std::size_t t = 0; t < shipped.size(); ++t) {
      kiosk::PopulationLevels row;
      row.name = medians.names[t];
      row.sound_median = medians.sound[t];
      row.haptic_median = medians.haptic[t];
      rows.push_back(row);
    }
    const std::string how = medians.from_cache         ? "from the cache " + medians.cache_file
                            : medians.cache_file.empty() ? std::string("measured (not cached)")
                                                         : "measured, cached in " + medians.cache_file;
    std::fprintf(out, "  the shipped textures' levels over %d strokes (seed %u): %s\n", strokes,
                 seed, how.c_str());
  }
  kiosk::PopulationLevels mine;
  double sound = 0.0, haptic = 0.0;
  int placed = 0;
  for (std::size_t t = 0; t < shipped.size(); ++t) {
    if (token > 0 && static_cast<int>(t) != token - 1) continue;
    std::vector<std::string> kiosk = shipped;
    kiosk[t] = path;
    mine = kiosk::MeasurePopulation(kiosk, t, population, defaults);
    sound += mine.sound_median;
    haptic += mine.haptic_median;
    ++placed;
  }
  mine.sound_median = sound / placed;
  mine.haptic_median = haptic / placed;
  rows.push_back(mine);
  return rows;
}

// --------------------------------------------------------------------------- cues

struct CueSource {
  std::string espeak;     // espeak-ng program ("" none)
  std::string cues_from;  // <dir>/<language>/name.* and description.* ("" none)
};

// The name and description cues of `t` in every language, into <folder>/cues/<language>/.
void MakeCues(const fs::path& folder, const NewTexture& t, const CueSource& source,
              std::FILE* out) {
  const std::string strings = kiosk::FindStringsDir();
  for (const auto& [code, name] : t.names) {
    const fs::path dir = folder / kiosk::kStaffCuesFolder / code;
    fs::create_directories(dir);
    for (const auto& [part, text] :
         {std::pair<std::string, std::string>{"name", name}, {"description", t.descriptions.at(code)}}) {
      const std::string key = t.key + "_" + part;
      if (!source.cues_from.empty()) {
        // The curator's recording, any format the kiosk reads; checked like the staff's cues.
        const fs::path from_dir = fs::path(source.cues_from) / code;
        std::optional<fs::path> found;
        std::error_code error;
        for (fs::directory_iterator it(from_dir, error), end; !error && it != end;
             it.increment(error)) {
          if (it->path().stem() == part && it->path().extension() != ".txt") found = it->path();
        }
        if (!found) {
          throw std::runtime_error("no recording " + (from_dir / part).string() +
                                   ".<wav|flac|ogg|opus> for the " + code + " " + part);
        }
        fs::copy_file(*found, dir / (key + found->extension().string()),
                      fs::copy_options::overwrite_existing);
      } else {
        const auto table = kiosk::LoadLanguageTable(strings, code);
        const auto speech =
            cues::SpeakEspeak(source.espeak, table.espeak_voice, table.words_per_minute, text,
                              (dir / (key + ".espeak.wav")).string());
        const auto shaped = cues::ShapeCue(speech);
        surface::WriteWav((dir / (key + ".wav")).string(), shaped.data(), shaped.size(), 1,
                          static_cast<int>(cues::kCueRateHz), surface::WavFormat::kPcm24);
      }
      WriteFile(dir / (key + ".txt"), text + "\n");
    }
    std::fprintf(out, "  cues %s: %s_name, %s_description\n", code.c_str(), t.key.c_str(),
                 t.key.c_str());
  }
}

std::string FindEspeak() {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path != nullptr ? path : "/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const fs::path candidate = fs::path(dir) / "espeak-ng";
    if (access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return {};
}

// --------------------------------------------------------------------------- new

struct NewOptions {
  std::string out_dir, photo, scan, height_map, material = "wood", config, espeak, cues_from;
  std::vector<std::string> names, descriptions;
  double relief_mm = 0.4;
  double scan_step_mm = 0.1;
  double width_mm = 0.3;
  double penetration_mm = 0.01;
  std::string style = "scrape";
  // The median of 200 strokes moves by up to ~0.9 LU from one population to another on a texture
  // whose strokes spread widely (a scan's file teeth: measured against the held-out seed); 600
  // brings that near 0.5.
  int population = 600;
  int token = 0;  // the token it is meant for (0: any)
  bool force = false;
  bool no_cache = false;
};

int RunNew(const NewOptions& o, std::FILE* out, std::FILE* err) {
  const auto fail = [&](const std::string& why) {
    std::fprintf(err, "sketch-a-scratch texture new: %s\n", why.c_str());
    return kExitRuntimeError;
  };
  if (o.photo.empty() + o.scan.empty() + o.height_map.empty() != 2) {
    return fail("give one of --photo, --height-map or --scan");
  }
  NewTexture t;
  const fs::path folder = fs::absolute(o.out_dir).lexically_normal();
  t.key = folder.filename().string();
  if (!IsKey(t.key)) {
    return fail("the folder's name '" + t.key +
                "' names the texture's cues and token: lower-case letters, digits and _ only");
  }
  const auto config = ConfigFor(o.config);
  const auto languages = KioskLanguagesOf(config);
  for (const auto& [items, into, what] :
       {std::tuple{&o.names, &t.names, "--name"}, {&o.descriptions, &t.descriptions, "--description"}}) {
    for (const auto& item : *items) {
      std::string code, text;
      if (!SplitLanguageText(item, &code, &text)) {
        return fail(std::string(what) + " '" + item + "': expected LANGUAGE=TEXT (en=...)");
      }
      const auto& known = kiosk::KioskLanguages();
      if (std::find(known.begin(), known.end(), code) == known.end()) {
        return fail(std::string(what) + " '" + item + "': " + code +
                    " is no language the kiosk knows (" + Joined(known) + ")");
      }
      (*into)[code] = text;
    }
  }
  std::vector<std::string> missing;
  for (const auto& code : languages) {
    if (!t.names.count(code)) missing.push_back("--name " + code + "=...");
    if (!t.descriptions.count(code)) missing.push_back("--description " + code + "=...");
  }
  if (!t.names.count("en")) missing.push_back("--name en=... (the texture file's own name)");
  if (!t.descriptions.count("en")) missing.push_back("--description en=...");
  if (!missing.empty()) {
    return fail("the kiosk speaks " + Joined(languages) + ": missing " + Joined(missing));
  }
  for (const auto& [code, text] : t.descriptions) {
    if (t.names.count(code) == 0) return fail("a description in " + code + " but no --name " + code);
  }
  for (const auto& [code, text] : t.names) {
    if (t.descriptions.count(code) == 0) return fail("--name " + code + " but no description");
  }

  // The material: a shipped one's name, or a file of the curator's, copied into the folder.
  std::optional<fs::path> material_file;
  if (o.material.find('/') != std::string::npos || fs::path(o.material).extension() == ".toml") {
    material_file = o.material;
    t.material = fs::path(o.material).stem().string();
    if (!IsKey(t.material)) return fail("a material file's name must be lower-case letters, digits, _");
    (void)kiosk::LoadMaterialFile(o.material);  // throws with file:line: key: what
  } else {
    t.material = o.material;
    (void)kiosk::FindMaterial(o.material, kiosk::MaterialSearchDirs(""));
  }
  if (t.material == "bubble_wrap") {
    return fail("bubble_wrap needs a bubble layout: choose another material for a curator's texture");
  }
  CueSource cue_source{o.espeak.empty() ? FindEspeak() : o.espeak, o.cues_from};
  if (cue_source.cues_from.empty() && cue_source.espeak.empty()) {
    return fail("no espeak-ng to speak the cues with (install espeak-ng, or record them: --cues-from)");
  }

  std::error_code error;
  if (fs::exists(folder, error) && !fs::is_empty(folder, error) && !o.force) {
    return fail(folder.string() + " exists and is not empty (--force replaces what is in it)");
  }
  fs::create_directories(folder);
  std::fprintf(out, "Making texture %s in %s\n", t.key.c_str(), folder.c_str());

  ScanGrid grid;
  if (!o.photo.empty()) {
    const cv::Mat photo = cv::imread(o.photo, cv::IMREAD_COLOR);
    if (photo.empty()) return fail(o.photo + ": not a PNG or JPEG picture OpenCV can read");
    if (photo.cols < kMinPhotoWidthPx || photo.rows < kMinPhotoHeightPx) {
      return fail(o.photo + ": " + std::to_string(photo.cols) + " x " + std::to_string(photo.rows) +
                  " px is too small (at least " + std::to_string(kMinPhotoWidthPx) + " x " +
                  std::to_string(kMinPhotoHeightPx) + "): blown up, its relief would be the blur's");
    }
    WritePng(folder / "picture.png", ToScreen(photo));
    t.relief_mm = o.relief_mm;
    t.height_scale_mm = o.relief_mm;
    t.source = "the photo " + fs::path(o.photo).filename().string() + " (" +
               std::to_string(photo.cols) + " x " + std::to_string(photo.rows) + " px)";
  } else if (!o.height_map.empty()) {
    std::string why;
    const cv::Mat map = ReadHeightMap(o.height_map, &why);
    if (map.empty()) return fail(o.height_map + ": " + why);
    double range = 0.0;
    WritePng(folder / "picture.png", HeightMapToScreen(map, &range));
    // White in the map is --relief-mm; the picture spans the heights the map uses.
    t.relief_mm = o.relief_mm * range;
    if (!(t.relief_mm >= 0.001)) {
      return fail(o.height_map + ": the height map is flat (its heights span " +
                  Fixed(t.relief_mm * 1e3, 2) + " um at --relief-mm " + Fixed(o.relief_mm, 2) + ")");
    }
    t.brightness = true;
    t.height_scale_mm = t.relief_mm;
    t.source = "the height map " + fs::path(o.height_map).filename().string() + " (" +
               std::to_string(map.cols) + " x " + std::to_string(map.rows) + " px, white " +
               Fixed(o.relief_mm, 3) + " mm)";
  } else {
    std::vector<std::string> problems;
    grid = ReadScanCsv(o.scan, &problems);
    if (!problems.empty()) {
      for (const auto& p : problems) std::fprintf(err, "%s\n", p.c_str());
      return fail(std::to_string(problems.size()) + " problem(s) in the scan");
    }
    double range_mm = 0.0;
    WritePng(folder / "picture.png", ScanToScreen(grid, o.scan_step_mm, &range_mm));
    if (!(range_mm >= 0.001)) return fail(o.scan + ": the scan is flat (its heights are all equal)");
    fs::copy_file(o.scan, folder / "scan.csv", fs::copy_options::overwrite_existing);
    t.scan = true;
    t.brightness = true;
    t.relief_mm = std::min(range_mm, 10.0);
    t.height_scale_mm = t.relief_mm;
    t.source = "the scan " + fs::path(o.scan).filename().string() + " (" +
               std::to_string(grid.rows.size()) + " x " + std::to_string(grid.rows[0].size()) +
               " heights, " + Fixed(o.scan_step_mm, 3) + " mm apart, " + Fixed(range_mm, 3) +
               " mm deep)";
  }
  if (material_file) {
    fs::copy_file(*material_file, folder / (t.material + ".toml"),
                  fs::copy_options::overwrite_existing);
  }
  t.probe.width_mm = o.width_mm;
  t.probe.penetration_mm = o.penetration_mm;
  t.probe.style = synth::ParseProbeStyle(o.style).value_or(synth::ProbeStyle::kScrape);
  const fs::path toml = folder / "texture.toml";
  WriteFile(toml, TextureToml(t));
  WriteDerivedHeightMap(folder, surface::LoadTextureFile(toml.string()));

  // Levels: the shipped textures' calibration first (gains and the stroke table), then the
  // visitor population's trim against the shipped textures' mean.
  std::fprintf(out, "  calibrating its levels (%zu grid strokes through the kiosk engine)...\n",
               kiosk::CalibrationStrokes().size());
  std::fflush(out);
  const auto calibration = kiosk::CalibrateTexture(toml.string());
  t.gains = calibration.gains;
  t.levels_toml = kiosk::LevelTableToml(calibration.levels);
  WriteFile(toml, TextureToml(t));
  std::fprintf(out, "  gains %.2f dB sound, %.2f dB vibration; trimming on %d visitor strokes...\n",
               t.gains.sound_gain_db, t.gains.haptic_gain_db, o.population);
  std::fflush(out);
  const std::string cache_dir = o.no_cache ? std::string() : kiosk::CacheDir();
  auto rows =
      MeasureAgainstShipped(toml.string(), o.population, kTrimSeed, true, o.token, cache_dir, out);
  double mean_sound = 0.0, mean_haptic = 0.0;
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    mean_sound += rows[i].sound_median / static_cast<double>(rows.size() - 1);
    mean_haptic += rows[i].haptic_median / static_cast<double>(rows.size() - 1);
  }
  // The trims act after the per-stroke matching, nearly one to one; a second pass takes up what
  // the leveller and the limiters bend.
  for (int pass = 0; pass < 2; ++pass) {
    const auto& mine = rows.back();
    const double off_sound = mean_sound - mine.sound_median;
    const double off_haptic = mean_haptic - mine.haptic_median;
    if (pass > 0 && std::fabs(off_sound) < 0.2 && std::fabs(off_haptic) < 0.3) break;
    t.gains.sound_trim_db = std::clamp(t.gains.sound_trim_db + off_sound, -12.0, 12.0);
    t.gains.haptic_trim_db = std::clamp(t.gains.haptic_trim_db + off_haptic, -12.0, 12.0);
    WriteFile(toml, TextureToml(t));
    rows.back() =
        MeasureAgainstShipped(toml.string(), o.population, kTrimSeed, false, o.token, cache_dir,
                              out)
            .back();
  }
  t.gains_note = "# Calibrated by `texture new` as the shipped textures are (calibration/"
                 "texture_levels.h); the trims put its\n# median over " +
                 std::to_string(o.population) + " visitor strokes (seed " +
                 std::to_string(kTrimSeed) + ") at the shipped textures' mean: " +
                 Fixed(rows.back().sound_median, 1) + " LUFS against " + Fixed(mean_sound, 1) +
                 ",\n# vibration " + Fixed(rows.back().haptic_median, 1) + " dB against " +
                 Fixed(mean_haptic, 1) + ".\n";
  WriteFile(toml, TextureToml(t));
  std::fprintf(out,
               "  level over the visitor population: median %.1f LUFS (%+.1f LU against the "
               "shipped textures' mean), vibration %.1f dB (%+.1f dB)\n",
               rows.back().sound_median, rows.back().sound_median - mean_sound,
               rows.back().haptic_median, rows.back().haptic_median - mean_haptic);
  MakeCues(folder, t, cue_source, out);
  const auto problems = CheckTextureFolder(folder.string(), languages);
  for (const auto& p : problems) std::fprintf(err, "%s\n", p.c_str());
  if (!problems.empty()) return fail("the new texture does not pass its own check");
  std::fprintf(out,
               "Done. Look at it: sketch-a-scratch texture preview %s --out DIR; install it: "
               "sketch-a-scratch texture install %s --token N\n",
               folder.c_str(), folder.c_str());
  return kExitOk;
}

// --------------------------------------------------------------------------- check

int KeyLine(const toml::table& root, std::string_view table, std::string_view key) {
  const toml::node* node = table.empty() ? root.get(key) : nullptr;
  if (!table.empty()) {
    if (const auto* t = root.get_as<toml::table>(table)) node = key.empty() ? t : t->get(key);
  }
  return node != nullptr ? static_cast<int>(node->source().begin.line) : 1;
}

}  // namespace

std::vector<std::string> CheckTextureFolder(const std::string& folder_arg,
                                            const std::vector<std::string>& languages) {
  std::vector<std::string> problems;
  const fs::path folder = fs::absolute(folder_arg).lexically_normal();
  const std::string toml_path = (folder / "texture.toml").string();
  const auto at = [&](int line, const std::string& key, const std::string& what) {
    problems.push_back(toml_path + ":" + std::to_string(line) + ": " + key + ": " + what);
  };
  std::error_code error;
  if (!fs::is_directory(folder, error)) {
    problems.push_back(folder.string() + ":1: folder: not a folder");
    return problems;
  }
  const std::string key = folder.filename().string();
  if (!IsKey(key)) {
    problems.push_back(folder.string() + ":1: folder: its name '" + key +
                       "' must be lower-case letters, digits and _ (it names the cues and tokens)");
  }
  if (!fs::is_regular_file(toml_path, error)) {
    at(1, "texture.toml", "missing");
    return problems;
  }
  surface::TextureFile texture;
  toml::table root;
  try {
    texture = surface::LoadTextureFile(toml_path);
    root = toml::parse_file(toml_path);
  } catch (const std::exception& bad) {
    problems.push_back(WithoutColumn(bad.what(), toml_path));
    return problems;  // the rest needs a readable file
  }
  // Languages: every one the kiosk speaks, and none it does not know.
  const auto& known = kiosk::KioskLanguages();
  for (const auto& [table, texts] : {std::pair{"names", &texture.names},
                                     std::pair{"descriptions", &texture.descriptions}}) {
    for (const auto& [code, text] : *texts) {
      if (std::find(known.begin(), known.end(), code) == known.end()) {
        at(KeyLine(root, table, code), std::string(table) + "." + code,
           "'" + code + "' is no language the kiosk knows (" + Joined(known) + ")");
      } else if (code == "en") {
        at(KeyLine(root, table, code), std::string(table) + ".en",
           "English is the file's own name and description, not a [" + std::string(table) +
               "] entry");
      }
    }
    for (const auto& code : languages) {
      if (code != "en" && texts->count(code) == 0) {
        at(KeyLine(root, table, ""), std::string(table) + "." + code,
           "missing: the kiosk speaks " + code + " ([language] in kiosk.toml)");
      }
    }
  }
  // The picture: readable, and large enough for the screen.
  int picture_width = 0, picture_height = 0;
  try {
    const auto picture = surface::LoadGrayImage(texture.picture_path);
    picture_width = picture.width;
    picture_height = picture.height;
    if (picture.width < kMinPictureWidthPx || picture.height < kMinPictureHeightPx) {
      at(KeyLine(root, "", "picture"), "picture",
         fs::path(texture.picture_path).filename().string() + " is " +
             std::to_string(picture.width) + " x " + std::to_string(picture.height) +
             " px: at least " + std::to_string(kMinPictureWidthPx) + " x " +
             std::to_string(kMinPictureHeightPx) + " (make it with texture new from a photo)");
    }
  } catch (const std::exception& bad) {
    at(KeyLine(root, "", "picture"), "picture", bad.what());
  }
  if (!fs::is_regular_file(texture.height_map_path, error)) {
    at(KeyLine(root, "", "height_map"), "height_map",
       fs::path(texture.height_map_path).filename().string() + " is missing");
  } else {
    // The height map is the picture's relief pixel for pixel (texture new derives it): one of
    // another size, or no grey image, belongs to another picture.
    const std::string name = fs::path(texture.height_map_path).filename().string();
    const cv::Mat height = cv::imread(texture.height_map_path, cv::IMREAD_UNCHANGED);
    if (height.empty()) {
      at(KeyLine(root, "", "height_map"), "height_map", name + " is no image OpenCV can read");
    } else if (height.channels() != 1 || (height.depth() != CV_8U && height.depth() != CV_16U)) {
      at(KeyLine(root, "", "height_map"), "height_map",
         name + " is not a grey 8- or 16-bit image");
    } else if (picture_width > 0 &&
               (height.cols != picture_width || height.rows != picture_height)) {
      at(KeyLine(root, "", "height_map"), "height_map",
         name + " is " + std::to_string(height.cols) + " x " + std::to_string(height.rows) +
             " px, the picture " + std::to_string(picture_width) + " x " +
             std::to_string(picture_height) +
             ": they are one surface (make the texture again with texture new)");
    }
  }
  // The material: the folder's own file first, then the shipped ones.
  try {
    auto dirs = kiosk::MaterialSearchDirs("");
    dirs.insert(dirs.begin(), folder.string());
    (void)kiosk::FindMaterial(texture.material, dirs);
  } catch (const std::exception& bad) {
    const std::string why = bad.what();
    // A material file's own errors already name their file and line.
    if (why.find(".toml:") != std::string::npos) {
      problems.push_back(why);
    } else {
      at(KeyLine(root, "", "material"), "material", why);
    }
  }
  if (!texture.levels) {
    at(1, "levels", "missing: the texture is not calibrated (make it with texture new)");
  }
  if (!texture.scan_path.empty()) ReadScanCsv(texture.scan_path, &problems);
  // The cues: a name and a description in every language, each one the kiosk would take.
  platform::Logger log;
  log.SetEchoToStderr(false);
  std::vector<std::string> keys = {key + "_name", key + "_description"};
  const auto cues = kiosk::LoadStaffCues((folder / kiosk::kStaffCuesFolder).string(), languages,
                                         keys, 48000.0, log);
  for (const auto& line : log.Recent()) {
    if (line.level >= platform::LogLevel::kWarn) {
      // "staff cue <path> refused: <why>; ..." -> "<path>:1: cue: <why>"
      std::string message = line.message;
      const std::string prefix = "staff cue ";
      if (message.rfind(prefix, 0) == 0) message.erase(0, prefix.size());
      const auto refused = message.find(" refused: ");
      if (refused != std::string::npos) {
        std::string why = message.substr(refused + 10);
        if (const auto semi = why.rfind("; "); semi != std::string::npos) why.erase(semi);
        problems.push_back(message.substr(0, refused) + ":1: cue: " + why);
      } else {
        problems.push_back(folder.string() + "/cues:1: cue: " + message);
      }
    }
  }
  for (const auto& code : languages) {
    for (const auto& cue_key : keys) {
      const auto language = cues.find(code);
      if (language == cues.end() || language->second.count(cue_key) == 0) {
        const int line = code == "en" ? KeyLine(root, "", cue_key == keys[0] ? "name" : "description")
                                      : KeyLine(root, cue_key == keys[0] ? "names" : "descriptions", code);
        at(line, "cues", "no usable cues/" + code + "/" + cue_key +
                             ".wav: blind visitors would not hear it (texture new speaks them, "
                             "or record one)");
      }
    }
  }
  return problems;
}

namespace {

// The figures a curator looks at, for a folder that passed its check.
void PrintFigures(const std::string& folder, int strokes, int token, const std::string& cache_dir,
                  std::FILE* out) {
  const std::string toml = (fs::path(folder) / "texture.toml").string();
  const auto loaded = surface::LoadTexture(toml);
  const auto& file = loaded.file;
  // How the sound follows the hand, from its calibrated table: scrape, slow to fast, light to firm.
  if (file.levels) {
    const auto& l = *file.levels;
    const auto mean_at = [&](int style, std::size_t speed, std::size_t pressure) {
      double sum = 0.0;
      for (std::size_t w = 0; w < l.widths_mm(style).size(); ++w) {
        sum += l.sound_lufs[l.Index(style, w, speed, pressure)];
      }
      return sum / static_cast<double>(l.widths_mm(style).size());
    };
    const std::size_t mid_p = l.pressures.size() / 2, mid_v = l.speeds_mm_s.size() / 2;
    for (const auto& [style, name] : {std::pair{0, "scrape"}, std::pair{1, "rub"}}) {
      std::fprintf(out,
                   "  gesture response (%s, at the texture's gains): %+.1f dB from %.0f to %.0f "
                   "mm/s, %+.1f dB from pressure %.2f to %.2f\n",
                   name, mean_at(style, l.speeds_mm_s.size() - 1, mid_p) - mean_at(style, 0, mid_p),
                   l.speeds_mm_s.front(), l.speeds_mm_s.back(),
                   mean_at(style, mid_v, l.pressures.size() - 1) - mean_at(style, mid_v, 0),
                   l.pressures.front(), l.pressures.back());
    }
  }
  // How much of the relief a pen feels: the share of the surface above the probe's penetration
  // threshold (what lies below it is felt as flat).
  {
    const auto& h = loaded.field->heights_m();
    const double threshold_m = file.probe.penetration_mm * 1e-3;
    const auto felt = std::count_if(h.begin(), h.end(), [&](float v) { return v > threshold_m; });
    std::fprintf(out,
                 "  felt relief: %.1f %% of the surface stands above the pen's %.3f mm "
                 "penetration (relief %.3f mm)\n",
                 100.0 * static_cast<double>(felt) / static_cast<double>(h.size()),
                 file.probe.penetration_mm, file.relief_mm);
  }
  if (strokes > 0) {
    const auto rows = MeasureAgainstShipped(toml, strokes, 7, true, token, cache_dir, out);
    double mean_sound = 0.0, mean_haptic = 0.0;
    for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
      mean_sound += rows[i].sound_median / static_cast<double>(rows.size() - 1);
      mean_haptic += rows[i].haptic_median / static_cast<double>(rows.size() - 1);
    }
    const auto& mine = rows.back();
    std::fprintf(out,
                 "  level over %d visitor strokes (seed 7): median %.1f LUFS, %+.1f LU against "
                 "the shipped textures' mean (%.1f; within +-%.0f LU is matched); vibration "
                 "%.1f dB, %+.1f dB; loudest stroke +%.1f LU over the median\n",
                 strokes, mine.sound_median, mine.sound_median - mean_sound, mean_sound,
                 kiosk::kSoundSpreadLu, mine.haptic_median, mine.haptic_median - mean_haptic,
                 mine.sound_max - mine.sound_median);
  }
}

// Copies `from` into `into` whole or not at all: a copy beside it, then renames.
void InstallFolder(const fs::path& from, const fs::path& into) {
  fs::create_directories(into.parent_path());
  const std::string tag = "." + into.filename().string() + "." + std::to_string(getpid());
  const fs::path fresh = into.parent_path() / (tag + ".new");
  const fs::path old = into.parent_path() / (tag + ".old");
  fs::remove_all(fresh);
  fs::copy(from, fresh, fs::copy_options::recursive);
  // The kiosk runs as its own user: whatever the curator's umask or the source's modes, the
  // folder must be readable by it (and nothing in it executable).
  const auto readable_dir = fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                            fs::perms::others_read | fs::perms::others_exec;
  const auto readable_file = fs::perms::owner_read | fs::perms::owner_write |
                             fs::perms::group_read | fs::perms::others_read;
  fs::permissions(into.parent_path(), readable_dir, fs::perm_options::add);
  fs::permissions(fresh, readable_dir, fs::perm_options::replace);
  for (const auto& entry : fs::recursive_directory_iterator(fresh)) {
    fs::permissions(entry.path(), entry.is_directory() ? readable_dir : readable_file,
                    fs::perm_options::replace);
  }
  std::error_code error;
  const bool had = fs::exists(into, error);
  if (had) fs::rename(into, old);
  fs::rename(fresh, into);
  if (had) fs::remove_all(old);
}

// kiosk.toml with [textures] token_N = "key": the line replaced, or added to the table, or the
// table added; the result must parse before it replaces the file.
std::string WithToken(const std::string& text, int token, const std::string& key) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  const std::string assignment = "token_" + std::to_string(token) + " = " + TomlString(key);
  const auto trimmed = [](std::string s) {
    s.erase(0, s.find_first_not_of(" \t"));
    return s;
  };
  int table = -1, end = static_cast<int>(lines.size());
  for (int i = 0; i < static_cast<int>(lines.size()); ++i) {
    const std::string line = trimmed(lines[static_cast<std::size_t>(i)]);
    if (line.rfind("[", 0) == 0) {
      if (table >= 0) {
        end = i;
        break;
      }
      if (line.rfind("[textures]", 0) == 0) table = i;
    }
  }
  if (table < 0) {
    if (!lines.empty() && !lines.back().empty()) lines.push_back("");
    lines.push_back("[textures]");
    lines.push_back(assignment);
  } else {
    bool replaced = false;
    const std::string name = "token_" + std::to_string(token);
    for (int i = table + 1; i < end; ++i) {
      const std::string line = trimmed(lines[static_cast<std::size_t>(i)]);
      if (line.rfind(name, 0) == 0 && line.find('=') != std::string::npos &&
          trimmed(line.substr(name.size())).rfind("=", 0) == 0) {
        lines[static_cast<std::size_t>(i)] = assignment;
        replaced = true;
      }
    }
    if (!replaced) lines.insert(lines.begin() + table + 1, assignment);
  }
  std::string out;
  for (const auto& line : lines) out += line + "\n";
  return out;
}

}  // namespace

int RunTextureCommand(const std::vector<std::string>& args, std::FILE* out, std::FILE* err) {
  CLI::App app(
      "A curator's own textures: make one from a photo or a scan (new), check it (check), hear "
      "and see it (preview), put it where the kiosk reads staff textures (install).",
      "texture");
  app.require_subcommand(1);
  NewOptions n;
  auto* make =
      app.add_subcommand("new", "make a texture folder from a photo, a height map or a scan");
  make->add_option("folder", n.out_dir, "the texture folder to make; its name is the texture's")
      ->required();
  make->add_option("--photo", n.photo, "a PNG or JPEG photograph, any size (cropped to 16:9)");
  make->add_option("--height-map", n.height_map,
                   "a grey PNG of heights, 8 or 16 bits (white: --relief-mm), any size (cropped to "
                   "16:9); its brightness is the relief and the picture");
  make->add_option("--scan", n.scan,
                   "a CSV of heights in mm: one row (a line scan) or a grid, --scan-step-mm apart");
  kiosk::AddNumberOption(*make, "--scan-step-mm", n.scan_step_mm, 0.001, 100.0,
                         "the scan's sample spacing (default 0.1 mm)");
  make->add_option("--material", n.material,
                   "a shipped material (wood, glass, dry_soil, metal, plastic) or a material "
                   "file (copied into the folder); default wood");
  make->add_option("--name", n.names, "LANGUAGE=NAME, once per language the kiosk speaks")
      ->required()
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  make->add_option("--description", n.descriptions,
                   "LANGUAGE=ONE SENTENCE, once per language the kiosk speaks")
      ->required()
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  kiosk::AddNumberOption(*make, "--relief-mm", n.relief_mm, 0.01, 10.0,
                         "a photo's strongest ridge height, a height map's white (default 0.4 mm)");
  kiosk::AddNumberOption(*make, "--width-mm", n.width_mm, 0.05, 20.0,
                         "the probe's default width (default 0.3 mm)");
  kiosk::AddNumberOption(*make, "--penetration-mm", n.penetration_mm, 0.0, 5.0,
                         "the probe's default penetration (default 0.01 mm)");
  make->add_option("--config", n.config,
                   "the kiosk.toml whose languages it must speak (default: the box's, else all "
                   "five)");
  make->add_option("--espeak", n.espeak, "the espeak-ng program (default: found in PATH)");
  make->add_option("--cues-from", n.cues_from,
                   "recorded cues instead of espeak-ng: DIR/<language>/name.wav and "
                   "description.wav (any format the kiosk reads)");
  make->add_option("--population", n.population,
                   "visitor strokes the level trim is measured on (default 600)")
      ->check(CLI::Range(20, 5000));
  make->add_option("--token", n.token,
                   "the token (1-4) it will show on: its level is matched in that kiosk set "
                   "(default: the mean over the four)")
      ->check(CLI::Range(1, 4));
  make->add_flag("--force", n.force, "replace what the folder holds");
  make->add_flag("--no-cache", n.no_cache,
                 "measure the shipped textures' levels afresh (else kept in $XDG_CACHE_HOME/"
                 "sketch-a-scratch, or ~/.cache/sketch-a-scratch, keyed on the program and files)");

  std::string folder, config_path, staff_dir, preview_out;
  int figures_strokes = 100;
  int token = 0;
  bool check_no_cache = false;
  auto* check = app.add_subcommand("check", "check a texture folder and print its figures");
  check->add_flag("--no-cache", check_no_cache, "measure the shipped textures' levels afresh");
  check->add_option("folder", folder, "the texture folder")->required();
  check->add_option("--config", config_path, "the kiosk.toml whose languages it must speak");
  check->add_option("--token", token, "the token (1-4) its level is measured on (default: each)")
      ->check(CLI::Range(1, 4));
  check->add_option("--strokes", figures_strokes,
                    "visitor strokes for its level against the shipped textures (0: skip)")
      ->check(CLI::Range(0, 5000));
  auto* preview = app.add_subcommand("preview", "render visitor strokes to WAVs and PNGs");
  preview->add_option("folder", folder, "the texture folder")->required();
  preview->add_option("--out", preview_out, "where the WAVs, PNGs and preview.txt go")->required();
  preview->add_option("--config", config_path, "the kiosk.toml whose languages it must speak");
  auto* install = app.add_subcommand("install", "check, then copy into <staff_dir>/textures/");
  install->add_option("folder", folder, "the texture folder")->required();
  install->add_option("--config", config_path,
                      "the kiosk.toml (default /etc/sketch-a-scratch/kiosk.toml): its staff_dir "
                      "and languages; --token edits it");
  install->add_option("--staff-dir", staff_dir, "instead of the configuration's staff_dir");
  install->add_option("--token", token, "show it on this token (1-4): sets [textures] token_N")
      ->check(CLI::Range(1, 4));
  if (const int code = kiosk::ParseCommandLine(app, args, out, err); code >= 0) return code;

  try {
    if (make->parsed()) return RunNew(n, out, err);
    const auto languages_for = [&](const std::string& path) {
      return KioskLanguagesOf(ConfigFor(path));
    };
    if (check->parsed()) {
      const auto problems = CheckTextureFolder(folder, languages_for(config_path));
      for (const auto& p : problems) std::fprintf(out, "%s\n", p.c_str());
      if (!problems.empty()) {
        std::fprintf(out, "%zu problem(s): the kiosk would refuse this texture\n", problems.size());
        return kExitRuntimeError;
      }
      std::fprintf(out, "%s: no problems\n", folder.c_str());
      PrintFigures(folder, figures_strokes, token,
                   check_no_cache ? std::string() : kiosk::CacheDir(), out);
      return kExitOk;
    }
    if (preview->parsed()) {
      const auto problems = CheckTextureFolder(folder, languages_for(config_path));
      for (const auto& p : problems) std::fprintf(err, "%s\n", p.c_str());
      if (!problems.empty()) return kExitRuntimeError;
      return RunTexturePreview((fs::absolute(folder) / "texture.toml").string(), preview_out, out,
                               err);
    }
    if (install->parsed()) {
      const std::string config_file =
          config_path.empty() ? "/etc/sketch-a-scratch/kiosk.toml" : config_path;
      std::error_code error;
      kiosk::KioskConfig config;
      if (fs::is_regular_file(config_file, error)) config = kiosk::LoadKioskConfig(config_file);
      const std::string staff = staff_dir.empty() ? config.staff_dir : staff_dir;
      if (staff.empty()) {
        std::fprintf(err, "sketch-a-scratch texture install: no staff_dir ([paths] in %s)\n",
                     config_file.c_str());
        return kExitRuntimeError;
      }
      const auto problems = CheckTextureFolder(folder, KioskLanguagesOf(config));
      for (const auto& p : problems) std::fprintf(err, "%s\n", p.c_str());
      if (!problems.empty()) {
        std::fprintf(err, "sketch-a-scratch texture install: %zu problem(s): nothing installed\n",
                     problems.size());
        return kExitRuntimeError;
      }
      const fs::path from = fs::absolute(folder).lexically_normal();
      const fs::path into = fs::path(kiosk::StaffTexturesDir(staff)) / from.filename();
      // The new config first (it may be refused), then the folder.
      std::string config_text;
      if (token > 0) {
        std::ifstream file(config_file, std::ios::binary);
        std::stringstream buffer;
        buffer << file.rdbuf();
        config_text = WithToken(buffer.str(), token, from.filename().string());
        (void)kiosk::ParseKioskConfig(config_text, config_file);
      }
      InstallFolder(from, into);
      std::fprintf(out, "installed %s\n", into.c_str());
      if (token > 0) {
        std::string why;
        if (!kiosk::AtomicWriteFile(config_file, config_text, &why)) {
          std::fprintf(err, "sketch-a-scratch texture install: %s\n", why.c_str());
          return kExitRuntimeError;
        }
        std::fprintf(out, "token %d shows %s (%s [textures] token_%d); restart the kiosk\n", token,
                     from.filename().c_str(), config_file.c_str(), token);
      } else {
        std::fprintf(out, "show it on a token: [textures] token_N = \"%s\" in %s\n",
                     from.filename().c_str(), config_file.c_str());
      }
      return kExitOk;
    }
  } catch (const std::exception& error) {
    std::fprintf(err, "sketch-a-scratch texture: %s\n", error.what());
    return kExitRuntimeError;
  }
  return kExitUsage;
}

}  // namespace sas::app
