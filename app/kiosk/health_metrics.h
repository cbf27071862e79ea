#pragma once
// The box's health for a fleet: Prometheus text-format metrics (exposition format 0.0.4) in one
// small file that node-exporter's textfile collector publishes. The kiosk itself opens no socket;
// a Prometheus server scrapes node-exporter on each box and the alert rules shipped with the
// package (sketch-a-scratch.rules.yml) watch the fleet.
//
// Snapshot (filled on the control thread from the engine, the status board and the audio side's
// published stats) -> FormatHealthMetrics (names with the sketch_a_scratch_ prefix, units in the
// names, counters ending in _total, enum-like states as one 0/1 gauge per state) ->
// HealthMetricsWriter (AtomicWriteFile: a temporary file beside the target, fsync, rename, so the
// collector reads either the last whole file or the new one, never half of one).
//
// Nothing about a visitor is in it: counts only, as the staff panel shows them.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "files/counters_file.h"
#include "platform/device_status.h"
#include "platform/log/log.h"

namespace sas::kiosk {

struct HealthSnapshot {
  std::string version;
  std::string box_name;
  double start_time_s = 0.0;  // Unix time the process started
  double uptime_s = 0.0;
  // Every device on the status board (audio_out, audio_in, pen, switches, storage, ...).
  std::vector<platform::DeviceStatus> devices;
  std::uint64_t xruns = 0;  // since the process started (a counter reset is a restart)
  std::optional<double> audio_callback_age_s;  // empty: no callback yet
  // Persisted usage counts, the counters file's fields (texture_keys order for the strokes).
  UsageCounters counters;
  std::vector<std::string> texture_keys;
  std::optional<double> speaker_leq_last_hour_dbfs;
  std::string texture_shown;    // a texture key, or "voice"
  bool config_accepted = true;  // false: the file was rejected (last good copy or defaults used)
};

// The text exposition format; every line ends in a newline.
std::string FormatHealthMetrics(const HealthSnapshot& snapshot);

// The box's name when the configuration gives none: the host name.
std::string DefaultBoxName();

// Control-side writer of the metrics file. Due() says when the next file is wanted: every
// `interval_s`, and at once (at most one write a second) when something staff act on changed
// (a device's state, the configuration's verdict), so an unplugged pen shows up in seconds.
class HealthMetricsWriter {
 public:
  HealthMetricsWriter(std::string path, double interval_s, platform::Logger& log);

  bool enabled() const { return !path_.empty(); }
  const std::string& path() const { return path_; }
  // `state_key`: a short text of the states that call for an early write.
  bool Due(std::int64_t now_ns, const std::string& state_key) const;
  // Writes the file atomically. A failure leaves the last file (or none) in place and no
  // temporary; the first failure is logged once (and the recovery), not every few seconds.
  bool Write(std::int64_t now_ns, const std::string& state_key, const std::string& text);

 private:
  std::string path_;
  std::int64_t interval_ns_;
  platform::Logger* log_;
  std::int64_t last_write_ns_ = 0;
  bool written_ = false;
  std::string last_state_key_;
  bool failing_ = false;
};

}  // namespace sas::kiosk
