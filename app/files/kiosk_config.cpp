// Kiosk configuration loading and validation with toml++ (see kiosk_config.h).
#include "files/kiosk_config.h"

#include "files/atomic_file.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <vector>

namespace sas::kiosk {
namespace {

std::string Where(const std::string& source, const toml::source_region& region,
                  const std::string& key) {
  return source + ":" + std::to_string(region.begin.line) + ": " + key + ": ";
}

// One accepted key: where it lives and how to apply it. Keeping the schema as data means the
// validator and the README's key list cannot drift apart silently.
struct KeySpec {
  const char* table;
  const char* key;
  std::function<void(const toml::node&, KioskConfig&, const std::string& where)> apply;
};

auto Text(std::string KioskConfig::*member, bool may_be_empty = false) {
  return [=](const toml::node& node, KioskConfig& config, const std::string& where) {
    const auto value = node.value<std::string>();
    if (!node.is_string() || !value) throw ConfigError(where + "expected a string");
    if (value->empty() && !may_be_empty) throw ConfigError(where + "must not be empty");
    config.*member = *value;
  };
}

// A folder: empty (none) or an absolute path (the unit's working directory is /, so a relative one
// would point somewhere nobody meant).
auto Folder(std::string KioskConfig::*member) {
  return [=](const toml::node& node, KioskConfig& config, const std::string& where) {
    const auto value = node.value<std::string>();
    if (!node.is_string() || !value) throw ConfigError(where + "expected a string");
    if (!value->empty() && value->front() != '/') {
      throw ConfigError(where + "expected an absolute path (starting with /) or \"\"");
    }
    config.*member = *value;
  };
}

// The metrics file: "" (none) or a name ending in .prom, the only files node-exporter's textfile
// collector reads; a relative one is in the state folder.
auto MetricsFile(std::string KioskConfig::*member) {
  return [=](const toml::node& node, KioskConfig& config, const std::string& where) {
    const auto value = node.value<std::string>();
    if (!node.is_string() || !value) throw ConfigError(where + "expected a string");
    const std::string suffix = ".prom";
    if (!value->empty() &&
        (value->size() <= suffix.size() || value->back() == '/' ||
         value->compare(value->size() - suffix.size(), suffix.size(), suffix) != 0)) {
      throw ConfigError(where +
                        "expected a file name ending in .prom (node-exporter reads only "
                        "those) or \"\"");
    }
    config.*member = *value;
  };
}

auto Choice(std::string KioskConfig::*member, std::vector<std::string> choices) {
  return [=](const toml::node& node, KioskConfig& config, const std::string& where) {
    const auto value = node.value<std::string>();
    std::string listed;
    for (const auto& choice : choices) listed += (listed.empty() ? "" : ", ") + choice;
    if (!node.is_string() || !value) {
      throw ConfigError(where + "expected a string (one of " + listed + ")");
    }
    for (const auto& choice : choices) {
      if (*value == choice) {
        config.*member = *value;
        return;
      }
    }
    throw ConfigError(where + "\"" + *value + "\" is not one of " + listed);
  };
}

auto Flag(bool KioskConfig::*member) {
  return [=](const toml::node& node, KioskConfig& config, const std::string& where) {
    if (!node.is_boolean()) throw ConfigError(where + "expected true or false");
    config.*member = *node.value<bool>();
  };
}

// A staff chord: "mod+mod[+mod...]+key" with at least two of ctrl, alt, shift, super (a single
// modifier is one a visitor hits by accident). The key name itself is SDL's to judge: the window
// refuses an unknown one at start and the kiosk then keeps the default chord (live_kiosk.cpp).
auto Chord(std::string KioskConfig::*member) {
  return [=](const toml::node& node, KioskConfig& config, const std::string& where) {
    const auto value = node.value<std::string>();
    if (!node.is_string() || !value) throw ConfigError(where + "expected a string");
    std::vector<std::string> parts;
    std::string part;
    for (const char c : *value + "+") {
      if (c != '+') {
        part += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        continue;
      }
      parts.push_back(part);
      part.clear();
    }
    int modifiers = 0;
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
      if (parts[i] != "ctrl" && parts[i] != "alt" && parts[i] != "shift" && parts[i] != "super") {
        throw ConfigError(where + "unknown modifier '" + parts[i] +
                          "' (ctrl, alt, shift or super)");
      }
      ++modifiers;
    }
    if (modifiers < 2 || parts.back().empty()) {
      throw ConfigError(where + "expected at least two modifiers and a key, e.g. \"ctrl+alt+s\"");
    }
    config.*member = *value;
  };
}

auto TextList(std::vector<std::string> KioskConfig::*member, std::size_t count) {
  return [=](const toml::node& node, KioskConfig& config, const std::string& where) {
    const auto* array = node.as_array();
    if (array == nullptr || array->size() != count) {
      throw ConfigError(where + "expected a list of " + std::to_string(count) + " strings");
    }
    std::vector<std::string> values;
    for (const auto& element : *array) {
      const auto value = element.value<std::string>();
      if (!element.is_string() || !value) {
        throw ConfigError(where + "expected a list of " + std::to_string(count) + " strings");
      }
      values.push_back(*value);
    }
    config.*member = std::move(values);
  };
}

// Language codes, each one of `allowed`, none twice; an empty list is allowed.
auto LanguageList(std::vector<std::string> KioskConfig::*member, std::vector<std::string> allowed) {
  return [=](const toml::node& node, KioskConfig& config, const std::string& where) {
    const auto* array = node.as_array();
    if (array == nullptr) throw ConfigError(where + "expected a list of language codes");
    std::vector<std::string> values;
    for (const auto& element : *array) {
      const auto value = element.value<std::string>();
      if (!element.is_string() || !value ||
          std::find(allowed.begin(), allowed.end(), *value) == allowed.end()) {
        throw ConfigError(where + "expected language codes among en, de, fr, it, es");
      }
      if (std::find(values.begin(), values.end(), *value) != values.end()) {
        throw ConfigError(where + "'" + *value + "' is listed twice");
      }
      values.push_back(*value);
    }
    config.*member = std::move(values);
  };
}

auto Integer(int KioskConfig::*member, int min, int max) {
  return [=](const toml::node& node, KioskConfig& config, const std::string& where) {
    if (!node.is_integer()) throw ConfigError(where + "expected an integer");
    const int64_t value = *node.value<int64_t>();
    if (value < min || value > max) {
      throw ConfigError(where + std::to_string(value) + " is out of range [" + std::to_string(min) +
                        ", " + std::to_string(max) + "]");
    }
    config.*member = static_cast<int>(value);
  };
}

auto Real(double KioskConfig::*member, double min, double max) {
  return [=](const toml::node& node, KioskConfig& config, const std::string& where) {
    if (!node.is_number()) throw ConfigError(where + "expected a number");
    const double value = *node.value<double>();
    if (!std::isfinite(value)) throw ConfigError(where + "must be a finite number");
    if (value < min || value > max) {
      std::ostringstream message;
      message << where << value << " is out of range [" << min << ", " << max << "]";
      throw ConfigError(message.str());
    }
    config.*member = value;
  };
}

// As Real, and 0 is accepted too: it means "off", and the range holds for every other value.
auto RealOrOff(double KioskConfig::*member, double min, double max) {
  return [=](const toml::node& node, KioskConfig& config, const std::string& where) {
    if (!node.is_number()) throw ConfigError(where + "expected a number");
    const double value = *node.value<double>();
    if (!std::isfinite(value)) throw ConfigError(where + "must be a finite number");
    if (value != 0.0 && (value < min || value > max)) {
      std::ostringstream message;
      message << where << value << " is out of range [" << min << ", " << max << "] (or 0: off)";
      throw ConfigError(message.str());
    }
    config.*member = value;
  };
}

// A texture's folder name: lower-case letters, digits and '_' (it names cue files and counters,
// and may never leave the textures folder).
bool IsTextureName(const std::string& value) {
  return !value.empty() && value.size() <= 64 && std::all_of(value.begin(), value.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
  });
}

