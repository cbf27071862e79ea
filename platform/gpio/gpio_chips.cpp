// GPIO chip discovery (see gpio_chips.h).
#include "platform/gpio/gpio_chips.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <gpiod.hpp>

namespace sas::platform {
namespace {

bool IsNumber(const std::string& text) {
  return !text.empty() && std::all_of(text.begin(), text.end(),
                                      [](unsigned char c) { return std::isdigit(c) != 0; });
}

// The chip's named lines as "offset=name" (the forms a configuration can use), at most 32 of
// them; "" when none is named.
std::string NamedLines(const GpioChipInfo& chip) {
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
  return names;
}

}  // namespace

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
    const std::string names = NamedLines(chip);
    report.push_back({"gpio", true,
                      chip.name + " '" + chip.label + "', " + std::to_string(chip.num_lines) +
                          " lines" + (names.empty() ? std::string(" (unnamed)") : ":" + names)});
  }
}

const GpioChipInfo* FindGpioChip(const std::vector<GpioChipInfo>& chips, const std::string& spec) {
  for (const auto& chip : chips) {
    if (chip.name == spec || "/dev/" + chip.name == spec ||
        (!chip.label.empty() && chip.label == spec) ||
        (IsNumber(spec) && chip.name == "gpiochip" + spec)) {
      return &chip;
    }
  }
  return nullptr;
}

std::vector<std::string> MissingGpioLines(const GpioChipInfo& chip,
                                          std::span<const std::string> lines) {
  std::vector<std::string> missing;
  for (const auto& spec : lines) {
    if (spec.empty()) continue;
    bool present = false;
    if (IsNumber(spec)) {
      // Longer than any offset a chip can have: missing (and no overflow in the conversion).
      present = spec.size() < 10 && std::stoul(spec) < chip.num_lines;
    } else {
      present =
          std::find(chip.line_names.begin(), chip.line_names.end(), spec) != chip.line_names.end();
    }
    if (!present) missing.push_back(spec);
  }
  return missing;
}

std::string DescribeMissingGpioLines(const GpioChipInfo& chip,
                                     const std::vector<std::string>& missing) {
  std::string listed;
  for (const auto& line : missing) listed += (listed.empty() ? "" : ",") + line;
  std::string has = "it has " + std::to_string(chip.num_lines) + " lines";
  if (chip.num_lines > 0) {
    const std::string names = NamedLines(chip);
    has += ": 0-" + std::to_string(chip.num_lines - 1) +
           (names.empty() ? std::string(", unnamed") : "; named" + names);
  }
  return chip.name + " lacks line" + (missing.size() == 1 ? " " : "s ") + listed + " (" + has + ")";
}

}  // namespace sas::platform
