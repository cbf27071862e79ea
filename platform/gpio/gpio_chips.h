#pragma once
// GPIO chip discovery through libgpiod 1.6's C++ bindings (v1 kernel character-device API).

#include <span>
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

// The chip `spec` names the way libgpiod looks chips up (name "gpiochip0", path
// "/dev/gpiochip0", label, or number "0"), or null when none of `chips` is it.
const GpioChipInfo* FindGpioChip(const std::vector<GpioChipInfo>& chips, const std::string& spec);

// The configured lines (offsets "17" or line names "GPIO17"; empty entries are unused) that `chip`
// does not have, in the order given.
std::vector<std::string> MissingGpioLines(const GpioChipInfo& chip,
                                          std::span<const std::string> lines);

// "gpiochip0 lacks lines 17,27 (it has 5 lines: 0-4, unnamed)": what is wrong with a
// configuration naming `missing` on `chip`, and what the chip offers instead.
std::string DescribeMissingGpioLines(const GpioChipInfo& chip,
                                     const std::vector<std::string>& missing);

}  // namespace sas::platform
