// Usage counters file (see counters_file.h).
#include "kiosk/counters_file.h"

#include <charconv>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "kiosk/atomic_file.h"

namespace sas::kiosk {
namespace {

constexpr const char* kStrokePrefix = "strokes.";

std::string Trim(const std::string& text) {
  const auto begin = text.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  const auto end = text.find_last_not_of(" \t\r");
  return text.substr(begin, end - begin + 1);
}

}  // namespace

std::string FormatCounters(const UsageCounters& counters,
                           const std::vector<std::string>& texture_names) {
  std::ostringstream out;
  out << "# Sketch-a-Scratch anonymous usage counters (no visitor data).\n";
  out << "sessions = " << counters.sessions << "\n";
  out << "recordings = " << counters.recordings << "\n";
  out << "failed_recordings = " << counters.failed_recordings << "\n";
  out << "voice_strokes = " << counters.voice_strokes << "\n";
  for (std::size_t i = 0; i < texture_names.size() && i < counters.strokes_per_texture.size();
       ++i) {
    out << kStrokePrefix << texture_names[i] << " = " << counters.strokes_per_texture[i] << "\n";
  }
  return out.str();
}

UsageCounters ParseCounters(const std::string& text, const std::vector<std::string>& texture_names,
                            const std::string& source_name) {
  UsageCounters counters;
  counters.strokes_per_texture.assign(texture_names.size(), 0);
  std::istringstream in(text);
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    line = Trim(line);
    if (line.empty() || line[0] == '#') continue;
    const auto where = source_name + ":" + std::to_string(line_number) + ": ";
    const auto equals = line.find('=');
    if (equals == std::string::npos) throw std::runtime_error(where + "expected key = value");
    const std::string key = Trim(line.substr(0, equals));
    const std::string value_text = Trim(line.substr(equals + 1));
    std::uint64_t value = 0;
    const auto [end, ec] =
        std::from_chars(value_text.data(), value_text.data() + value_text.size(), value);
    if (ec != std::errc() || end != value_text.data() + value_text.size()) {
      throw std::runtime_error(where + key + ": not a whole number");
    }
    if (key == "sessions") {
      counters.sessions = value;
    } else if (key == "recordings") {
      counters.recordings = value;
    } else if (key == "failed_recordings") {
      counters.failed_recordings = value;
    } else if (key == "voice_strokes") {
      counters.voice_strokes = value;
    } else if (key.rfind(kStrokePrefix, 0) == 0) {
      const std::string name = key.substr(std::string(kStrokePrefix).size());
      for (std::size_t i = 0; i < texture_names.size(); ++i) {
        if (texture_names[i] == name) counters.strokes_per_texture[i] = value;
      }
    } else {
      throw std::runtime_error(where + key + ": unknown key");
    }
  }
  return counters;
}

bool SaveCounters(const std::string& path, const UsageCounters& counters,
                  const std::vector<std::string>& texture_names, std::string* error) {
  return AtomicWriteFile(path, FormatCounters(counters, texture_names), error);
}

bool LoadCounters(const std::string& path, const std::vector<std::string>& texture_names,
                  UsageCounters* counters, std::string* error) {
  *counters = UsageCounters{};
  counters->strokes_per_texture.assign(texture_names.size(), 0);
  std::ifstream file(path, std::ios::binary);
  if (!file) return true;  // first start: nothing counted yet
  std::ostringstream text;
  text << file.rdbuf();
  try {
    *counters = ParseCounters(text.str(), texture_names, path);
  } catch (const std::exception& e) {
    if (error) *error = e.what();
    return false;
  }
  return true;
}

}  // namespace sas::kiosk