auto TokenTexture(std::size_t token) {
  return [=](const toml::node& node, KioskConfig& config, const std::string& where) {
    const auto value = node.value<std::string>();
    if (!node.is_string() || !value) throw ConfigError(where + "expected a string");
    if (!IsTextureName(*value)) {
      throw ConfigError(where + "expected a texture folder name (lower-case letters, digits, _)");
    }
    config.token_textures[token] = *value;
  };
}

// A texture folder's name; whether the kiosk shows it is judged with [textures] (below).
auto DefaultTexture() {
  return [](const toml::node& node, KioskConfig& config, const std::string& where) {
    const auto value = node.value<std::string>();
    if (!node.is_string() || !value || !IsTextureName(*value)) {
      throw ConfigError(where + "expected a texture folder name (lower-case letters, digits, _)");
    }
    config.default_texture = *value;
  };
}

const std::vector<KeySpec>& Schema() {
  static const std::vector<KeySpec> schema = {
      {"audio", "output_device", Text(&KioskConfig::output_device)},
      {"audio", "input_device", Text(&KioskConfig::input_device)},
      {"audio", "sample_rate_hz", Integer(&KioskConfig::sample_rate_hz, 8000, 192000)},
      {"audio", "buffer_frames", Integer(&KioskConfig::buffer_frames, 16, 4096)},
      {"audio", "reopen_backoff_initial_s",
       Real(&KioskConfig::reopen_backoff_initial_s, 0.01, 60.0)},
      {"audio", "reopen_backoff_max_s", Real(&KioskConfig::reopen_backoff_max_s, 0.1, 600.0)},
      {"audio", "stall_timeout_s", Real(&KioskConfig::stall_timeout_s, 0.1, 60.0)},
      {"recording", "max_duration_s", Real(&KioskConfig::record_max_duration_s, 0.5, 5.0)},
      {"recording", "silence_rms_dbfs", Real(&KioskConfig::record_silence_rms_dbfs, -120.0, -6.0)},
      {"recording", "clip_level", Real(&KioskConfig::record_clip_level, 0.5, 1.0)},
      {"switches", "backend",
       Choice(&KioskConfig::switches_backend, {"auto", "gpio", "mcp2221", "keyboard"})},
      {"switches", "debounce_ms", Integer(&KioskConfig::switches_debounce_ms, 0, 1000)},
      {"switches", "active_low", Flag(&KioskConfig::switches_active_low)},
      {"switches", "gpio_chip", Text(&KioskConfig::gpio_chip)},
      {"switches", "gpio_lines", TextList(&KioskConfig::gpio_lines, 5)},
      {"switches", "mcp2221_path", Text(&KioskConfig::mcp2221_path, true)},
      {"switches", "mcp2221_poll_ms", Integer(&KioskConfig::mcp2221_poll_ms, 5, 1000)},
      {"pen", "device", Text(&KioskConfig::pen_device, true)},
      {"pen", "seat", Text(&KioskConfig::pen_seat)},
      {"gains", "sound_gain_db", Real(&KioskConfig::sound_gain_db, -60.0, 40.0)},
      {"gains", "haptic_gain_db", Real(&KioskConfig::haptic_gain_db, -60.0, 40.0)},
      {"gains", "sound_ceiling_db", Real(&KioskConfig::sound_ceiling_db, -40.0, 0.0)},
      {"gains", "haptic_ceiling_db", Real(&KioskConfig::haptic_ceiling_db, -40.0, 0.0)},
      {"gains", "low_vibration_db", Real(&KioskConfig::low_vibration_db, 0.0, 40.0)},
      {"gains", "stroke_cap_lu", Real(&KioskConfig::stroke_cap_lu, 0.0, 40.0)},
      {"gains", "ambient_adaptive", Flag(&KioskConfig::ambient_adaptive)},
      {"gains", "ambient_min_db", Real(&KioskConfig::ambient_min_db, -20.0, 30.0)},
      {"gains", "ambient_max_db", Real(&KioskConfig::ambient_max_db, -20.0, 30.0)},
      {"gains", "ambient_per_db", Real(&KioskConfig::ambient_per_db, 0.0, 2.0)},
      {"gains", "ambient_quiet_dbfs", Real(&KioskConfig::ambient_quiet_dbfs, -120.0, 0.0)},
      {"gains", "ambient_rate_db_per_s", Real(&KioskConfig::ambient_rate_db_per_s, 0.01, 20.0)},
      {"session", "idle_timeout_s", Real(&KioskConfig::idle_timeout_s, 5.0, 3600.0)},
      // One of the four kiosk textures (the engine's folder names) or a staff texture a token
      // shows: checked against [textures] once the whole file is read (a typo used to be
      // accepted and the kiosk silently showed its first texture instead).
      {"session", "default_texture", DefaultTexture()},
      {"session", "describe_after_rest_s", Real(&KioskConfig::describe_after_rest_s, 0.0, 10.0)},
      {"attract", "passive_stroke", Flag(&KioskConfig::attract_passive_stroke)},
      {"attract", "invitation_interval_s", Real(&KioskConfig::invitation_interval_s, 0.0, 3600.0)},
      {"language", "default", Choice(&KioskConfig::language, {"en", "de", "fr", "it", "es"})},
      {"language", "visitor_choices",
       LanguageList(&KioskConfig::visitor_languages, {"en", "de", "fr", "it", "es"})},
      {"staff", "chord", Chord(&KioskConfig::staff_chord)},
      {"staff", "chord_hold_s", Real(&KioskConfig::staff_chord_hold_s, 0.0, 10.0)},
      {"staff", "panel_timeout_s", Real(&KioskConfig::staff_panel_timeout_s, 10.0, 86400.0)},
      // The actuator's resonance: 0 (no compensation), else the range of the inertial actuators
      // a stylus can carry (exciters from ~20 Hz, linear resonant actuators up to a few hundred).
      {"transducer", "resonance_hz",
       RealOrOff(&KioskConfig::transducer_resonance_hz, 20.0, 1000.0)},
      {"transducer", "q", Real(&KioskConfig::transducer_q, 0.3, 50.0)},
      {"textures", "token_1", TokenTexture(0)},
      {"textures", "token_2", TokenTexture(1)},
      {"textures", "token_3", TokenTexture(2)},
      {"textures", "token_4", TokenTexture(3)},
      {"paths", "staff_dir", Folder(&KioskConfig::staff_dir)},
      {"fleet", "metrics_file", MetricsFile(&KioskConfig::metrics_file)},
      {"fleet", "metrics_interval_s", Real(&KioskConfig::metrics_interval_s, 1.0, 300.0)},
      {"fleet", "box_name", Text(&KioskConfig::box_name, true)},
  };
  return schema;
}

}  // namespace

