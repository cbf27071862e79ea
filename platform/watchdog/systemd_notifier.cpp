// sd_notify wrapper (see systemd_notifier.h).
#include "platform/watchdog/systemd_notifier.h"

#include <systemd/sd-daemon.h>

#include <cstdlib>

namespace sas::platform {

bool SystemdNotifier::UnderSystemd() const {
  return std::getenv("NOTIFY_SOCKET") != nullptr;
}

std::uint64_t SystemdNotifier::WatchdogIntervalUs() const {
  uint64_t interval_us = 0;
  return sd_watchdog_enabled(0, &interval_us) > 0 ? interval_us : 0;
}

bool SystemdNotifier::Notify(const std::string& message) const {
  return sd_notify(0, message.c_str()) > 0;
}

void ReportSystemd(DeviceReport& report) {
  SystemdNotifier notifier;
  if (!notifier.UnderSystemd()) {
    report.push_back({"systemd", false, "not started by systemd (no watchdog)"});
    return;
  }
  const auto interval_us = notifier.WatchdogIntervalUs();
  report.push_back({"systemd", true,
                    interval_us ? "watchdog every " + std::to_string(interval_us / 1000) + " ms"
                                : std::string("notify socket, watchdog off")});
}

}  // namespace sas::platform
