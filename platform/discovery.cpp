// Aggregates the per-device reports and the choice the kiosk would make (see discovery.h). The
// choice rules are the ones the backends apply at start: audio by name (exact, else unique
// substring), switches gpio -> MCP2221A -> keys for "auto", pen = first tablet-tool device.
#include "platform/discovery.h"

#include <algorithm>

#include "platform/audio/audio_devices.h"
#include "platform/gpio/gpio_chips.h"
#include "platform/hid/hid_devices.h"
#include "platform/pen/tablet_devices.h"
#include "platform/watchdog/systemd_notifier.h"

namespace sas::platform {
namespace {

const AudioDeviceInfo* PickAudio(const std::vector<AudioDeviceInfo>& devices,
                                 const std::string& name, bool output) {
  auto channels = [output](const AudioDeviceInfo& d) {
    return output ? d.max_output_channels : d.max_input_channels;
  };
  const AudioDeviceInfo* partial = nullptr;
  int partial_count = 0;
  for (const auto& d : devices) {
    if (channels(d) <= 0) continue;
    if (d.name == name) return &d;
    if (d.name.find(name) != std::string::npos) {
      partial = &d;
      ++partial_count;
    }
  }
  return partial_count == 1 ? partial : nullptr;
}

void AddAudioUse(DeviceReport& report, const std::vector<AudioDeviceInfo>& devices,
                 const std::string& name, bool output) {
  const AudioDeviceInfo* d = PickAudio(devices, name, output);
  const std::string what = output ? "audio out" : "audio in";
  if (d == nullptr) {
    report.push_back({"use", false,
                      what + ": configured device '" + name + "' not present -> " +
                          (output ? "runs silent, retries" : "recording disabled")});
    return;
  }
  const int ch = output ? d->max_output_channels : d->max_input_channels;
  std::string detail = what + ": '" + d->name + "' (" + std::to_string(ch) + " ch)";
  if (output && ch < 2) detail += " -- only 1 channel: no transducer channel";
  report.push_back({"use", output ? ch >= 2 : true, detail});
}

}  // namespace

DeviceReport DiscoverDevices(const DeviceSelection& selection) {
  DeviceReport report;
  ReportAudioDevices(report);
  ReportGpioChips(report);
  ReportHidAdapters(report);
  ReportTablets(report);
  ReportSystemd(report);

  const auto audio = ListAudioDevices();
  AddAudioUse(report, audio, selection.audio_output, true);
  AddAudioUse(report, audio, selection.audio_input, false);

  report.push_back(SwitchesUse(selection, ListGpioChips(), ListMcp2221Adapters()));

  const auto tablets = ListTablets();
  const auto tablet = std::find_if(tablets.begin(), tablets.end(), [&](const TabletInfo& t) {
    return selection.pen_device.empty() || t.name.find(selection.pen_device) != std::string::npos;
  });
  report.push_back({"use", tablet != tablets.end(),
                    tablet != tablets.end()
                        ? "pen: " + tablet->name + " via libinput (pressure, tilt)"
                        : std::string("pen: mouse/touch via SDL2 (no pressure or tilt)")});
  return report;
}

DeviceReport DiscoverDevices() {
  return DiscoverDevices(DeviceSelection{});
}

DeviceFinding SwitchesUse(const DeviceSelection& selection, const std::vector<GpioChipInfo>& chips,
                          const std::vector<HidDeviceInfo>& adapters) {
  const std::string& backend = selection.switches_backend;
  const bool want_gpio = backend == "gpio" || backend == "auto";
  const bool want_hid = backend == "mcp2221" || backend == "auto";
  // Why the configured chip, which is there, will not be used: the lines it lacks.
  std::string gpio_problem;
  if (want_gpio) {
    if (const GpioChipInfo* chip = FindGpioChip(chips, selection.gpio_chip)) {
      const auto missing = MissingGpioLines(*chip, selection.gpio_lines);
      if (missing.empty()) {
        std::string lines;
        for (const auto& line : selection.gpio_lines) {
          if (!line.empty()) lines += (lines.empty() ? "" : ",") + line;
        }
        return {"use", true,
                "token switches: GPIO " + selection.gpio_chip + " lines " + lines +
                    " (tokens 1-4, record), debounce " +
                    std::to_string(selection.switches_debounce_ms) + " ms"};
      }
      gpio_problem = "GPIO " + DescribeMissingGpioLines(*chip, missing);
    }
  }
  std::string used;
  bool ok = gpio_problem.empty();
  if (want_hid && !adapters.empty()) {
    used = "MCP2221A " + adapters.front().path + " GP0-3, record on key R";
  } else {
    used = "keys 1-4 (toggle tokens) and R (record)";
    ok = ok && backend == "keyboard";
    if (gpio_problem.empty() && backend != "keyboard") {
      used += " -- no " + (backend == "auto" ? std::string("GPIO chip or USB adapter") : backend);
    }
  }
  return {"use", ok,
          "token switches: " + (gpio_problem.empty() ? used : gpio_problem + "; using " + used)};
}

}  // namespace sas::platform
