// The staff panel's logic (kiosk/staff_panel.h): what its buttons do and what its text says, on a
// real engine with offline audio.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cctype>
#include <chrono>
#include <string>
#include <thread>
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
    return {&engine,   &output, &board, &switches,
            &selector, true,    pen,    "Configuration: test.toml (accepted)",
            128,       48000};
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

TEST_CASE(
    "staff panel: the low-vibration button says what it does, and its caption says the mode's "
    "state",
    "[kiosk]") {
  Rig rig;
  kiosk::StaffPanel panel;
  const auto caption = [&](StaffButton button) {
    for (const auto& c : kiosk::StaffButtonCaptions(rig.engine)) {
      if (c.first == button) return c.text;
    }
    return std::string("?");
  };
  CHECK(std::string(kiosk::StaffButtonLabel(StaffButton::kLowVibration, false)) == "Turn on");
  CHECK(caption(StaffButton::kLowVibration) == "Low vibration: off");
  REQUIRE_FALSE(rig.engine.low_vibration());
  CHECK(panel.Press(StaffButton::kLowVibration, 1000 * kMs, rig.engine, rig.log));
  CHECK(rig.engine.low_vibration());
  CHECK(rig.log.Recent().back().Text() == "info staff: low-vibration mode on");
  CHECK(std::string(kiosk::StaffButtonLabel(StaffButton::kLowVibration, true)) == "Turn off");
  CHECK(caption(StaffButton::kLowVibration) == "Low vibration: on");
  CHECK_FALSE(panel.Press(StaffButton::kCount, 3000 * kMs, rig.engine, rig.log));
  // The steps say their size; the captions over each pair say the setting now.
  CHECK(std::string(kiosk::StaffButtonLabel(StaffButton::kVolumeUp, false)) == "+3 dB");
  CHECK(std::string(kiosk::StaffButtonLabel(StaffButton::kVibrationDown, false)) == "-3 dB");
  CHECK(caption(StaffButton::kVolumeDown) == "Volume: 0 dB");
  CHECK(panel.Press(StaffButton::kVolumeUp, 4000 * kMs, rig.engine, rig.log));
  CHECK(caption(StaffButton::kVolumeDown) == "Volume: +3 dB");
  CHECK(caption(StaffButton::kVibrationDown) == "Vibration: 0 dB");
  for (const auto& c : kiosk::StaffButtonCaptions(rig.engine)) {
    CHECK(static_cast<int>(c.first) <= static_cast<int>(c.last));
  }
}

