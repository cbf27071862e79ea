// --list-devices' report: found devices plus the "use" lines saying what the kiosk would pick.
#include <algorithm>
#include <catch2/catch.hpp>

#include "alsa_file_config.h"
#include "platform/discovery.h"

namespace {

std::vector<std::string> UseLines(const sas::platform::DeviceReport& report) {
  std::vector<std::string> lines;
  for (const auto& f : report)
    if (f.category == "use") lines.push_back(f.detail);
  return lines;
}

bool Has(const std::vector<std::string>& lines, const std::string& prefix) {
  return std::any_of(lines.begin(), lines.end(),
                     [&](const std::string& l) { return l.rfind(prefix, 0) == 0; });
}

}  // namespace

TEST_CASE("device report says which audio devices and switch backend the kiosk would use",
          "[platform]") {
  sas::test::AlsaFileConfig alsa;
  sas::platform::DeviceSelection selection;
  selection.audio_output = "kiosk_out";
  selection.audio_input = "kiosk_in";
  selection.switches_backend = "gpio";
  selection.gpio_chip = "sas-test-no-such-gpiochip";
  const auto report = sas::platform::DiscoverDevices(selection);
  const auto use = UseLines(report);
  INFO(::Catch::Detail::stringify(use));
  CHECK(Has(use, "audio out: 'kiosk_out'"));
  CHECK(Has(use, "audio in: 'kiosk_in'"));
  CHECK(Has(use, "token switches: keys 1-4"));
  CHECK(Has(use, "pen: "));
  // Every device class appears, found or not.
  for (const char* category : {"audio", "gpio", "hid", "pen", "systemd"}) {
    CHECK(std::any_of(report.begin(), report.end(),
                      [&](const auto& f) { return f.category == category; }));
  }

  selection.audio_output = "no_such_card";
  const auto missing = UseLines(sas::platform::DiscoverDevices(selection));
  CHECK(Has(missing, "audio out: configured device 'no_such_card' not present -> runs silent"));
}

TEST_CASE(
    "device report: a GPIO chip that lacks the configured lines is no GPIO choice, and the line names "
    "chip, lines and what is used instead",
    "[platform]") {
  using sas::platform::GpioChipInfo;
  using sas::platform::HidDeviceInfo;
  sas::platform::DeviceSelection selection;  // auto, gpiochip0, 17 27 22 23 24
  const std::vector<GpioChipInfo> chips = {{"gpiochip0", "gpio-sim", 5, {"", "", "", "", ""}}};
  const std::vector<HidDeviceInfo> adapter = {{"/dev/hidraw3", "MCP2221 USB-I2C/UART Combo", ""}};
  const std::string lacks =
      "token switches: GPIO gpiochip0 lacks lines 17,27,22,23,24 (it has 5 lines: 0-4, unnamed); "
      "using ";

  auto use = sas::platform::SwitchesUse(selection, chips, adapter);
  CHECK_FALSE(use.found);
  CHECK(use.detail == lacks + "MCP2221A /dev/hidraw3 GP0-3, record on key R");

  use = sas::platform::SwitchesUse(selection, chips, {});
  CHECK_FALSE(use.found);
  CHECK(use.detail == lacks + "keys 1-4 (toggle tokens) and R (record)");

  selection.switches_backend = "gpio";  // the adapter is then not tried
  use = sas::platform::SwitchesUse(selection, chips, adapter);
  CHECK(use.detail == lacks + "keys 1-4 (toggle tokens) and R (record)");

  // Lines the chip has: GPIO, as configured.
  selection.gpio_lines = {"0", "1", "2", "3", "4"};
  selection.switches_debounce_ms = 20;
  use = sas::platform::SwitchesUse(selection, chips, adapter);
  CHECK(use.found);
  CHECK(use.detail ==
        "token switches: GPIO gpiochip0 lines 0,1,2,3,4 (tokens 1-4, record), debounce 20 ms");

  // No chip at all: the adapter, which is no problem with "auto".
  selection.switches_backend = "auto";
  use = sas::platform::SwitchesUse(selection, {}, adapter);
  CHECK(use.found);
  CHECK(use.detail == "token switches: MCP2221A /dev/hidraw3 GP0-3, record on key R");
}
