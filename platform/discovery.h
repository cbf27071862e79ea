#pragma once
// The whole hardware report: every device class the kiosk can use, found or not.

#include "platform/device_finding.h"

namespace sas::platform {

DeviceReport DiscoverDevices();

}  // namespace sas::platform
