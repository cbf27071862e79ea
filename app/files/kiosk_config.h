#pragma once
// The kiosk's one configuration file (/etc/sketch-a-scratch/kiosk.toml on the box). Every key is
// optional and has a built-in default; a key we do not know, a wrong type or a value out of range
// is an error naming the file, line and key, and nothing of a bad file is applied.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

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
  double reopen_backoff_initial_s = 0.25;  // a lost device is retried after this, doubling...
  double reopen_backoff_max_s = 8.0;       // ...up to this
  double stall_timeout_s = 1.0;            // no audio callback for this long = device lost
  // [recording] — the visitor's voice, in RAM only.
  double record_max_duration_s = 5.0;
  double record_silence_rms_dbfs = -50.0;  // a quieter take counts as "nothing recorded"
  double record_clip_level = 0.999;        // |sample| at or above this is clipped
  // [switches] — the token switches and the record button.
  std::string switches_backend = "auto";  // auto | gpio | mcp2221 | keyboard
  int switches_debounce_ms = 30;
  bool switches_active_low = true;      // switch to ground against the pull-up
  std::string gpio_chip = "gpiochip0";  // name, path or label
  std::vector<std::string> gpio_lines = {"17", "27", "22", "23", "24"};  // tokens 1-4, record
  std::string mcp2221_path;  // hidraw path; empty = first 04d8:00dd adapter
  int mcp2221_poll_ms = 15;
  // [pen]
  std::string pen_device;  // substring of the tablet's name; empty = the first tablet
  std::string pen_seat = "seat0";
  // [gains] — deliberately high for a loud room; the output limiters keep samples in [-1, 1].
  double sound_gain_db = 12.0;
  double haptic_gain_db = 39.0;
  // Final safety stage (synth/safety_stage.h): true-peak ceilings of what reaches the devices.
  double sound_ceiling_db = -1.0;  // speaker ceiling, dBTP (<= 0)
  double haptic_ceiling_db = 0.0;  // transducer peak ceiling, dBFS (<= 0): the haptic limiter's top
  double low_vibration_db = 12.0;  // haptic attenuation while staff low-vibration mode is on, dB
  // Stroke leveller (synth/output_stage.h): a stroke's sound is held to this many LU above the
  // textures' calibrated level (output_gains.h); 0 turns it off.
  double stroke_cap_lu = 5.0;
  // Ambient-adaptive sound gain (ambient_gain.h): while idle, the microphone's room level moves an
  // extra sound gain between ambient_min_db and ambient_max_db, ambient_per_db dB per dB of room
  // level above ambient_quiet_dbfs, changing at most ambient_rate_db_per_s.
  bool ambient_adaptive = false;
  double ambient_min_db = 0.0;
  double ambient_max_db = 12.0;
  double ambient_per_db = 0.5;
  double ambient_quiet_dbfs = -60.0;
  double ambient_rate_db_per_s = 1.0;
  // [session]
  double idle_timeout_s = 60.0;
  std::string default_texture = "wooden_board";
  // Seconds the pen must rest still on a texture before its description is spoken (0: never).
  double describe_after_rest_s = 2.0;
  // [attract] — while nobody is at the box: the engine strokes the picture itself, gently, in
  // bursts (the paper's passive exploration), and shows and speaks the invitation in each visitor
  // language in turn, invitation_interval_s seconds of quiet after each (0: no spoken invitation,
  // the configured language only). At the default every language is heard within a minute.
  bool attract_passive_stroke = true;
  double invitation_interval_s = 1.0;
  // [language] — what the kiosk says and shows (textures/strings/<code>.toml): the configured
  // language, and the ones the visitor's language key (L) steps through (empty: no choice).
  std::string language = "en";
  std::vector<std::string> visitor_languages = {"en", "de", "fr", "it", "es"};
  // [staff] — the chord that opens the staff panel: modifiers (ctrl, alt, shift, super) and one
  // key name, held for chord_hold_s. At least two modifiers, so a visitor cannot type it by chance.
  std::string staff_chord = "ctrl+alt+s";
  double staff_chord_hold_s = 1.0;
  // The panel closes itself this long after the last staff action (chord or button), so one left
  // open does not hold off the idle reset.
  double staff_panel_timeout_s = 300.0;
  // [transducer] — the actuator on the stylus, as a mass on a spring (synth/transducer_eq.h): its
  // resonance and quality factor from the datasheet (Fs, Qms/Qts). The drive on ch 2 is then
  // compensated so that the acceleration at the pen follows the designed signal. 0 Hz: a flat,
  // broadband transducer, nothing compensated.
  double transducer_resonance_hz = 0.0;
  double transducer_q = 1.0;
  // [textures] token_1 .. token_4 — which texture each token shows: a folder name, looked up
  // first among the staff's own textures (<staff_dir>/textures/<name>/, `sketch-a-scratch texture
  // install` puts them there), then among the shipped ones. A staff texture that does not load is
  // refused with a warning and its token shows the shipped texture of its place.
  std::vector<std::string> token_textures = {"bubble_wrap", "broken_glass", "wooden_board",
                                             "cracked_ground"};
  // [paths] — where staff put their own files, outside the package's (an upgrade, a removal and a
  // reinstall keep them; a purge removes them with kiosk.toml): recorded cues in
  // <staff_dir>/cues/<language>/<cue key>.wav (kiosk/staff_cues.h), their own textures in
  // <staff_dir>/textures/<name>/. "": none are read.
  std::string staff_dir = "/etc/sketch-a-scratch";
  // [fleet] — health metrics for a fleet watched by Prometheus (kiosk/health_metrics.h): the
  // file node-exporter's textfile collector reads (a relative name is in the state folder, where
  // the package's link in the collector's folder points; "": none written), how often it is
  // rewritten, and the box's name in it ("": the host name).
  std::string metrics_file = "sketch_a_scratch.prom";
  double metrics_interval_s = 5.0;
  std::string box_name;
};

// The largest configuration file read. The shipped kiosk.toml is a few kB with every key and
// its comment; 1 MiB is hundreds of times that and still parses in a fraction of a second. A
// larger file is something else saved over it (a log, an image, a runaway script): refused before
// it is read, where a 100 MB one took 18 s to parse at start and was then copied whole to the
// last good one.
inline constexpr std::uintmax_t kMaxConfigFileBytes = 1024 * 1024;

// Parses `path`. Throws ConfigError ("<file>:<line>: <key>: <what>") on any problem, and for a
// file over kMaxConfigFileBytes ("<file>: too large for a configuration file (...)").
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
