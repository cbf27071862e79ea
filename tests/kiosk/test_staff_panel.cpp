// The staff panel's logic (kiosk/staff_panel.h): what its buttons do and what its text says, on a
// real engine with offline audio.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "files/staff_settings.h"
#include "kiosk/staff_panel.h"

using namespace sas;
using kiosk::StaffButton;

namespace {

constexpr std::int64_t kMs = 1'000'000;

struct Rig {
  Rig() : engine(Options()), output(engine.audio(), platform::AudioOutputConfig{}) {
    log.SetEchoToStderr(false);
  }
  static kiosk::KioskEngineOptions Options() {
    kiosk::KioskEngineOptions options;
    options.virtual_clock = true;
    options.cues_dir = "/nonexistent";
    return options;
  }
  kiosk::StaffPanelInputs Inputs(const platform::PenReading& pen = {}) const {
    return {&engine, &output, &board, &switches, &selector, true, pen, "Config: test.toml",
            128,     48000};
  }
  bool HasLine(const std::string& text) const {
    for (const auto& line : kiosk::StaffPanelLines(Inputs())) {
      if (line.text == text) return true;
    }
    return false;
  }

  kiosk::KioskEngine engine;
  platform::OfflineAudioOutput output;
  platform::Logger log;
  platform::DeviceStatusBoard board{log};
  platform::SwitchInputs switches;
  platform::TokenSelector selector;
};

}  // namespace

TEST_CASE(
    "staff panel: a button acts once per press, and a pen resting on it repeats only after "
    "half a second",
    "[kiosk]") {
  Rig rig;
  kiosk::StaffPanel panel;
  const double start_db = rig.engine.staff_settings().volume_db;
  CHECK(panel.Press(StaffButton::kVolumeUp, 1000 * kMs, rig.engine, rig.log));
  CHECK(rig.engine.staff_settings().volume_db == Approx(start_db + kiosk::kStaffStepDb));
  CHECK_FALSE(panel.Press(StaffButton::kVolumeUp, 1200 * kMs, rig.engine, rig.log));
  CHECK_FALSE(panel.Press(StaffButton::kVolumeDown, 1500 * kMs, rig.engine, rig.log));
  CHECK(rig.engine.staff_settings().volume_db == Approx(start_db + kiosk::kStaffStepDb));
  CHECK(panel.Press(StaffButton::kVolumeDown, 1501 * kMs, rig.engine, rig.log));
  CHECK(rig.engine.staff_settings().volume_db == Approx(start_db));
  CHECK(rig.log.Recent().back().Text().find("info staff: volume ") == 0);
}

TEST_CASE("staff panel: the low-vibration button toggles the mode, and its label says which",
          "[kiosk]") {
  Rig rig;
  kiosk::StaffPanel panel;
  CHECK(std::string(kiosk::StaffButtonLabel(StaffButton::kLowVibration, false)) == "Low vib off");
  REQUIRE_FALSE(rig.engine.low_vibration());
  CHECK(panel.Press(StaffButton::kLowVibration, 1000 * kMs, rig.engine, rig.log));
  CHECK(rig.engine.low_vibration());
  CHECK(rig.log.Recent().back().Text() == "info staff: low-vibration mode on");
  CHECK(std::string(kiosk::StaffButtonLabel(StaffButton::kLowVibration, true)) == "Low vib on");
  CHECK_FALSE(panel.Press(StaffButton::kCount, 3000 * kMs, rig.engine, rig.log));
}

TEST_CASE(
    "staff panel: the text names the version first, marks a device that is not ok, and "
    "reports the pen, the record button and the configuration line",
    "[kiosk]") {
  Rig rig;
  rig.board.Set("pen", platform::DeviceState::kMissing, "no pen tablet", "libinput");
  rig.board.Set("audio_out", platform::DeviceState::kOk, "running", "portaudio");
  platform::PenReading pen;
  pen.origin = platform::PenOrigin::kTablet;
  pen.pressure = 0.5;
  pen.tilt_x_deg = 30.0;
  pen.x_px = 100.0;
  pen.y_px = 200.0;
  const auto lines = kiosk::StaffPanelLines(rig.Inputs(pen));
  REQUIRE(lines.size() > 4);
  CHECK(lines[0].text.find("Sketch-a-Scratch ") == 0);
  CHECK(lines[0].warning);
  const auto find = [&](const std::string& start) -> const kiosk::StaffPanelLine* {
    for (const auto& line : lines) {
      if (line.text.rfind(start, 0) == 0) return &line;
    }
    return nullptr;
  };
  REQUIRE(find("pen: missing (libinput)"));
  CHECK(find("pen: missing (libinput)")->warning);
  REQUIRE(find("audio_out: ok (portaudio) - running"));
  CHECK_FALSE(find("audio_out: ok")->warning);
  REQUIRE(find("Pen: "));
  CHECK(find("Pen: ")->text == "Pen: pressure 0.50, tilt 30.0 deg, at 100,200 (tablet)");
  REQUIRE(find("Switches: "));
  CHECK(find("Switches: ")->text.find(", record down, showing ") != std::string::npos);
  CHECK(rig.HasLine("Config: test.toml"));
  CHECK(rig.HasLine("Volume 0 dB, vibration 0 dB"));
}

TEST_CASE(
    "staff panel: the speaker's Leq reads as dBFS, as silent after a visit with no sound, and as a "
    "dash before any",
    "[kiosk]") {
  CHECK(kiosk::LeqText(-20.34) == "-20.3 dBFS");
  CHECK(kiosk::LeqText(-99.5) == "-99.5 dBFS");
  CHECK(kiosk::LeqText(-300.0) == "silent");  // the meter's floor: no sample above zero
  CHECK(kiosk::LeqText(std::nullopt) == "-");
}
