#pragma once
// GPIO chip discovery through libgpiod 1.6's C++ bindings (v1 kernel character-device API).

#include <string>
#include <vector>

#include "platform/device_finding.h"

namespace sas::platform {

struct GpioChipInfo {
  std::string name;   // gpiochip0
  std::string label;  // driver label, e.g. pinctrl-bcm2711
  unsigned num_lines = 0;
  std::vector<std::string> line_names;  // by offset; empty string for unnamed lines
};

// Every GPIO chip the process may open; empty on machines without one (or without permission,
// reported through `error`).
std::vector<GpioChipInfo> ListGpioChips(std::string* error = nullptr);

void ReportGpioChips(DeviceReport& report);

}  // namespace sas::platform
