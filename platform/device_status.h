#pragma once
// What the staff panel shows about each device: state, one human sentence, and counters (xruns,
// reconnects, events). Written by the platform supervisors on the control thread (and by device
// threads on state changes), read by the staff panel: a mutex-guarded table, never touched from
// the audio callback. Every state change is also logged once, so the journal and the panel agree:
// a state change = exactly one log line.

#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "platform/log/log.h"

namespace sas::platform {

enum class DeviceState {
  kOk,            // working
  kMissing,       // absent at start; a fallback is in use
  kLost,          // was working, disappeared
  kReconnecting,  // lost, retrying with back-off
  kDisabled,      // not configured / not wanted
};

const char* DeviceStateName(DeviceState state);

struct DeviceStatus {
  std::string device;  // "audio_out", "audio_in", "switches", "pen", "watchdog"
  DeviceState state = DeviceState::kMissing;
  std::string message;           // one sentence for staff
  std::string backend;           // "portaudio", "gpio", "mcp2221", "keyboard", "libinput", ...
  std::uint64_t reconnects = 0;  // successful reopen after loss
  std::uint64_t failures = 0;    // losses + failed opens
  std::uint64_t events = 0;      // backend specific (xruns for audio, events for inputs)
};

class DeviceStatusBoard {
 public:
  explicit DeviceStatusBoard(Logger& logger = DefaultLogger()) : logger_(&logger) {}

  // Sets state + message. Logs one line when the state, backend or message changed (warn for
  // missing/lost/reconnecting, info otherwise); repeated identical updates are silent.
  void Set(const std::string& device, DeviceState state, const std::string& message,
           const std::string& backend = {});
  void AddReconnect(const std::string& device);
  void AddFailure(const std::string& device);
  void SetEvents(const std::string& device, std::uint64_t events);

  DeviceStatus Get(const std::string& device) const;  // default (kMissing, "") when unknown
  std::vector<DeviceStatus> All() const;
  Logger& logger() const { return *logger_; }

 private:
  mutable std::mutex mutex_;
  std::map<std::string, DeviceStatus> table_;
  Logger* logger_;
};

}  // namespace sas::platform
