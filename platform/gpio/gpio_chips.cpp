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
      GpioChipInfo info{chip.name(), chip.label(), chip.num_lines(), {}};
      for (unsigned offset = 0; offset < chip.num_lines(); ++offset)
        info.line_names.push_back(chip.get_line(offset).name());
      chips.push_back(std::move(info));
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
    // Named lines (offset=name) so a configuration can use either; unnamed ones are counted.
    std::string names;
    int shown = 0;
    for (std::size_t i = 0; i < chip.line_names.size(); ++i) {
      if (chip.line_names[i].empty()) continue;
      if (++shown > 32) {
        names += " ...";
        break;
      }
      names += " " + std::to_string(i) + "=" + chip.line_names[i];
    }
    report.push_back({"gpio", true,
                      chip.name + " '" + chip.label + "', " + std::to_string(chip.num_lines) +
                          " lines" + (names.empty() ? std::string(" (unnamed)") : ":" + names)});
  }
}

}  // namespace sas::platform
