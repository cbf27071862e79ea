#pragma once
// The whole hardware report: every device class the kiosk can use, found or not, followed by
// "use" lines saying what the kiosk would pick with the given configuration (the defaults when
// called without one), so `sketch-a-scratch --list-devices` answers "will it work here?".

#include <array>
#include <string>
#include <vector>

#include "platform/device_finding.h"
#include "platform/gpio/gpio_chips.h"
#include "platform/hid/hid_devices.h"
#include "platform/input/switch_event.h"

namespace sas::platform {

// The configuration keys that steer device choice (mirrors the kiosk's [audio], [switches] and
// [pen] sections; see README "Configuration").
struct DeviceSelection {
  std::string audio_output = "default";
  std::string audio_input = "default";
  std::string switches_backend = "auto";  // auto | gpio | mcp2221 | keyboard
  std::string gpio_chip = "gpiochip0";
  // Tokens 1-4 and the record button: offsets or line names, "" = none.
  std::array<std::string, kSwitchInputCount> gpio_lines = {"17", "27", "22", "23", "24"};
  int switches_debounce_ms = 30;
  std::string pen_device;  // substring of the tablet name; empty = first
};

DeviceReport DiscoverDevices(const DeviceSelection& selection);
DeviceReport DiscoverDevices();

// The "use" line for the token switches given the chips and adapters found, by the rule the kiosk
// applies at start (OpenSwitchInputs): GPIO when the chip is there with every configured line,
// else the MCP2221A adapter, else the keys. A chip that lacks configured lines is a problem
// (found = false) named with what is used instead.
DeviceFinding SwitchesUse(const DeviceSelection& selection, const std::vector<GpioChipInfo>& chips,
                          const std::vector<HidDeviceInfo>& adapters);

}  // namespace sas::platform
