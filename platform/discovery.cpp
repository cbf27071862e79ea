// Aggregates the per-device reports (see discovery.h).
#include "platform/discovery.h"

#include "platform/audio/audio_devices.h"
#include "platform/gpio/gpio_chips.h"
#include "platform/hid/hid_devices.h"
#include "platform/pen/tablet_devices.h"
#include "platform/watchdog/systemd_notifier.h"

namespace sas::platform {

DeviceReport DiscoverDevices() {
  DeviceReport report;
  ReportAudioDevices(report);
  ReportGpioChips(report);
  ReportHidAdapters(report);
  ReportTablets(report);
  ReportSystemd(report);
  return report;
}

}  // namespace sas::platform
