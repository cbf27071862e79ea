#pragma once
// systemd service notification (sd_notify): READY=1, WATCHDOG=1, STATUS=. A no-op when the
// process was not started by systemd (no NOTIFY_SOCKET), so it is always safe to call.

#include <cstdint>
#include <string>

#include "platform/device_finding.h"

namespace sas::platform {

class SystemdNotifier {
 public:
  // True when NOTIFY_SOCKET is set: messages go somewhere.
  bool UnderSystemd() const;
  // The watchdog period systemd expects pings within, or 0 when the watchdog is off.
  std::uint64_t WatchdogIntervalUs() const;

  bool Ready() const { return Notify("READY=1"); }
  bool Ping() const { return Notify("WATCHDOG=1"); }
  bool Status(const std::string& text) const { return Notify("STATUS=" + text); }
  bool Notify(const std::string& message) const;
};

void ReportSystemd(DeviceReport& report);

}  // namespace sas::platform
