#pragma once
// The whole hardware report: every device class the kiosk can use, found or not, followed by
// "use" lines saying what the kiosk would pick with the given configuration (the defaults when
// called without one), so `sketch-a-scratch --list-devices` answers "will it work here?".

#include <string>

#include "platform/device_finding.h"

namespace sas::platform {

// The configuration keys that steer device choice (mirrors the kiosk's [audio], [switches] and
// [pen] sections; see README "Configuration").
struct DeviceSelection {
  std::string audio_output = "default";
  std::string audio_input = "default";
  std::string switches_backend = "auto";  // auto | gpio | mcp2221 | keyboard
  std::string gpio_chip = "gpiochip0";
  std::string gpio_lines = "17,27,22,23,24";  // tokens 1-4, record
  std::string pen_device;                     // substring of the tablet name; empty = first
};

DeviceReport DiscoverDevices(const DeviceSelection& selection);
DeviceReport DiscoverDevices();

}  // namespace sas::platform
