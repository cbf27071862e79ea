#pragma once
// The live kiosk: the full-screen SDL window, the pen (libinput, else SDL mouse/touch),
// the token switches and record button, the microphone and the speaker/transducer, all wired to
// one KioskEngine, plus the staff panel, the watchdog and the device status board.
//
//   sketch-a-scratch kiosk [--config FILE] [--state-dir DIR]   (FILE default
//   /etc/sketch-a-scratch/kiosk.toml); exits 1 at once when there is no display.

#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "platform/audio/audio_output.h"
#include "platform/gpio/gpio_switches.h"
#include "platform/pen/pen_source.h"

namespace sas::app {

// The one seam for the end-to-end test (tests/e2e/kiosk_gpio_e2e_app.cpp): the product passes
// nothing and every backend is real. `gpio_events`, when set, builds the GPIO token switches'
// event source from the configured chip and lines instead of libgpiod (Debian 12's kernel has no
// gpio-sim); the backend choice, the GPIO switch thread, debounce, active-low and the token rule
// stay the real ones. It is called only when [switches] backend is "gpio" or "auto", must not
// throw, and may return null (then libgpiod is used).
//
// The UI latency measurement (tests/bench/ui_latency_audio_loss.sh) uses two more: `audio_stream`,
// when set, is the audio output's device in place of PortAudio (the supervision, its back-off and
// its background thread stay the real ones), and `on_pass`, when set, is called at the end of
// every pass of the UI loop with the pass's start and end (CLOCK_MONOTONIC ns); it must be quick.
//
// The start-up test (tests/kiosk/test_live_kiosk.cpp) uses two more: `pen`, when set, is the pen
// source in place of libinput (OpenPen's start and status stay the real ones), and `on_present`,
// when set, is called right after each frame the window presented (CLOCK_MONOTONIC ns), before
// anything the frame triggers (the first one: READY=1 and the "kiosk ready" line).
struct KioskBackends {
  std::function<std::unique_ptr<platform::GpioEventSource>(const platform::GpioSwitchConfig&)>
      gpio_events;
  std::function<std::unique_ptr<platform::AudioStreamBackend>()> audio_stream;
  std::function<void(std::int64_t start_ns, std::int64_t end_ns)> on_pass;
  std::function<std::unique_ptr<platform::PenSource>()> pen;
  std::function<void(std::int64_t presented_ns)> on_present;
};

// Runs until SIGTERM/SIGINT (systemd's stop), saving the usage counters on the way out. It tells
// systemd it is ready (READY=1) and prints "kiosk ready ..." on `out` once its first frame is on
// the screen, and pings the watchdog after every pass of its loop from then on. SIGHUP
// saves them at once and the kiosk runs on; SIGUSR1 writes the devices' status to the journal;
// SIGPIPE is ignored. Returns the exit code; 1 when no window opens.
int RunKiosk(const std::vector<std::string>& args, std::FILE* out, std::FILE* err,
             const KioskBackends& backends = {});

}  // namespace sas::app
