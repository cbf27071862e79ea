// Prometheus text-format health metrics and their atomic writer (see health_metrics.h).
#include "kiosk/health_metrics.h"

#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "files/atomic_file.h"

namespace sas::kiosk {
namespace {

constexpr std::int64_t kNsPerS = 1'000'000'000;
// An early write (a state changed) comes at most this often: a flapping cable must not turn the
// writer into a loop of rewrites.
constexpr std::int64_t kMinGapNs = kNsPerS;

// Label values may hold any UTF-8; the format escapes backslash, double quote and newline.
std::string Escape(const std::string& value) {
  std::string out;
  out.reserve(value.size());
  for (const char c : value) {
    if (c == '\\') {
      out += "\\\\";
    } else if (c == '"') {
      out += "\\\"";
    } else if (c == '\n') {
      out += "\\n";
    } else {
      out += c;
    }
  }
  return out;
}

// Shortest text that reads back as the same double; the format's own spellings for the rest.
std::string Number(double value) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0 ? "+Inf" : "-Inf";
  char text[32];
  // Whole numbers (Unix times, counts) as digits: 1700000000, not 1.7e+09.
  if (value == std::trunc(value) && std::fabs(value) < 9007199254740992.0) {
    std::snprintf(text, sizeof text, "%.0f", value);
    return text;
  }
  std::snprintf(text, sizeof text, "%.17g", value);
  for (int digits = 1; digits < 17; ++digits) {
    char shorter[32];
    std::snprintf(shorter, sizeof shorter, "%.*g", digits, value);
    if (std::strtod(shorter, nullptr) == value) return shorter;
  }
  return text;
}

class Exposition {
 public:
  void Family(const char* name, const char* type, const char* help) {
    out_ << "# HELP " << name << ' ' << help << "\n# TYPE " << name << ' ' << type << '\n';
  }
  void Sample(const char* name, const std::string& labels, const std::string& value) {
    out_ << name;
    if (!labels.empty()) out_ << '{' << labels << '}';
    out_ << ' ' << value << '\n';
  }
  std::string Text() const { return out_.str(); }

 private:
  std::ostringstream out_;
};

std::string Label(const char* name, const std::string& value) {
  return std::string(name) + "=\"" + Escape(value) + "\"";
}

}  // namespace