KioskConfig ParseKioskConfig(const std::string& text, const std::string& source_name) {
  toml::table root;
  try {
    root = toml::parse(text, source_name);
  } catch (const toml::parse_error& error) {
    throw ConfigError(source_name + ":" + std::to_string(error.source().begin.line) +
                      ": syntax error: " + std::string(error.description()));
  }
  KioskConfig config;     // filled on a copy: a bad file changes nothing
  std::string where_max;  // for the cross-key checks below
  std::string where_default;
  for (const auto& [table_key, table_node] : root) {
    const std::string table_name(table_key.str());
    const auto* table = table_node.as_table();
    if (table == nullptr) {
      throw ConfigError(Where(source_name, table_node.source(), table_name) +
                        "unknown top-level key (expected a [table])");
    }
    for (const auto& [key, node] : *table) {
      const std::string dotted = table_name + "." + std::string(key.str());
      const std::string where = Where(source_name, node.source(), dotted);
      const KeySpec* spec = nullptr;
      for (const auto& candidate : Schema()) {
        if (table_name == candidate.table && key.str() == candidate.key) spec = &candidate;
      }
      if (spec == nullptr) throw ConfigError(where + "unknown key");
      spec->apply(node, config, where);
      if (dotted == "gains.ambient_max_db" ||
          (where_max.empty() && dotted == "gains.ambient_min_db"))
        where_max = where;
      if (dotted == "session.default_texture") where_default = where;
    }
  }
  // The texture shown with no token: a shipped one (shown by its token's texture when a staff
  // texture took that token) or one a token shows, a staff texture too.
  {
    const std::vector<std::string> shipped = {"bubble_wrap", "broken_glass", "wooden_board",
                                              "cracked_ground"};
    const auto& tokens = config.token_textures;
    if (std::find(shipped.begin(), shipped.end(), config.default_texture) == shipped.end() &&
        std::find(tokens.begin(), tokens.end(), config.default_texture) == tokens.end()) {
      std::string listed;
      for (const auto& name : shipped) listed += name + ", ";
      throw ConfigError(where_default + "\"" + config.default_texture +
                        "\" is no texture the kiosk shows (" + listed +
                        "or one a [textures] token_N names)");
    }
  }
  if (config.ambient_min_db > config.ambient_max_db) {
    std::ostringstream message;
    message << where_max << "gains.ambient_min_db (" << config.ambient_min_db
            << ") must not exceed gains.ambient_max_db (" << config.ambient_max_db << ")";
    throw ConfigError(message.str());
  }
  return config;
}