TEST_CASE(
    "staff panel: the text names the version first, marks a device that is not ok, reports each "
    "device by name with the journal's name, the pen, the tokens and the configuration in use "
    "(amber when rejected), and ends with the journal's last lines as the journal has them",
    "[kiosk]") {
  Rig rig;
  rig.board.Set("pen", platform::DeviceState::kMissing, "no pen tablet", "libinput");
  rig.board.Set("audio_out", platform::DeviceState::kOk, "running", "portaudio");
  rig.board.Set("switches", platform::DeviceState::kOk, "keys 1-4", "keyboard");
  rig.board.Set("config", platform::DeviceState::kOk, "configuration file loaded");
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
  // The about lines name the contact scheme each texture runs.
  REQUIRE(find("Contact (contact_bench's choice"));
  CHECK(find("Contact (contact_bench's choice")->text.find(" x1-") != std::string::npos);
  REQUIRE(find("Pen tablet (pen): missing (libinput): no pen tablet"));
  CHECK(find("Pen tablet (pen): ")->warning);
  REQUIRE(find("Sound output (audio_out): ok (portaudio): running; xruns 0"));
  CHECK_FALSE(find("Sound output (audio_out): ")->warning);
  REQUIRE(find("Pen: "));
  CHECK(find("Pen: ")->text == "Pen: pressure 0.50, tilt 30.0 deg, at 100,200 (tablet)");
  REQUIRE(find("Token switches (switches): ok (keyboard): keys 1-4"));
  CHECK(find("Token switches (switches): ")->text.find("; tokens on: none, record button down") !=
        std::string::npos);
  // The configuration: its own line (not a device line), whether it was accepted, its values.
  CHECK_FALSE(find("Configuration file"));
  REQUIRE(find("Configuration: test.toml (accepted)"));
  CHECK_FALSE(find("Configuration: ")->warning);
  REQUIRE(find("In use: "));
  CHECK(
      find("In use: ")->text.find("output 'default', microphone 'default', 48000 Hz, 128 frames") !=
      std::string::npos);
  CHECK(find("In use: ")->text.find("sound +12 dB, vibration +39 dB, low vibration -12 dB") !=
        std::string::npos);
  REQUIRE(find("Usage: visits 0, recordings 0 (0 failed), strokes: "));
  // One label style: every line but the title and the journal's reads "Label: ...", with the
  // label in sentence case.
  for (const auto& line : lines) {
    if (&line == &lines[0] || line.journal) continue;
    INFO(line.text);
    CHECK(std::isupper(static_cast<unsigned char>(line.text[0])));
    CHECK(line.text.find(": ") != std::string::npos);
  }

  // A rejected configuration's line stands out and says which copy runs.
  rig.board.Set("config", platform::DeviceState::kMissing, "rejected: test.toml:2: x: bad");
  auto rejected = rig.Inputs();
  rejected.config_line = "Configuration: test.toml rejected, running on the last good copy: ...";
  for (const auto& line : kiosk::StaffPanelLines(rejected)) {
    if (line.text.rfind("Configuration: ", 0) == 0) CHECK(line.warning);
  }

  // The text ends with the journal's last lines, exactly as the journal has them (not amber:
  // amber is for states now, not for history).
  for (int i = 0; i < 12; ++i) {
    rig.log.Warn("audio_out", "line " + std::to_string(i) + " /var/lib/sketch-a-scratch/x.toml");
  }
  const auto with_journal = kiosk::StaffPanelLines(rig.Inputs());
  std::vector<std::string> journal;
  for (const auto& line : with_journal) {
    if (line.journal) journal.push_back(line.text);
  }
  REQUIRE(journal.size() == kiosk::kStaffJournalLines);
  CHECK(journal.back() == "warn audio_out: line 11 /var/lib/sketch-a-scratch/x.toml");
  CHECK(journal.front() == "warn audio_out: line 4 /var/lib/sketch-a-scratch/x.toml");
  CHECK_FALSE(with_journal.back().warning);
  CHECK(with_journal.back().journal);
}

// Renders silence; its first call takes `first_ms` (a stream's warm-up: first touches of memory,
// the device starting).
class SlowFirstRenderer final : public platform::AudioRenderer {
 public:
  explicit SlowFirstRenderer(int first_ms) : first_ms_(first_ms) {}
  void Render(float* interleaved, int frames, int channels) noexcept override {
    if (calls_++ == 0) std::this_thread::sleep_for(std::chrono::milliseconds(first_ms_));
    std::fill(interleaved, interleaved + frames * channels, 0.0f);
  }

 private:
  int first_ms_;
  int calls_ = 0;
};

TEST_CASE(
    "staff panel: the audio load is said in words, as a share of the callback's time budget, "
    "and a slow first callback does not stand for the running kiosk's peak",
    "[kiosk]") {
  Rig rig;
  SlowFirstRenderer renderer(200);
  platform::OfflineAudioOutput output(renderer, platform::AudioOutputConfig{});
  auto inputs = rig.Inputs();
  inputs.output = &output;
  const auto load_line = [&] {
    for (const auto& line : kiosk::StaffPanelLines(inputs)) {
      if (line.text.rfind("Audio load: ", 0) == 0) return line.text;
    }
    return std::string();
  };
  CHECK(load_line() == "Audio load: none (no sound output)");
  REQUIRE(output.Start());
  output.RenderBlocks(platform::AudioCallbackCore::kWarmUpCallbacks + 400);
  const auto stats = output.Stats();
  CHECK(stats.max_callback_ns >= 200 * kMs);  // the first callback, as it happened
  // The peak the panel shows is the running kiosk's: silence costs next to nothing (a preempted
  // callback on a busy machine may take a few ms, never the first one's 200).
  CHECK(stats.recent_max_callback_ns < 50 * kMs);
  CHECK(stats.mean_callback_ns < 50 * kMs);
  const std::string line = load_line();
  INFO(line);
  CHECK_THAT(line, Catch::Matches("Audio load: [0-9.]+ % of the time budget, peak [0-9.]+ % in the "
                                  "last 20 s \\(budget 2\\.67 ms a callback: 128 frames at 48000 "
                                  "Hz; over 100 % the sound breaks up\\)"));
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
