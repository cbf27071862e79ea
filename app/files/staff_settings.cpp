// The staff's persisted panel settings (see staff_settings.h).
#include "files/staff_settings.h"

#include <sys/stat.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "files/atomic_file.h"

namespace sas::kiosk {
namespace {

std::string Number(double value) {
  std::ostringstream out;
  out << value;
  const std::string text = out.str();
  // TOML wants a float to look like one ("3.0", not "3").
  return text.find_first_of(".e") == std::string::npos ? text + ".0" : text;
}

}  // namespace

double StepStaffDb(double value_db, int steps) {
  return std::clamp(value_db + steps * kStaffStepDb, kStaffMinDb, kStaffMaxDb);
}

std::string FormatStaffSettings(const StaffSettings& settings) {
  return "# Written by the kiosk's staff panel (volume and vibration buttons); kept across "
         "restarts.\n"
         "volume_db = " +
         Number(settings.volume_db) + "\nvibration_db = " + Number(settings.vibration_db) +
         "\nlow_vibration = " + (settings.low_vibration ? "true" : "false") + "\n";
}

StaffSettings ParseStaffSettings(const std::string& text, const std::string& source_name) {
  toml::table root;
  try {
    root = toml::parse(text, source_name);
  } catch (const toml::parse_error& error) {
    throw std::runtime_error(source_name + ":" + std::to_string(error.source().begin.line) +
                             ": syntax error: " + std::string(error.description()));
  }
  StaffSettings settings;
  for (const auto& [key, node] : root) {
    const std::string where = source_name + ":" + std::to_string(node.source().begin.line) + ": " +
                              std::string(key.str()) + ": ";
    if (key.str() == "volume_db" || key.str() == "vibration_db") {
      if (!node.is_number()) throw std::runtime_error(where + "expected a number");
      const double value = *node.value<double>();
      if (!std::isfinite(value) || value < kStaffMinDb || value > kStaffMaxDb) {
        throw std::runtime_error(where + "out of range [" + Number(kStaffMinDb) + ", " +
                                 Number(kStaffMaxDb) + "]");
      }
      (key.str() == "volume_db" ? settings.volume_db : settings.vibration_db) = value;
    } else if (key.str() == "low_vibration") {
      if (!node.is_boolean()) throw std::runtime_error(where + "expected true or false");
      settings.low_vibration = *node.value<bool>();
    } else {
      throw std::runtime_error(where + "unknown key");
    }
  }
  return settings;
}

StaffSettingsLoad LoadStaffSettings(const std::string& path) {
  StaffSettingsLoad load;
  RemoveStaleTemporaries(path);  // left by a kill in the middle of a save
  std::error_code error;
  if (!std::filesystem::exists(path, error)) return load;  // never saved yet: the defaults
  std::string problem;
  if (!std::filesystem::is_regular_file(path, error)) {
    problem = path + ": not a regular file";
  } else {
    std::ifstream file(path, std::ios::binary);
    std::ostringstream text;
    text << file.rdbuf();
    if (!file) {
      problem = path + ": cannot read it";
    } else if (text.str().empty()) {
      problem = path + ": empty (the kiosk never writes an empty file)";
    } else {
      try {
        load.settings = ParseStaffSettings(text.str(), path);
        return load;
      } catch (const std::runtime_error& bad) {
        problem = bad.what();
      }
    }
  }
  load.settings = StaffSettings{};
  // Kept, never overwritten: staff (or whoever damaged it) may want to see what it held.
  const std::string aside = AsidePath(path);
  if (std::rename(path.c_str(), aside.c_str()) == 0) {
    problem += "; file kept as " + aside;
  } else {
    problem += "; could not be moved aside (" + std::string(std::strerror(errno)) +
               "), so it is left in place and panel changes are not saved this run";
    load.may_save = false;
  }
  load.report = problem + "; using the defaults (volume 0 dB, vibration 0 dB, low vibration off)";
  return load;
}

bool SaveStaffSettings(const std::string& path, const StaffSettings& settings, std::string* error) {
  return AtomicWriteFile(path, FormatStaffSettings(settings), error);
}

}  // namespace sas::kiosk
