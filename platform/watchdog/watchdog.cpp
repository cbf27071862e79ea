// Watchdog supervisor (see watchdog.h).
#include "platform/watchdog/watchdog.h"

#include <cstdio>

#include "platform/log/log.h"

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

std::string WatchdogSupervisor::Describe(std::int64_t now_ns) const {
  std::string out;
  for (const auto& w : watched_) {
    const std::int64_t beat = w.heartbeat_ns();
    if (beat == kExempt || (beat != 0 && now_ns - beat <= max_age_ns_)) continue;
    char age[48];
    if (beat == 0) {
      std::snprintf(age, sizeof age, "never");
    } else {
      std::snprintf(age, sizeof age, "%.1f s", static_cast<double>(now_ns - beat) * 1e-9);
    }
    out += (out.empty() ? "" : ", ") + w.name + " (" + age + ")";
  }
  return out;
}

bool WatchdogSupervisor::Tick(std::int64_t now_ns) {
  const std::string stalled = Stalled(now_ns);
  if (stalled != last_stalled_) {
    notifier_.Status(stalled.empty() ? "running" : "stalled: " + stalled);
    if (log_ != nullptr && !stalled.empty()) {
      log_->Warn("watchdog", "no ping to systemd while these threads show no sign of life: " +
                                 Describe(now_ns));
    } else if (log_ != nullptr && last_stalled_ != "\x01") {
      log_->Info("watchdog", "every thread alive again: pinging systemd");
    }
    last_stalled_ = stalled;
  }
  if (!stalled.empty()) return false;
  notifier_.Ping();
  return true;
}

}  // namespace sas::platform