std::string FormatHealthMetrics(const HealthSnapshot& s) {
  Exposition e;
  e.Family("sketch_a_scratch_info", "gauge", "The kiosk's version and the box's name (always 1).");
  e.Sample("sketch_a_scratch_info", Label("version", s.version) + "," + Label("box", s.box_name),
           "1");
  e.Family("sketch_a_scratch_start_time_seconds", "gauge", "Unix time the kiosk process started.");
  e.Sample("sketch_a_scratch_start_time_seconds", "", Number(s.start_time_s));
  e.Family("sketch_a_scratch_uptime_seconds", "gauge", "Seconds since the kiosk process started.");
  e.Sample("sketch_a_scratch_uptime_seconds", "", Number(s.uptime_s));

  // One 0/1 gauge per device and state, so an alert can ask for a state directly and a device
  // keeps its series whatever state it is in.
  static constexpr std::array kStates = {
      platform::DeviceState::kOk, platform::DeviceState::kMissing, platform::DeviceState::kLost,
      platform::DeviceState::kReconnecting, platform::DeviceState::kDisabled};
  e.Family("sketch_a_scratch_device_state", "gauge",
           "1 for each device's current state (ok, missing, lost, reconnecting, disabled), 0 for "
           "the others.");
  for (const auto& device : s.devices) {
    for (const auto state : kStates) {
      e.Sample(
          "sketch_a_scratch_device_state",
          Label("device", device.device) + "," + Label("state", platform::DeviceStateName(state)),
          device.state == state ? "1" : "0");
    }
  }

  e.Family("sketch_a_scratch_audio_xruns_total", "counter",
           "Audio under- and overruns reported by the output device since the kiosk started.");
  e.Sample("sketch_a_scratch_audio_xruns_total", "", std::to_string(s.xruns));
  e.Family("sketch_a_scratch_audio_callback_age_seconds", "gauge",
           "Seconds since the last audio callback (NaN before the first).");
  e.Sample("sketch_a_scratch_audio_callback_age_seconds", "",
           s.audio_callback_age_s ? Number(*s.audio_callback_age_s) : "NaN");

  e.Family("sketch_a_scratch_visits_total", "counter",
           "Visits (a first touch after the attract screen), kept across restarts.");
  e.Sample("sketch_a_scratch_visits_total", "", std::to_string(s.counters.sessions));
  e.Family("sketch_a_scratch_strokes_total", "counter",
           "Pen strokes per texture (voice: the visitor's recorded voice), kept across restarts.");
  for (std::size_t i = 0; i < s.texture_keys.size(); ++i) {
    const std::uint64_t count =
        i < s.counters.strokes_per_texture.size() ? s.counters.strokes_per_texture[i] : 0;
    e.Sample("sketch_a_scratch_strokes_total", Label("texture", s.texture_keys[i]),
             std::to_string(count));
  }
  e.Sample("sketch_a_scratch_strokes_total", Label("texture", "voice"),
           std::to_string(s.counters.voice_strokes));
  e.Family("sketch_a_scratch_recordings_total", "counter",
           "Voice recordings by result (ok: became a surface; failed: too quiet, clipped, no "
           "microphone), kept across restarts.");
  e.Sample("sketch_a_scratch_recordings_total", Label("result", "ok"),
           std::to_string(s.counters.recordings));
  e.Sample("sketch_a_scratch_recordings_total", Label("result", "failed"),
           std::to_string(s.counters.failed_recordings));

  e.Family("sketch_a_scratch_speaker_leq_last_hour_dbfs", "gauge",
           "Equivalent continuous level of the speaker channel over the last hour, dB re full "
           "scale (NaN before any audio).");
  e.Sample("sketch_a_scratch_speaker_leq_last_hour_dbfs", "",
           s.speaker_leq_last_hour_dbfs ? Number(*s.speaker_leq_last_hour_dbfs) : "NaN");

  e.Family("sketch_a_scratch_texture_shown", "gauge",
           "1 for the surface on the screen now, 0 for the others.");
  for (const auto& key : s.texture_keys) {
    e.Sample("sketch_a_scratch_texture_shown", Label("texture", key),
             s.texture_shown == key ? "1" : "0");
  }
  e.Sample("sketch_a_scratch_texture_shown", Label("texture", "voice"),
           s.texture_shown == "voice" ? "1" : "0");

  e.Family("sketch_a_scratch_config_accepted", "gauge",
           "1 when the configuration file was accepted, 0 when it was rejected (the last good "
           "copy or the defaults are in use).");
  e.Sample("sketch_a_scratch_config_accepted", "", s.config_accepted ? "1" : "0");
  return e.Text();
}

std::string DefaultBoxName() {
  char name[256] = {};
  if (gethostname(name, sizeof name - 1) != 0 || name[0] == '\0') return "sketch-a-scratch";
  return name;
}

HealthMetricsWriter::HealthMetricsWriter(std::string path, double interval_s, platform::Logger& log)
    : path_(std::move(path)),
      interval_ns_(static_cast<std::int64_t>(interval_s * static_cast<double>(kNsPerS))),
      log_(&log) {
  // A kill between creating and renaming a temporary leaves one beside the file.
  if (enabled()) RemoveStaleTemporaries(path_);
}

bool HealthMetricsWriter::Due(std::int64_t now_ns, const std::string& state_key) const {
  if (!enabled()) return false;
  if (!written_) return true;
  const std::int64_t since = now_ns - last_write_ns_;
  if (since >= interval_ns_) return true;
  return state_key != last_state_key_ && since >= kMinGapNs;
}

bool HealthMetricsWriter::Write(std::int64_t now_ns, const std::string& state_key,
                                const std::string& text) {
  if (!enabled()) return false;
  // A failed write is tried again a full interval later, not at every pass.
  written_ = true;
  last_write_ns_ = now_ns;
  last_state_key_ = state_key;
  std::string error;
  // Not synced to disk: the file is rewritten within a few seconds of every start, and the
  // control loop that writes it also draws the picture.
  if (!AtomicWriteFile(path_, text, &error, Durability::kReadersOnly)) {
    if (!failing_) log_->Warn("metrics", "not written: " + error + "; retrying");
    failing_ = true;
    return false;
  }
  if (failing_) log_->Info("metrics", "written again to " + path_);
  failing_ = false;
  return true;
}

}  // namespace sas::kiosk
