#pragma once
// One line of the hardware report: what kind of device, whether it is there, and the details a
// member of staff or an engineer needs to act on it.

#include <string>
#include <vector>

namespace sas::platform {

struct DeviceFinding {
  std::string category;  // "audio", "gpio", "hid", "pen", "display", "systemd"
  bool found = false;
  std::string detail;
};

using DeviceReport = std::vector<DeviceFinding>;

}  // namespace sas::platform
