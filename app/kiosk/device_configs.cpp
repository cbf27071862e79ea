// The configuration as device settings (see device_configs.h).
#include "kiosk/device_configs.h"

#include <algorithm>

namespace sas::kiosk {

platform::AudioInputConfig AudioInputConfigFor(const KioskConfig& config) {
  platform::AudioInputConfig input;
  input.device = config.input_device;
  input.sample_rate_hz = config.sample_rate_hz;
  return input;
}

platform::VoiceRecorderConfig RecorderConfigFor(const KioskConfig& config) {
  platform::VoiceRecorderConfig recorder;
  recorder.sample_rate_hz = config.sample_rate_hz;
  recorder.max_duration_s = config.record_max_duration_s;
  recorder.clip_level = static_cast<float>(config.record_clip_level);
  recorder.silence_rms_dbfs = config.record_silence_rms_dbfs;
  return recorder;
}

platform::AudioOutputConfig AudioOutputConfigFor(const KioskConfig& config) {
  platform::AudioOutputConfig output;
  output.device = config.output_device;
  output.sample_rate_hz = config.sample_rate_hz;
  output.frames_per_buffer = config.buffer_frames;
  output.reopen_backoff_initial_s = config.reopen_backoff_initial_s;
  output.reopen_backoff_max_s = config.reopen_backoff_max_s;
  output.stall_timeout_s = config.stall_timeout_s;
  return output;
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
  platform::PenConfig pen;
  pen.screen_width_px = screen_width_px;
  pen.screen_height_px = screen_height_px;
  pen.seat = config.pen_seat;
  pen.device_name_contains = config.pen_device;
  return pen;
}

}  // namespace sas::kiosk
