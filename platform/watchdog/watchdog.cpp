// Watchdog supervisor (see watchdog.h).
#include "platform/watchdog/watchdog.h"

namespace sas::platform {

void WatchdogSupervisor::Watch(std::string name, std::function<std::int64_t()> heartbeat_ns) {
  watched_.push_back({std::move(name), std::move(heartbeat_ns)});
}

void WatchdogSupervisor::Ready(const std::string& status) {
  notifier_.Notify("READY=1\nSTATUS=" + status);
}

std::string WatchdogSupervisor::Stalled(std::int64_t now_ns) const {
  std::string stalled;
  for (const auto& w : watched_) {
    const std::int64_t beat = w.heartbeat_ns();
    if (beat == kExempt) continue;
    if (beat == 0 || now_ns - beat > max_age_ns_) stalled += (stalled.empty() ? "" : ", ") + w.name;
  }
  return stalled;
}

bool WatchdogSupervisor::Tick(std::int64_t now_ns) {
  const std::string stalled = Stalled(now_ns);
  if (stalled != last_stalled_) {
    notifier_.Status(stalled.empty() ? "running" : "stalled: " + stalled);
    last_stalled_ = stalled;
  }
  if (!stalled.empty()) return false;
  notifier_.Ping();
  return true;
}

}  // namespace sas::platform
