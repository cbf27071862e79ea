// GPIO chip discovery (see gpio_chips.h).
#include "platform/gpio/gpio_chips.h"

#include <filesystem>
#include <gpiod.hpp>

namespace sas::platform {

std::vector<GpioChipInfo> ListGpioChips(std::string* error) {
  std::vector<GpioChipInfo> chips;
  std::error_code ec;
  // Open the chips one by one (rather than with gpiod::make_chip_iter) so that one chip we may
  // not open does not hide the others.
  for (const auto& entry : std::filesystem::directory_iterator("/dev", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("gpiochip", 0) != 0) continue;
    try {
      gpiod::chip chip(entry.path().string(), gpiod::chip::OPEN_BY_PATH);
      chips.push_back({chip.name(), chip.label(), chip.num_lines()});
    } catch (const std::exception& e) {
      if (error) *error = entry.path().string() + ": " + e.what();
    }
  }
  return chips;
}

void ReportGpioChips(DeviceReport& report) {
  std::string error;
  const auto chips = ListGpioChips(&error);
  if (chips.empty()) {
    report.push_back({"gpio", false,
                      "no GPIO chip" + (error.empty() ? std::string() : " (" + error + ")") +
                          ": token switches fall back to the USB adapter or keys 1-4"});
  }
  for (const auto& chip : chips) {
    report.push_back(
        {"gpio", true,
         chip.name + " '" + chip.label + "', " + std::to_string(chip.num_lines) + " lines"});
  }
}

}  // namespace sas::platform
