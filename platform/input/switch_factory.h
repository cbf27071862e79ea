#pragma once
// Chooses the token-switch backend from configuration, with the keyboard as the fallback that is
// always there (keys 1-4 and R also work next to hardware switches, for staff and tests).
//   backend = "gpio"     libgpiod lines; chip absent -> keyboard, one warning, status "missing"
//   backend = "mcp2221"  USB adapter;    adapter absent -> keyboard, one warning, status "missing",
//                        and the adapter is used as soon as it is plugged in (status "ok")
//   backend = "auto"     gpio if the chip opens, else the adapter if present, else keyboard
//   backend = "keyboard" keys only
// Status key "switches". A chip that is there but lacks a configured line is a configuration
// mistake: a warning naming the chip, the lines it lacks and what is used instead (the adapter or
// the keys), whichever backend takes over; a chip that is simply absent is not (with "auto", a PC
// without a GPIO header is a normal set-up).

#include <memory>
#include <string>

#include "platform/device_status.h"
#include "platform/gpio/gpio_switches.h"
#include "platform/hid/mcp2221.h"
#include "platform/input/switch_input.h"

namespace sas::platform {

struct SwitchesConfig {
  std::string backend = "auto";
  GpioSwitchConfig gpio;
  Mcp2221SwitchConfig mcp2221;
};

struct SwitchInputs {
  std::unique_ptr<SwitchInput> hardware;  // null when only the keyboard is in use
  std::unique_ptr<KeyboardSwitchInput> keyboard = std::make_unique<KeyboardSwitchInput>();
  // Control thread: next event from the hardware, then from the keyboard.
  bool Pop(SwitchEvent& event) {
    return (hardware && hardware->Pop(event)) || keyboard->Pop(event);
  }
  const char* ActiveBackend() const { return hardware ? hardware->Name() : keyboard->Name(); }
};

// Set-up (control thread). Never throws for a missing device: that is a fallback, not an error.
// `gpio_source` / `hid_opener` default to the real devices; tests inject fakes. `gpio_factory`,
// when set, builds the GPIO lines' source in place of libgpiod (when `gpio_source` is null, and
// again after a loss); it may throw as MakeLibgpiodEventSource does.
SwitchInputs OpenSwitchInputs(const SwitchesConfig& config, DeviceStatusBoard& board,
                              std::unique_ptr<GpioEventSource> gpio_source = nullptr,
                              HidOpener hid_opener = nullptr,
                              GpioSwitchInput::SourceFactory gpio_factory = nullptr);

}  // namespace sas::platform
