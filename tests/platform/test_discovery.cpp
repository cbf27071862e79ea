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
