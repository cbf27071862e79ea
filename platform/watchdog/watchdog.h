#pragma once
// The kiosk's liveness contract with systemd (Type=notify, WatchdogSec=): READY=1 once the kiosk
// is up, STATUS= lines for `systemctl status`, and WATCHDOG=1 from the control loop only when
// every watched thread has shown a recent heartbeat (the audio callback, the input threads), so a
// hung audio or input thread gets the kiosk restarted instead of a frozen exhibit. A thread that
// is legitimately not running (audio device lost, running silent) is exempt: its heartbeat
// function returns kExempt. All of this is a no-op without NOTIFY_SOCKET.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "platform/watchdog/systemd_notifier.h"

namespace sas::platform {

class Logger;

class WatchdogSupervisor {
 public:
  static constexpr std::int64_t kExempt = -1;

  // `max_age_ns`: heartbeats older than this block the ping. Typically a quarter of WatchdogSec.
  explicit WatchdogSupervisor(std::int64_t max_age_ns, SystemdNotifier notifier = {})
      : max_age_ns_(max_age_ns), notifier_(notifier) {}

  // `heartbeat_ns` returns the CLOCK_MONOTONIC time of the thread's last sign of life, or kExempt.
  void Watch(std::string name, std::function<std::int64_t()> heartbeat_ns);

  // A withheld ping is also a journal warning naming the threads and how long they have been
  // silent (systemd's own line says only "Watchdog timeout"), and their return an info line.
  void ReportTo(Logger* log) { log_ = log; }

  void Ready(const std::string& status);
  // Control loop: pings when every heartbeat is recent; otherwise sends one STATUS= naming the
  // stalled threads (once per change) and no ping. Returns whether it pinged.
  bool Tick(std::int64_t now_ns);
  // The names of threads whose heartbeat is stale at `now_ns` ("" when all are fine).
  std::string Stalled(std::int64_t now_ns) const;

 private:
  struct Watched {
    std::string name;
    std::function<std::int64_t()> heartbeat_ns;
  };
  std::int64_t max_age_ns_;
  SystemdNotifier notifier_;
  std::vector<Watched> watched_;
  std::string Describe(std::int64_t now_ns) const;  // "audio (3.1 s), pen (2.2 s)"

  std::string last_stalled_ = "\x01";  // "unknown": the first Tick always sends a STATUS
  Logger* log_ = nullptr;
};

}  // namespace sas::platform
