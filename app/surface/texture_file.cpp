// Texture file loading and validation with toml++ (see texture_file.h).
#include "surface/texture_file.h"

#include <toml++/toml.h>
#include <algorithm>
#include <array>
#include <filesystem>
#include <functional>
#include <set>

#include "surface/image_loader.h"  // LoadError, ReadFileBytes

namespace sas::surface {
namespace {

// Error context: the file, and where a node sits in it.
class Checker {
 public:
  explicit Checker(std::string path) : path_(std::move(path)) {}

  [[noreturn]] void Fail(const toml::source_region& where, const std::string& key,
                         const std::string& why) const {
    throw LoadError(path_ + ":" + std::to_string(where.begin.line) + ":" +
                    std::to_string(where.begin.column) + ": " + key + ": " + why);
  }

  // Rejects any key of `table` not in `allowed`.
  void OnlyKeys(const toml::table& table, const std::string& prefix,
                std::initializer_list<std::string_view> allowed) const {
    for (const auto& [key, node] : table) {
      if (std::find(allowed.begin(), allowed.end(), key.str()) == allowed.end()) {
        Fail(key.source(), prefix + std::string(key.str()), "unknown key");
      }
    }
  }

  const toml::node& Need(const toml::table& table, const toml::source_region& table_where,
                         const std::string& prefix, std::string_view key) const {
    const toml::node* node = table.get(key);
    if (node == nullptr) Fail(table_where, prefix + std::string(key), "missing required key");
    return *node;
  }

  std::string String(const toml::table& table, const toml::source_region& where,
                     const std::string& prefix, std::string_view key) const {
    const toml::node& node = Need(table, where, prefix, key);
    const auto value = node.value<std::string>();
    if (!node.is_string() || !value)
      Fail(node.source(), prefix + std::string(key), "must be a string");
    if (value->empty()) Fail(node.source(), prefix + std::string(key), "must not be empty");
    return *value;
  }

  double Number(const toml::table& table, const toml::source_region& where,
                const std::string& prefix, std::string_view key, double lo, double hi) const {
    const toml::node& node = Need(table, where, prefix, key);
    if (!node.is_number()) Fail(node.source(), prefix + std::string(key), "must be a number");
    const double value = *node.value<double>();
    if (!(value >= lo && value <= hi)) {
      Fail(node.source(), prefix + std::string(key),
           "value " + std::to_string(value) + " outside [" + std::to_string(lo) + ", " +
               std::to_string(hi) + "]");
    }
    return value;
  }

  const toml::table& Table(const toml::table& table, const toml::source_region& where,
                           std::string_view key) const {
    const toml::node& node = Need(table, where, "", key);
    if (!node.is_table())
      Fail(node.source(), std::string(key), "must be a table [" + std::string(key) + "]");
    return *node.as_table();
  }

