// The configuration as device settings (kiosk/device_configs.h): every key reaches its device,
// and the device report (--list-devices) is given the same choices.
#include <catch2/catch.hpp>

#include "kiosk/device_configs.h"

using namespace sas;

TEST_CASE(
    "device configs: audio, switch and pen keys reach their devices, and both switch "
    "share polarity and debounce",
    "[kiosk]") {
  kiosk::KioskConfig config;
  config.input_device = "USB mic";
  config.output_device = "hw:CARD=Device";
  config.sample_rate_hz = 44100;
  config.buffer_frames = 256;
  config.reopen_backoff_initial_s = 0.5;
  config.reopen_backoff_max_s = 4.0;
  config.stall_timeout_s = 2.0;
  config.record_max_duration_s = 3.0;
  config.record_clip_level = 0.9;
  config.record_silence_rms_dbfs = -45.0;
  config.switches_backend = "gpio";
  config.gpio_chip = "gpiochip1";
  config.gpio_lines = {"5", "6", "13"};
  config.switches_active_low = false;
  config.switches_debounce_ms = 12;
  config.mcp2221_path = "/dev/hidraw3";
  config.mcp2221_poll_ms = 7;
  config.pen_seat = "seat1";
  config.pen_device = "Wacom";

  const auto input = kiosk::AudioInputConfigFor(config);
  CHECK(input.device == "USB mic");
  CHECK(input.sample_rate_hz == 44100);
  const auto recorder = kiosk::RecorderConfigFor(config);
  CHECK(recorder.sample_rate_hz == 44100);
  CHECK(recorder.max_duration_s == 3.0);
  CHECK(recorder.clip_level == Approx(0.9f));
  CHECK(recorder.silence_rms_dbfs == -45.0);
  const auto output = kiosk::AudioOutputConfigFor(config);
  CHECK(output.device == "hw:CARD=Device");
  CHECK(output.sample_rate_hz == 44100);
  CHECK(output.frames_per_buffer == 256);
  CHECK(output.reopen_backoff_initial_s == 0.5);
  CHECK(output.reopen_backoff_max_s == 4.0);
  CHECK(output.stall_timeout_s == 2.0);

  const auto switches = kiosk::SwitchesConfigFor(config);
  CHECK(switches.backend == "gpio");
  CHECK(switches.gpio.chip == "gpiochip1");
  CHECK(switches.gpio.lines[0] == "5");
  CHECK(switches.gpio.lines[2] == "13");
  CHECK(switches.gpio.lines[3] == platform::GpioSwitchConfig{}.lines[3]);  // not configured
  for (const bool active_low : {switches.gpio.active_low, switches.mcp2221.active_low}) {
    CHECK_FALSE(active_low);
  }
  CHECK(switches.gpio.debounce_ms == 12);
  CHECK(switches.mcp2221.debounce_ms == 12);
  CHECK(switches.mcp2221.path == "/dev/hidraw3");
  CHECK(switches.mcp2221.poll_interval_ms == 7);

  const auto pen = kiosk::PenConfigFor(config, 1280, 720);
  CHECK(pen.screen_width_px == 1280);
  CHECK(pen.screen_height_px == 720);
  CHECK(pen.seat == "seat1");
  CHECK(pen.device_name_contains == "Wacom");

  // --list-devices judges the same devices the kiosk opens.
  const auto selection = kiosk::DeviceSelectionFor(config);
  CHECK(selection.audio_output == "hw:CARD=Device");
  CHECK(selection.audio_input == "USB mic");
  CHECK(selection.switches_backend == "gpio");
  CHECK(selection.gpio_chip == "gpiochip1");
  CHECK(selection.gpio_lines == switches.gpio.lines);
  CHECK(selection.switches_debounce_ms == 12);
  CHECK(selection.pen_device == "Wacom");
}
