#pragma once
// Pings systemd's watchdog on the control loop's behalf while it is inside a step that can take
// long on a slow machine without being hung. Drawing one frame with a software renderer under
// emulation on a busy host took up to 11 s, past the unit's WatchdogSec of 10 s, and systemd
// killed a working kiosk for it. While the loop is inside such a step (Begin .. End) a helper
// thread pings every `interval_ns`, but only for `max_busy_ns` from the step's start and only if
// the loop's own last tick pinged (every watched thread alive then): a step that never ends (a
// hung graphics driver) still stops the pings, and systemd restarts the kiosk.

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>

namespace sas::platform {

class BusyKeeper {
 public:
  BusyKeeper(std::function<void()> ping, std::int64_t interval_ns, std::int64_t max_busy_ns);
  ~BusyKeeper();
  BusyKeeper(const BusyKeeper&) = delete;
  BusyKeeper& operator=(const BusyKeeper&) = delete;

  // The loop enters a long step at `now_ns` (CLOCK_MONOTONIC); `alive`: its last tick pinged.
  void Begin(std::int64_t now_ns, bool alive);
  void End();
  // Pings sent on the loop's behalf so far.
  std::uint64_t pings() const;

  // The rule: inside a step begun by a live loop at `begin_ns`, ping at `now_ns` while the step
  // is younger than `max_busy_ns`.
  static bool ShouldPing(bool busy, bool alive, std::int64_t begin_ns, std::int64_t now_ns,
                         std::int64_t max_busy_ns);

 private:
  void Run();

  std::function<void()> ping_;
  std::int64_t interval_ns_;
  std::int64_t max_busy_ns_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool busy_ = false;
  bool alive_ = false;
  bool stop_ = false;
  std::int64_t begin_ns_ = 0;
  std::uint64_t pings_ = 0;
  std::thread thread_;
};

}  // namespace sas::platform
