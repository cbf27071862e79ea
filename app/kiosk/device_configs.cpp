// The configuration as device settings (see device_configs.h).
#include "kiosk/device_configs.h"

#include <algorithm>

namespace sas::kiosk {

platform::AudioInputConfig AudioInputConfigFor(const KioskConfig& config) {
  return {.device = config.input_device, .sample_rate_hz = config.sample_rate_hz};
}

platform::VoiceRecorderConfig RecorderConfigFor(const KioskConfig& config) {
  return {.sample_rate_hz = config.sample_rate_hz,
          .max_duration_s = config.record_max_duration_s,
          .clip_level = static_cast<float>(config.record_clip_level),
          .silence_rms_dbfs = config.record_silence_rms_dbfs};
}

platform::AudioOutputConfig AudioOutputConfigFor(const KioskConfig& config) {
  return {.device = config.output_device,
          .sample_rate_hz = config.sample_rate_hz,
          .frames_per_buffer = config.buffer_frames,
          .reopen_backoff_initial_s = config.reopen_backoff_initial_s,
          .reopen_backoff_max_s = config.reopen_backoff_max_s,
          .stall_timeout_s = config.stall_timeout_s};
}

platform::SwitchesConfig SwitchesConfigFor(const KioskConfig& config) {
  platform::SwitchesConfig switches;
  switches.backend = config.switches_backend;
  switches.gpio.chip = config.gpio_chip;
  // Tokens 1-4 and the record button; a shorter list leaves the rest at their defaults.
  const std::size_t lines = std::min(switches.gpio.lines.size(), config.gpio_lines.size());
  std::copy_n(config.gpio_lines.begin(), lines, switches.gpio.lines.begin());
  switches.gpio.active_low = config.switches_active_low;
  switches.gpio.debounce_ms = config.switches_debounce_ms;
  switches.mcp2221.path = config.mcp2221_path;
  switches.mcp2221.active_low = config.switches_active_low;
  switches.mcp2221.debounce_ms = config.switches_debounce_ms;
  switches.mcp2221.poll_interval_ms = config.mcp2221_poll_ms;
  return switches;
}

platform::PenConfig PenConfigFor(const KioskConfig& config, int screen_width_px,
                                 int screen_height_px) {
  return {.screen_width_px = screen_width_px,
          .screen_height_px = screen_height_px,
          .seat = config.pen_seat,
          .device_name_contains = config.pen_device};
}

platform::DeviceSelection DeviceSelectionFor(const KioskConfig& config) {
  platform::DeviceSelection selection;
  selection.audio_output = config.output_device;
  selection.audio_input = config.input_device;
  const platform::SwitchesConfig switches = SwitchesConfigFor(config);
  selection.switches_backend = switches.backend;
  selection.gpio_chip = switches.gpio.chip;
  selection.gpio_lines = switches.gpio.lines;
  selection.switches_debounce_ms = config.switches_debounce_ms;
  selection.pen_device = config.pen_device;
  return selection;
}

}  // namespace sas::kiosk
