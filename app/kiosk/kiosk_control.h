#pragma once
// The kiosk's control loop body, device side: one Step per pass drains the pen and the token
// switches into the KioskEngine, ticks it, supervises the audio device and keeps the staff-visible
// status (platform::DeviceStatusBoard) in step with what the engine and the devices report. The
// live kiosk (app/live_kiosk.cpp) calls it between its window's events and its frame; the
// fault-injection test (tests/kiosk/test_kiosk_faults.cpp) calls the same Step with the platform
// fakes in place of PortAudio, libinput, libgpiod and hidapi, so what it checks is what runs.
//
// Per Step: pen events (handed to the caller's pen handler: the UI also draws them) -> a tablet
// that went away with its tip down gets a synthesised tip-up (the sound stops, the stroke ends)
// -> switch events (TokenSelector -> OnToken; record button) -> engine.Tick (session timers,
// counters) -> audio Poll (lost device: silent, reopened with back-off) -> the engine is told
// whether a callback runs, and whether the microphone still delivers. Session actions come back to
// the caller and are logged here, one journal line per visible step.
//
// A Step takes at most kPenReadingsPerStep pen readings and kSwitchEventsPerStep switch events;
// the rest stay queued, in order with their own timestamps, for the next Step (Backlog() says
// so, and the loop then does not sleep). A queue that filled up before the loop ran (input
// arriving while a slow machine starts) is thus worked off over a few passes instead of in one
// long pass that keeps the frame and the watchdog's ping waiting.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "files/kiosk_config.h"
#include "kiosk/kiosk_engine.h"
#include "platform/audio/audio_input.h"
#include "platform/audio/audio_output.h"
#include "platform/device_status.h"
#include "platform/input/switch_factory.h"
#include "platform/input/token_selector.h"
#include "platform/log/log.h"
#include "platform/pen/pen_source.h"

namespace sas::kiosk {

// The staff panel's and the journal's line about the configuration file that was (or was not)
// used at start: "Configuration: <path> (accepted)" when it loaded, else "... rejected, running
// on the last good copy | the built-in defaults: <file>:<line>: <key>: <what>".
std::string ConfigStatusLine(const std::string& path, const ConfigLoadResult& loaded);

// Puts what happened at start on the board, so the staff panel lists it next to the devices (and
// the journal has one line each): "config" (ok, or "missing: rejected: <file>:<line>: <key>:
// <what> (using the last good configuration | the built-in defaults)") and "textures" (how many
// loaded, and which were left out and why).
void ReportConfig(platform::DeviceStatusBoard& board, const ConfigLoadResult& loaded);
void ReportTextures(platform::DeviceStatusBoard& board, const KioskEngine& engine);

// For a process that runs for months: large blocks (pictures, height fields, voice takes) are
// always mapped and unmapped on their own (a fixed mmap threshold, glibc's mallopt) instead of
// being carved from the heap, where a freed 24 MB field can stay resident behind a small live
// block. Called at the start of the kiosk and of the soak run.
void TuneAllocatorForLongRuns();

struct KioskDevices {
  platform::AudioOutput* output = nullptr;             // required
  platform::PenSource* pen = nullptr;                  // null: no libinput at all (mouse/touch)
  platform::SwitchInputs* switches = nullptr;          // required
  const platform::DeviceStatusBoard* board = nullptr;  // null: SIGUSR1's status names no device
  platform::AudioInput* input = nullptr;  // null: no microphone to watch (none at start)
};

class KioskControl {
 public:
  // A pass normally finds a handful of readings (a tablet reports at 100-300 Hz, the loop runs
  // at the display's 60 Hz or faster): 64 leaves over ten times that in hand, so a full pen queue
  // (1024) drains in 16 passes, while one pass's pen work stays a fixed, small amount even where
  // each reading costs milliseconds (an emulated machine).
  static constexpr int kPenReadingsPerStep = 64;
  // Token switches change a few times a minute; each event may switch the texture. A queue full
  // of them (a bouncing contact at start) is worked off 16 at a time.
  static constexpr int kSwitchEventsPerStep = 16;

  // Receives every pen reading (and the synthesised lift); the live kiosk hands it to the view
  // and the engine, tests to the engine.
  using PenHandler = std::function<void(const platform::PenReading&)>;

  KioskControl(KioskEngine& engine, KioskDevices devices, platform::Logger& log);

  // True when pointer (mouse/touch) input should drive the engine: no tablet, or it is unplugged.
  bool PointerActive() const;
  // One pass of the loop at `now_ns` (CLOCK_MONOTONIC, or a test's clock). Returns the session's
  // actions for the UI (already applied to the engine and logged).
  std::vector<SessionAction> Step(std::int64_t now_ns, const PenHandler& on_pen);
  // Clean stop (SIGTERM): counters saved, audio stopped. False when the save failed (logged).
  bool Shutdown();
  // SIGHUP (the unit's reload): the usage counters are saved now rather than at the next periodic
  // save, and one journal line says so and that the configuration is only read at start. The
  // loop goes on. False when the save failed (logged).
  bool Hangup();
  // SIGUSR1: one journal line (info) with every status board entry and the visit count, for staff
  // without the panel (`systemctl kill -s USR1`). The loop goes on.
  void ReportStatus();
  // Between passes: acts on the flags the signal handlers raised (kiosk_signals.h): SIGHUP ->
  // Hangup(), SIGUSR1 -> ReportStatus(). True when SIGTERM/SIGINT asked the loop to end.
  bool HandleSignals();

  // True when the last Step left pen readings or switch events queued (its budget ran out): the
  // loop should come round again at once instead of waiting for input.
  bool Backlog() const { return backlog_; }
  bool record_down() const { return record_down_; }
  const platform::TokenSelector& selector() const { return selector_; }

 private:
  KioskEngine* engine_;
  KioskDevices devices_;
  platform::Logger* log_;
  platform::TokenSelector selector_;
  bool record_down_ = false;
  bool backlog_ = false;
  bool pen_was_connected_ = true;
  platform::PenReading last_pen_{};
};

// One journal line per visible session step (staff reading the journal, the end-to-end tests).
void LogSessionActions(platform::Logger& log, const KioskEngine& engine,
                       const std::vector<SessionAction>& actions);

}  // namespace sas::kiosk