 private:
  std::string path_;
};

// An array of numbers within [lo, hi]; `count` > 0: exactly that many.
std::vector<double> Numbers(const Checker& check, const toml::table& table, std::string_view key,
                            double lo, double hi, std::size_t count,
                            const char* count_is = "widths x speeds x pressures") {
  const std::string name = "levels." + std::string(key);
  const toml::node& node = check.Need(table, table.source(), "levels.", key);
  if (!node.is_array()) check.Fail(node.source(), name, "must be an array of numbers");
  const toml::array& array = *node.as_array();
  if (count > 0 && array.size() != count) {
    check.Fail(node.source(), name,
               "must hold " + std::to_string(count) + " numbers (" + count_is + ")");
  }
  if (array.empty() || array.size() > 256)
    check.Fail(node.source(), name, "must hold 1..256 numbers");
  std::vector<double> values;
  for (const toml::node& element : array) {
    if (!element.is_number()) check.Fail(element.source(), name, "must be an array of numbers");
    const double value = *element.value<double>();
    if (!(value >= lo && value <= hi)) {
      check.Fail(element.source(), name,
                 "value " + std::to_string(value) + " outside [" + std::to_string(lo) + ", " +
                     std::to_string(hi) + "]");
    }
    values.push_back(value);
  }
  return values;
}

StrokeLevelTable ParseLevels(const Checker& check, const toml::table& table) {
  check.OnlyKeys(table, "levels.",
                 {"scrape_widths_mm", "rub_widths_mm", "speeds_mm_s", "pressures",
                  "scrape_sound_lufs", "scrape_haptic_rms_db", "rub_sound_lufs",
                  "rub_haptic_rms_db", "roll_widths_mm", "roll_sound_lufs", "roll_haptic_rms_db"});
  StrokeLevelTable levels;
  levels.scrape_widths_mm = Numbers(check, table, "scrape_widths_mm", 0.05, 50.0, 0);
  levels.rub_widths_mm = Numbers(check, table, "rub_widths_mm", 0.05, 50.0,
                                 levels.scrape_widths_mm.size(), "as many as scrape_widths_mm");
  // Roll rows came later than scrape and rub: a table without them stays valid.
  const bool roll = table.contains("roll_widths_mm") || table.contains("roll_sound_lufs") ||
                    table.contains("roll_haptic_rms_db");
  if (roll) {
    levels.roll_widths_mm = Numbers(check, table, "roll_widths_mm", 0.05, 50.0, 0);
  }
  levels.speeds_mm_s = Numbers(check, table, "speeds_mm_s", 1.0, 5000.0, 0);
  levels.pressures = Numbers(check, table, "pressures", 0.01, 1.0, 0);
  const std::pair<const char*, const std::vector<double>*> axes[] = {
      {"scrape_widths_mm", &levels.scrape_widths_mm},
      {"rub_widths_mm", &levels.rub_widths_mm},
      {"roll_widths_mm", &levels.roll_widths_mm},
      {"speeds_mm_s", &levels.speeds_mm_s},
      {"pressures", &levels.pressures}};
  for (const auto& [key, axis] : axes) {
    if (!axis->empty() &&
        std::adjacent_find(axis->begin(), axis->end(), std::greater_equal<>()) != axis->end()) {
      check.Fail(table.get(key)->source(), std::string("levels.") + key,
                 "must be strictly increasing");
    }
  }
  const std::size_t per_width = levels.speeds_mm_s.size() * levels.pressures.size();
  for (const char* style : {"scrape", "rub", "roll"}) {
    if (!roll && std::string_view(style) == "roll") break;
    const std::size_t per_style =
        per_width * (std::string_view(style) == "roll" ? levels.roll_widths_mm.size()
                                                       : levels.scrape_widths_mm.size());
    for (const bool sound : {true, false}) {
      const std::string key = std::string(style) + (sound ? "_sound_lufs" : "_haptic_rms_db");
      const auto values = Numbers(check, table, key, -200.0, 20.0, per_style);
      auto& into = sound ? levels.sound_lufs : levels.haptic_rms_db;
      into.insert(into.end(), values.begin(), values.end());
    }
  }
  return levels;
}

// A text the kiosk speaks as a description: one sentence, short enough to be heard out.
void CheckSentence(const Checker& check, const std::string& d, const toml::source_region& where,
                   const std::string& key) {
  if (d.size() > 240) check.Fail(where, key, "longer than 240 characters");
  const auto stop = d.find_first_of(".!?");
  if (stop == std::string::npos || stop != d.size() - 1) {
    check.Fail(where, key, "must be exactly one sentence ending in '.', '!' or '?'");
  }
}

}  // namespace

TextureFile ParseTextureFile(const std::string& text, const std::string& path) {
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw LoadError(path + ":" + std::to_string(e.source().begin.line) + ":" +
                    std::to_string(e.source().begin.column) + ": syntax: " +
                    std::string(e.description()));
  }
  const Checker check(path);
  const toml::source_region top{{1, 1}, {1, 1}, nullptr};
  check.OnlyKeys(root, "",
                 {"name", "description", "material", "picture", "height_map", "height_scale_mm",
                  "relief_mm", "gains", "levels", "probe", "bubbles", "relief_from", "scan",
                  "names", "descriptions"});
  TextureFile t;
  t.name = check.String(root, top, "", "name");
  t.description = check.String(root, top, "", "description");
  CheckSentence(check, t.description, root.get("description")->source(), "description");
  // Other languages' names and descriptions: a table of two-letter codes; which codes the kiosk
  // speaks is the kiosk's business (texture check says which are missing or unknown).
  for (const char* table_key : {"names", "descriptions"}) {
    const toml::node* node = root.get(table_key);
    if (node == nullptr) continue;
    if (!node->is_table()) {
      check.Fail(node->source(), table_key, std::string("must be a table [") + table_key + "]");
    }
    const bool sentences = std::string_view(table_key) == "descriptions";
    auto& into = sentences ? t.descriptions : t.names;
    for (const auto& [code, value] : *node->as_table()) {
      const std::string key = std::string(table_key) + "." + std::string(code.str());
      const bool code_ok =
          code.str().size() == 2 && std::all_of(code.str().begin(), code.str().end(),
                                                 [](char c) { return c >= 'a' && c <= 'z'; });
      if (!code_ok) check.Fail(code.source(), key, "not a language code (two lower-case letters)");
      const auto entry = value.value<std::string>();
      if (!value.is_string() || !entry) check.Fail(value.source(), key, "must be a string");
      if (entry->empty()) check.Fail(value.source(), key, "must not be empty");
      if (sentences) CheckSentence(check, *entry, value.source(), key);
      into[std::string(code.str())] = *entry;
    }
  }
  t.material = check.String(root, top, "", "material");
  // A material file's name (files/material_file.h finds it): letters, digits and '_' only, so it
  // can never climb out of the materials folder.
  if (t.material.size() > 64 ||
      !std::all_of(t.material.begin(), t.material.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
      })) {
    check.Fail(root.get("material")->source(), "material",
               "'" + t.material + "' is no material name (lower-case letters, digits and _)");
  }
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  t.picture_path = (folder / check.String(root, top, "", "picture")).string();
  t.height_map_path = (folder / check.String(root, top, "", "height_map")).string();
  t.height_scale_mm = check.Number(root, top, "", "height_scale_mm", 0.001, 50.0);
  t.relief_mm = check.Number(root, top, "", "relief_mm", 0.0, 10.0);
  if (root.contains("relief_from")) {
    const std::string from = check.String(root, top, "", "relief_from");
    if (from != "edges" && from != "brightness") {
      check.Fail(root.get("relief_from")->source(), "relief_from",
                 "'" + from + "' is not edges or brightness");
    }
    t.relief_from_brightness = from == "brightness";
  }
  if (root.contains("scan")) t.scan_path = (folder / check.String(root, top, "", "scan")).string();

  const toml::table& gains = check.Table(root, top, "gains");
  check.OnlyKeys(gains, "gains.",
                 {"sound_gain_db", "haptic_gain_db", "sound_trim_db", "haptic_trim_db"});
  // Wide upper bound: the calibrated gains (calibration/texture_levels.h) bring a material whose
  // modes lie far above the transducer's 40–400 Hz band (glass) up to the others' vibration
  // strength.
  t.gains.sound_gain_db =
      check.Number(gains, gains.source(), "gains.", "sound_gain_db", -60.0, 80.0);
  t.gains.haptic_gain_db =
      check.Number(gains, gains.source(), "gains.", "haptic_gain_db", -60.0, 80.0);
  if (gains.contains("sound_trim_db")) {
    t.gains.sound_trim_db =
        check.Number(gains, gains.source(), "gains.", "sound_trim_db", -12.0, 12.0);
  }
  if (gains.contains("haptic_trim_db")) {
    t.gains.haptic_trim_db =
        check.Number(gains, gains.source(), "gains.", "haptic_trim_db", -12.0, 12.0);
  }

  if (const toml::node* node = root.get("levels")) {
    if (!node->is_table()) check.Fail(node->source(), "levels", "must be a table [levels]");
    t.levels = ParseLevels(check, *node->as_table());
  }

  const toml::table& probe = check.Table(root, top, "probe");
  check.OnlyKeys(probe, "probe.", {"width_mm", "penetration_mm", "style"});
  t.probe.width_mm = check.Number(probe, probe.source(), "probe.", "width_mm", 0.01, 50.0);
  t.probe.penetration_mm =
      check.Number(probe, probe.source(), "probe.", "penetration_mm", 0.0, 10.0);
  const std::string style = check.String(probe, probe.source(), "probe.", "style");
  if (const auto parsed = synth::ParseProbeStyle(style)) {
    t.probe.style = *parsed;
  } else {
    check.Fail(probe.get("style")->source(), "probe.style",
               "'" + style + "' is not scrape, rub or roll");
  }

  if (const toml::node* node = root.get("bubbles")) {
    if (t.material != "bubble_wrap") {
      check.Fail(node->source(), "bubbles", "only a bubble_wrap texture has bubbles");
    }
    if (!node->is_table()) check.Fail(node->source(), "bubbles", "must be a table [bubbles]");
    const toml::table& b = *node->as_table();
    check.OnlyKeys(
        b, "bubbles.",
        {"pop_force_n", "layout", "pitch_px", "radius_px", "origin_x_px", "origin_y_px"});
    BubbleSettings s;
    s.pop_force_n = check.Number(b, b.source(), "bubbles.", "pop_force_n", 0.05, 50.0);
    const std::string layout = check.String(b, b.source(), "bubbles.", "layout");
    if (layout != "hexagonal") {
      check.Fail(b.get("layout")->source(), "bubbles.layout", "only 'hexagonal' is supported");
    }
    s.layout.pitch_px = check.Number(b, b.source(), "bubbles.", "pitch_px", 4.0, 4096.0);
    s.layout.radius_px = check.Number(b, b.source(), "bubbles.", "radius_px", 1.0, 2048.0);
    if (s.layout.radius_px * 2.0 > s.layout.pitch_px) {
      check.Fail(b.get("radius_px")->source(), "bubbles.radius_px",
                 "bubbles would overlap (2 r > pitch)");
    }
    s.layout.origin_x_px = check.Number(b, b.source(), "bubbles.", "origin_x_px", -4096.0, 16384.0);
    s.layout.origin_y_px = check.Number(b, b.source(), "bubbles.", "origin_y_px", -4096.0, 16384.0);
    t.bubbles = s;
  } else if (t.material == "bubble_wrap") {
    check.Fail(top, "bubbles", "missing required table for a bubble_wrap texture");
  }
  return t;
}

TextureFile LoadTextureFile(const std::string& path) {
  const auto bytes = ReadFileBytes(path, 1U << 20);
  return ParseTextureFile(std::string(bytes.begin(), bytes.end()), path);
}

}  // namespace sas::surface
