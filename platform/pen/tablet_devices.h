#pragma once
// Pen tablet discovery through libinput's udev backend: devices with the tablet-tool capability
// (SDL2 2.26 gives no pen pressure or tilt, so the pen must come from libinput).

#include <string>
#include <vector>

#include "platform/device_finding.h"

namespace sas::platform {

struct TabletInfo {
  std::string name;
  std::string sysname;  // event node name, e.g. event5
};

std::vector<TabletInfo> ListTablets(std::string* error = nullptr);

void ReportTablets(DeviceReport& report);

}  // namespace sas::platform