namespace {

std::string TooLarge(const std::string& path, const std::string& bytes) {
  return path + ": too large for a configuration file (" + bytes + " bytes; the limit is " +
         std::to_string(kMaxConfigFileBytes / 1024) + " KiB)";
}

// A directory (or a device, a FIFO) opens and reads as an empty, valid file through ifstream; it
// would then replace the last good copy with 0 bytes. Only a regular file is a configuration.
// One over kMaxConfigFileBytes is refused by its size before any of it is read, and the read
// itself stops there (a file still growing).
std::string ReadConfigText(const std::string& path) {
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (std::filesystem::is_directory(status)) {
    throw ConfigError(path + ": is a directory, not a configuration file");
  }
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    throw ConfigError(path + ": not a regular file");
  }
  if (const auto size = std::filesystem::file_size(path, error);
      !error && size > kMaxConfigFileBytes) {
    throw ConfigError(TooLarge(path, std::to_string(size)));
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) throw ConfigError(path + ": cannot open configuration file");
  std::string text;
  char chunk[16 * 1024];
  while (file.read(chunk, sizeof chunk) || file.gcount() > 0) {
    text.append(chunk, static_cast<std::size_t>(file.gcount()));
    if (text.size() > kMaxConfigFileBytes) {
      throw ConfigError(TooLarge(path, "over " + std::to_string(kMaxConfigFileBytes)));
    }
  }
  if (file.bad()) throw ConfigError(path + ": cannot read configuration file");
  return text;
}

}  // namespace

