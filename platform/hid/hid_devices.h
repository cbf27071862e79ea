#pragma once
// USB-HID discovery through hidapi (hidraw backend): the MCP2221A GPIO adapter that reads the
// token switches on kiosk PCs without a GPIO header.

#include <string>
#include <vector>

#include "platform/device_finding.h"

namespace sas::platform {

inline constexpr unsigned short kMcp2221VendorId = 0x04D8;
inline constexpr unsigned short kMcp2221ProductId = 0x00DD;

struct HidDeviceInfo {
  std::string path;  // /dev/hidrawN
  std::string product;
  std::string serial;
};

std::vector<HidDeviceInfo> ListMcp2221Adapters();

void ReportHidAdapters(DeviceReport& report);

}  // namespace sas::platform
