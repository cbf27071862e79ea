// Token-switch backend selection with keyboard fallback (see switch_factory.h).
#include "platform/input/switch_factory.h"

namespace sas::platform {

SwitchInputs OpenSwitchInputs(const SwitchesConfig& config, DeviceStatusBoard& board,
                              std::unique_ptr<GpioEventSource> gpio_source, HidOpener hid_opener,
                              GpioSwitchInput::SourceFactory gpio_factory) {
  SwitchInputs inputs;
  const bool want_gpio = config.backend == "gpio" || config.backend == "auto";
  const bool want_hid = config.backend == "mcp2221" || config.backend == "auto";
  std::string why;
  // The GPIO chip is there but the configuration names lines it lacks: a mistake staff must
  // hear about (a warning) even when the adapter takes over and everything seems to work.
  bool gpio_misconfigured = false;
  if (want_gpio) {
    auto gpio = std::make_unique<GpioSwitchInput>(config.gpio, std::move(gpio_source));
    gpio->ReportTo(&board);  // a loss once running: one line, and one when the lines return
    if (gpio_factory) gpio->SetSourceFactory(std::move(gpio_factory));
    std::string error;
    if (gpio->Start(&error)) {
      board.Set("switches", DeviceState::kOk,
                "GPIO " + config.gpio.chip + ", debounce " +
                    std::to_string(static_cast<int>(config.gpio.debounce_ms)) + " ms",
                "gpio");
      inputs.hardware = std::move(gpio);
      return inputs;
    }
    why = "GPIO chip '" + config.gpio.chip + "' unusable (" + error + ")";
    gpio_misconfigured = gpio->lines_missing();
    // The journal says why the GPIO header is not used even when the adapter takes over. (A
    // chip lacking lines gets its warning below, once it is known what is used instead.)
    if (want_hid && !gpio_misconfigured) {
      board.logger().Info("switches", why + "; trying the MCP2221A adapter");
    }
  }
  if (want_hid) {
    auto hid = std::make_unique<Mcp2221SwitchInput>(
        config.mcp2221, hid_opener ? std::move(hid_opener) : MakeHidapiOpener(config.mcp2221.path),
        board);
    std::string error;
    if (hid->Start(&error)) {  // sets status "ok" itself
      if (gpio_misconfigured) {
        board.logger().Warn("switches", why + "; using the MCP2221A adapter instead");
      }
      inputs.hardware = std::move(hid);
      return inputs;
    }
    if (config.backend == "mcp2221") {
      // Asked for explicitly: keys meanwhile, and the adapter is taken as soon as it appears.
      board.AddFailure("switches");
      board.Set("switches", DeviceState::kMissing,
                error + "; keys 1-4 (R records) until it is plugged in", "mcp2221");
      hid->StartWaiting();
      inputs.hardware = std::move(hid);
      return inputs;
    }
    why += (why.empty() ? "" : " and ") + error;
  }
  if (config.backend == "keyboard") {
    board.Set("switches", DeviceState::kOk, "keys 1-4 toggle tokens, R records", "keyboard");
  } else {
    board.AddFailure("switches");
    board.Set("switches", DeviceState::kMissing,
              why + "; token switches fall back to keys 1-4 (R records)", "keyboard");
  }
  return inputs;
}

}  // namespace sas::platform
