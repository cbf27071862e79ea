#pragma once
// The kiosk under its control loop with the platform fakes, as the control and pen tests drive
// it: the engine on the virtual clock without spoken cues, offline audio, keys for tokens and a
// fake tablet.

#include <catch2/catch.hpp>
#include <memory>
#include <utility>

#include "kiosk/kiosk_control.h"
#include "kiosk/kiosk_engine.h"
#include "platform/audio/audio_output.h"
#include "platform/log/log.h"
#include "platform/pen/pen_source.h"

namespace sas::test {

inline kiosk::KioskEngineOptions VirtualClockOptions() {
  kiosk::KioskEngineOptions options;
  options.virtual_clock = true;
  options.cues_dir = "/nonexistent";
  return options;
}

struct QuietLogger : platform::Logger {
  QuietLogger() { SetEchoToStderr(false); }
};

// A kiosk with offline audio, keys for tokens and `pen_source` as its tablet, under the control
// loop.
struct TabletRig {
  explicit TabletRig(std::unique_ptr<platform::FakePenSource> pen_source)
      : engine(VirtualClockOptions()),
        output(engine.audio(), platform::AudioOutputConfig{}),
        fake(pen_source.get()),
        pen(platform::OpenPen({}, board, std::move(pen_source))),
        control(engine, {&output, pen.get(), &switches}, log) {
    REQUIRE(output.Start());
    REQUIRE(pen != nullptr);
  }

  kiosk::KioskEngine engine;
  platform::OfflineAudioOutput output;
  platform::SwitchInputs switches;
  QuietLogger log;
  platform::DeviceStatusBoard board{log};
  platform::FakePenSource* fake;
  std::unique_ptr<platform::PenSource> pen;
  kiosk::KioskControl control;
};

}  // namespace sas::test
