#pragma once
// The kiosk's one configuration file (/etc/sketch-a-scratch/kiosk.toml on the box). Every key is
// optional and has a built-in default; a key we do not know, a wrong type or a value out of range
// is an error naming the file, line and key, and nothing of a bad file is applied.

#include <stdexcept>
#include <string>

namespace sas::kiosk {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct KioskConfig {
  // [audio]
  std::string output_device = "default";  // PortAudio device name (ALSA name on the box)
  std::string input_device = "default";
  int sample_rate_hz = 48000;
  int buffer_frames = 128;
  // [gains] — deliberately high for a loud room; the output limiters keep samples in [-1, 1].
  double sound_gain_db = 12.0;
  double haptic_gain_db = 6.0;
  // [session]
  double idle_timeout_s = 60.0;
  std::string default_texture = "wooden_board";
};

// Parses `path`. Throws ConfigError ("<file>:<line>: <key>: <what>") on any problem.
KioskConfig LoadKioskConfig(const std::string& path);
// Same, from text already in memory; `source_name` is used in messages.
KioskConfig ParseKioskConfig(const std::string& text, const std::string& source_name);

}  // namespace sas::kiosk

namespace sas::kiosk {

// The result of loading the configuration at start: the kiosk always gets a usable one.
struct ConfigLoadResult {
  KioskConfig config;
  enum class Source { kFile, kLastGood, kDefaults } source = Source::kDefaults;
  std::string problem;  // empty when the file loaded; else the error, for journal + staff panel
};

// Loads `path`. When it is valid, a copy is kept at `last_good_path` (atomically). When it is
// missing or bad, the last good copy is used, else the built-in defaults; `problem` says which
// and why. Never throws.
ConfigLoadResult LoadKioskConfigWithFallback(const std::string& path,
                                             const std::string& last_good_path);

}  // namespace sas::kiosk