KioskConfig LoadKioskConfig(const std::string& path) {
  return ParseKioskConfig(ReadConfigText(path), path);
}

}  // namespace sas::kiosk

namespace sas::kiosk {

ConfigLoadResult LoadKioskConfigWithFallback(const std::string& path,
                                             const std::string& last_good_path) {
  ConfigLoadResult result;
  std::string text;
  if (!last_good_path.empty()) RemoveStaleTemporaries(last_good_path);  // a kill mid-copy
  try {
    text = ReadConfigText(path);
    result.config = ParseKioskConfig(text, path);
    result.source = ConfigLoadResult::Source::kFile;
  } catch (const ConfigError& error) {
    result.problem = error.what();
  }
  if (result.source == ConfigLoadResult::Source::kFile) {
    if (!last_good_path.empty()) {
      std::string ignored;  // failing to keep a backup must not stop the kiosk
      AtomicWriteFile(last_good_path, text, &ignored);
    }
    return result;
  }
  if (!last_good_path.empty()) {
    try {
      result.config = LoadKioskConfig(last_good_path);
      result.source = ConfigLoadResult::Source::kLastGood;
      result.problem += " (using the last good configuration)";
      return result;
    } catch (const ConfigError&) {
      // fall through to the defaults
    }
  }
  result.config = KioskConfig{};
  result.source = ConfigLoadResult::Source::kDefaults;
  result.problem += " (using the built-in defaults)";
  return result;
}

}  // namespace sas::kiosk
