#pragma once
// What staff set on the staff panel and the kiosk must keep across a restart: the volume and the
// vibration strength (steps of kStaffStepDb on top of the configuration's gains) and the
// low-vibration mode. Kept in the state folder (`staff.toml`), never in the staff's own
// configuration file: the kiosk does not rewrite what a person wrote, and runs without root.
//  - every save is one AtomicWriteFile (the old file or the new one, never a mix);
//  - a damaged file (bad TOML, an unknown key, a wrong type, a value out of range) is renamed aside
//    with a timestamp (`staff.toml.damaged-YYYYMMDD-HHMMSS`) before anything is written, the kiosk
//    starts with the defaults, and one journal line says what was wrong and where the file went;
//  - when it cannot be moved aside it is left as it is and never overwritten this run.

#include <string>

namespace sas::kiosk {

inline constexpr double kStaffStepDb = 3.0;
inline constexpr double kStaffMinDb = -24.0;  // quieter than this is off for a visitor
inline constexpr double kStaffMaxDb = 6.0;    // the safety stage's ceilings still hold above 0

struct StaffSettings {
  double volume_db = 0.0;     // speaker: cues, textures and test signals
  double vibration_db = 0.0;  // transducer
  bool low_vibration = false;

  bool operator==(const StaffSettings&) const = default;
};

// `value` moved by `steps` steps of kStaffStepDb, kept within [kStaffMinDb, kStaffMaxDb].
double StepStaffDb(double value_db, int steps);

// `key = value` lines (valid TOML) with a comment saying who writes the file.
std::string FormatStaffSettings(const StaffSettings& settings);
// Throws std::runtime_error ("<source>:<line>: <key>: <what>") on any problem.
StaffSettings ParseStaffSettings(const std::string& text, const std::string& source_name);

struct StaffSettingsLoad {
  StaffSettings settings;  // the defaults unless the file was whole
  std::string report;      // empty when the file was whole or absent; else one journal line
  bool may_save = true;    // false: a damaged file could not be moved aside
};
// The kiosk's start-up load (see the top of this file). Never throws.
StaffSettingsLoad LoadStaffSettings(const std::string& path);

// Writes `path` atomically; false and the reason when it could not.
bool SaveStaffSettings(const std::string& path, const StaffSettings& settings, std::string* error);

}  // namespace sas::kiosk
