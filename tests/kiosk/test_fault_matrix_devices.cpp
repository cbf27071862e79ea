// The fault matrix, devices: every device the kiosk talks to (audio out, pen tablet,
// GPIO token switches, the MCP2221A USB token board) lost while a visitor is at it and given back,
// or absent at start (the microphone: absent at start only, it is opened once). Each row runs the
// kiosk's own control-loop body (KioskControl::Step, as app/live_kiosk.cpp runs it) with the real
// engine and the platform fakes, and checks the same promise: one journal line at warning priority
// when the device goes (and none while it stays away), the staff status board entry, the loop going
// on with what it has (a stroke during the fault is counted), one info line when the device comes
// back, and the counters saved at the stop equal to what the visitors did. Signals are
// test_fault_matrix_signals.cpp.
#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <catch2/catch.hpp>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "fault_matrix_support.h"
#include "files/counters_file.h"
#include "kiosk/kiosk_control.h"
#include "kiosk/kiosk_engine.h"
#include "kiosk/kiosk_signals.h"
#include "kiosk_test_fakes.h"
#include "platform/audio/audio_input.h"
#include "platform/audio/audio_output.h"
#include "platform/audio/background_audio_output.h"
#include "platform/audio/fake_audio_backend.h"
#include "platform/common/clock.h"
#include "platform/gpio/gpio_switches.h"
#include "platform/hid/mcp2221.h"
#include "platform/input/switch_factory.h"
#include "platform/log/log.h"
#include "platform/pen/pen_source.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;
using namespace sas;
using platform::DeviceState;
using platform::LogLevel;

namespace {

constexpr std::int64_t kMs = 1'000'000;
const std::vector<std::string> kTextureKeys = {"wooden_board", "cracked_ground"};

// A GPIO chip whose lines can fail (as when the board carrying them goes or its driver is
// unbound) and come back. Edges go through a pipe the switch thread polls like libgpiod's line
// fds; a failed chip's fd reports POLLHUP, which the real source also treats as fatal.
struct GpioChip {
  std::atomic<bool> present{true};
  std::array<std::atomic<bool>, platform::kSwitchInputCount> high{true, true, true, true, true};
  std::mutex mutex;
  int write_fd = -1;  // the open source's pipe, -1 when none
};

class ChipSource final : public platform::GpioEventSource {
 public:
  explicit ChipSource(GpioChip& chip) : chip_(&chip) {
    REQUIRE(pipe2(fds_, O_CLOEXEC | O_NONBLOCK) == 0);
    std::lock_guard<std::mutex> lock(chip_->mutex);
    chip_->write_fd = fds_[1];
  }
  ~ChipSource() override {
    std::lock_guard<std::mutex> lock(chip_->mutex);
    if (chip_->write_fd == fds_[1]) chip_->write_fd = -1;
    close(fds_[0]);
    if (fds_[1] >= 0) close(fds_[1]);
  }
  std::vector<pollfd> Fds() const override { return {{fds_[0], POLLIN, 0}}; }
  bool Read(const std::vector<pollfd>& ready, std::vector<platform::RawEdge>& out) override {
    if ((ready[0].revents & (POLLERR | POLLHUP | POLLNVAL)) != 0) return false;
    platform::RawEdge edge;
    while (read(fds_[0], &edge, sizeof edge) == static_cast<ssize_t>(sizeof edge))
      out.push_back(edge);
    return true;
  }
  std::array<bool, platform::kSwitchInputCount> InitialLevels() override {
    std::array<bool, platform::kSwitchInputCount> levels{};
    for (std::size_t i = 0; i < levels.size(); ++i) levels[i] = chip_->high[i].load();
    return levels;
  }
  std::string Describe() const override { return "test chip lines 17 27 22 23 24"; }
  // The chip goes: the writer end closes, so the reader sees POLLHUP.
  void Fail() {
    std::lock_guard<std::mutex> lock(chip_->mutex);
    if (chip_->write_fd == fds_[1]) chip_->write_fd = -1;
    close(fds_[1]);
    fds_[1] = -1;
  }

 private:
  GpioChip* chip_;
  int fds_[2] = {-1, -1};
};

using sas::test::TokenBoard;
using sas::test::TokenBoardHid;

enum class Switches { kGpio, kGpioMissing, kMcp2221, kMcp2221Absent };

struct RigOptions {
  bool audio_present = true;
  bool pen_present = true;
  Switches switches = Switches::kGpio;
  bool microphone_absent = false;  // the real PortAudio input, asked for a device not there
};

// One kiosk: engine, fake devices, control loop, its own journal and status board.
struct Rig {
  explicit Rig(const RigOptions& options) {
    log.SetEchoToStderr(false);
    engine_options.cues_dir = "/nonexistent";
    for (const auto& key : kTextureKeys)
      engine_options.texture_paths.push_back(test::TexturePath(key));
    engine_options.counters_path = dir.file("counters.toml");
    engine = std::make_unique<kiosk::KioskEngine>(engine_options);
    engine->SetStatusBoard(&board);

    device.present = options.audio_present;
    platform::AudioOutputConfig output_config;
    output_config.reopen_backoff_initial_s = 0.05;
    output_config.reopen_backoff_max_s = 0.2;
    output_config.stall_timeout_s = 60.0;  // the test is the device's thread: it pumps by hand
    output = std::make_unique<platform::SupervisedAudioOutput>(
        std::make_unique<platform::FakeAudioStreamBackend>(device), engine->audio(), output_config,
        board);
    output->Start();

    pen_owned = platform::OpenPen(
        {}, board,
        std::make_unique<platform::FakePenSource>(options.pen_present, /*waits_for_tablet=*/true));
    REQUIRE(pen_owned);
    pen = static_cast<platform::FakePenSource*>(pen_owned.get());

    platform::SwitchesConfig config;
    config.mcp2221.poll_interval_ms = 5;
    config.mcp2221.reopen_interval_ms = 20;
    std::unique_ptr<platform::GpioEventSource> source;
    switch (options.switches) {
      case Switches::kGpio:
        config.backend = "gpio";
        source = std::make_unique<ChipSource>(chip);
        gpio_source = static_cast<ChipSource*>(source.get());
        break;
      case Switches::kGpioMissing:
        config.backend = "gpio";
        config.gpio.chip = "/nonexistent/gpiochip-missing";
        break;
      case Switches::kMcp2221Absent:
        token_board.present = false;
        config.backend = "mcp2221";
        break;
      case Switches::kMcp2221:
        config.backend = "mcp2221";
        break;
    }
    switches = platform::OpenSwitchInputs(config, board, std::move(source), [this]() {
      return token_board.present ? std::make_unique<TokenBoardHid>(token_board) : nullptr;
    });
    if (auto* gpio = dynamic_cast<platform::GpioSwitchInput*>(switches.hardware.get())) {
      gpio->SetSourceFactory([this]() -> std::unique_ptr<platform::GpioEventSource> {
        if (!chip.present) throw std::runtime_error("GPIO chip gone");
        auto fresh = std::make_unique<ChipSource>(chip);
        gpio_source = fresh.get();
        return fresh;
      });
    }
    if (options.microphone_absent) {
      // A private ALSA configuration whose only card does not exist, so the sandbox's (or the
      // build machine's) sound cards are never probed; then as app/live_kiosk.cpp does it.
      const std::string conf =
          dir.Write("asound.conf", "pcm.null { type null }\npcm.!default { type hw card 63 }\n");
      setenv("ALSA_CONFIG_PATH", conf.c_str(), 1);
      platform::AudioInputConfig input_config;
      input_config.device = "sas_no_such_microphone";
      microphone = platform::MakePortAudioInput(input_config, {}, board);
      if (microphone->Start()) engine->SetRecorder(&microphone->recorder());
      unsetenv("ALSA_CONFIG_PATH");
    }
    control = std::make_unique<kiosk::KioskControl>(
        *engine, kiosk::KioskDevices{output.get(), pen, &switches, &board}, log);
  }
  ~Rig() {
    if (switches.hardware) switches.hardware->Stop();
    if (microphone) {
      engine->SetRecorder(nullptr);
      microphone->Stop();
    }
  }

  // One pass of the loop and one audio block of the fake device.
  void Pass() {
    now += 2667 * 1000;
    control->Step(now, [this](const platform::PenReading& e) { engine->OnPen(e); });
    platform::FakeAudioStreamBackend::Pump(device, 1);
  }
  // A stroke through the tablet when it is connected, else through the mouse (the live loop
  // hands pointer events to the engine while PointerActive()).
  void Stroke() {
    for (int i = 0; i <= 20; ++i) {
      const bool down = i < 20;
      if (control->PointerActive()) {
        platform::PenReading input;
        input.time_ns = now;
        input.x_px = 300.0 + 4.0 * i;
        input.y_px = 400.0;
        input.tip_down = down;
        input.pressure = down ? 0.8 : 0.0;
        engine->OnPen(input);
      } else {
        platform::PenReading e;
        e.time_ns = now;
        e.x_px = 300.0 + 4.0 * i;
        e.y_px = 400.0;
        e.pressure = down ? 0.8 : 0.0;
        e.tip_down = down;
        e.in_proximity = true;
        pen->Push(e);
      }
      Pass();
    }
    ++strokes;
  }
  // Passes (in real time: device threads run on their own clocks) until `done`; the 60 s bound
  // only stops a broken run, a busy host just takes longer.
  bool PassUntil(const std::function<bool()>& done) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < deadline) {
      Pass();
      if (done()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return done();
  }
  double RmsSince(std::size_t sample) const {
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t i = sample; i < device.played.size(); i += 2, ++n) {
      sum += static_cast<double>(device.played[i]) * device.played[i];
    }
    return n ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
  }
  // Journal lines since `from` (the log's count then) that mention `device` / contain `text`.
  int Lines(std::uint64_t from, const std::string& text, LogLevel level) const {
    const auto recent = log.Recent();
    const std::uint64_t total = log.Count();
    int n = 0;
    for (std::size_t i = 0; i < recent.size(); ++i) {
      if (total - recent.size() + i < from) continue;
      if (recent[i].level == level && recent[i].Text().find(text) != std::string::npos) ++n;
    }
    return n;
  }
  int LinesAbout(std::uint64_t from, const std::string& component) const {
    const auto recent = log.Recent();
    const std::uint64_t total = log.Count();
    int n = 0;
    for (std::size_t i = 0; i < recent.size(); ++i) {
      if (total - recent.size() + i >= from && recent[i].component == component) ++n;
    }
    return n;
  }

  sas::test::TempDir dir;
  platform::Logger log;
  platform::DeviceStatusBoard board{log};
  kiosk::KioskEngineOptions engine_options;
  std::unique_ptr<kiosk::KioskEngine> engine;
  platform::FakeAudioStreamBackend::Shared device;
  std::unique_ptr<platform::SupervisedAudioOutput> output;
  std::unique_ptr<platform::PenSource> pen_owned;
  platform::FakePenSource* pen = nullptr;
  GpioChip chip;
  std::atomic<ChipSource*> gpio_source{nullptr};
  TokenBoard token_board;
  platform::SwitchInputs switches;
  std::unique_ptr<platform::AudioInput> microphone;
  std::unique_ptr<kiosk::KioskControl> control;
  // The devices' supervisors time their retries on CLOCK_MONOTONIC, so the loop's clock starts
  // there (and runs faster: one 2.67 ms audio block per pass).
  std::int64_t now = platform::MonotonicNowNs();
  int strokes = 0;
};

// What a row does to its device and what it expects the journal and the board to say.
struct DeviceRow {
  const char* name;
  RigOptions options;
  const char* device;                // status board key and journal component
  DeviceState fault_state;           // the board while the device is away
  const char* fault_line;            // the one warning line (contains)
  std::function<void(Rig&)> fault;   // null: absent from the start
  std::function<bool(Rig&)> during;  // checks while away (what still works); true = ok
  std::function<void(Rig&)> back;    // the device returns
  const char* back_line;             // the one info line (contains)
  std::function<bool(Rig&)> after;   // checks once back; true = ok
};

// A stroke after the fault still sounds.
bool Sounds(Rig& rig) {
  const std::size_t mark = rig.device.played.size();
  rig.Stroke();
  return rig.RmsSince(mark) > 1e-3;
}

// Placing `token` shows `texture` (not the voice), then the token is lifted again.
std::function<bool(Rig&)> TokenSwitches(int token, int texture) {
  return [token, texture](Rig& rig) {
    rig.switches.keyboard->OnKey(static_cast<char>('1' + token), true, rig.now);
    rig.Pass();
    const bool shown = !rig.engine->surface().voice && rig.engine->surface().texture == texture;
    rig.switches.keyboard->OnKey(static_cast<char>('1' + token), true, rig.now);  // lift it
    rig.Pass();
    return shown;
  };
}

// The sound output: lost while running, and absent at start.
std::vector<DeviceRow> AudioRows() {
  return {
      {"audio out lost mid-visit, back",
       {},
       "audio_out",
       DeviceState::kLost,
       "warn audio_out: lost: stream stopped: device gone",
       [](Rig& rig) {
         platform::FakeAudioStreamBackend::Unplug(rig.device);
         rig.Pass();
       },
       [](Rig& rig) {
         // Silent, retried with back-off: the loop runs, no further line per attempt.
         for (int i = 0; i < 200; ++i) rig.Pass();
         return !rig.output->Running() && rig.device.open_attempts > 2;
       },
       [](Rig& rig) {
         platform::FakeAudioStreamBackend::Replug(rig.device);
         rig.PassUntil([&] { return rig.output->Running(); });
       },
       "info audio_out: ok: reopened",
       Sounds},
      {"audio out absent at start, plugged in later",
       {false, true, Switches::kGpio},
       "audio_out",
       DeviceState::kMissing,
       "warn audio_out: missing: output device 'default' not found",
       nullptr,
       [](Rig& rig) { return !rig.output->Running(); },
       [](Rig& rig) {
         platform::FakeAudioStreamBackend::Replug(rig.device);
         rig.PassUntil([&] { return rig.output->Running(); });
       },
       "info audio_out: ok:",
       Sounds},
  };
}

// The pen tablet: unplugged mid-stroke, and absent at start.
std::vector<DeviceRow> PenRows() {
  return {
      {"pen tablet unplugged mid-stroke, back",
       {},
       "pen",
       DeviceState::kLost,
       "warn pen: lost: pen tablet 'fake tablet' unplugged",
       [](Rig& rig) {
         platform::PenReading e;
         e.time_ns = rig.now;
         e.x_px = 500.0;
         e.y_px = 500.0;
         e.pressure = 0.8;
         e.tip_down = true;
         e.in_proximity = true;
         rig.pen->Push(e);
         rig.Pass();
         rig.pen->Unplug(rig.board);  // libinput's DEVICE_REMOVED: no tip-up will come
         rig.Pass();
         ++rig.strokes;  // the stroke the visitor was drawing, lifted by the loop
       },
       [](Rig& rig) {
         // The stroke was lifted (the sound decays) and the mouse stands in.
         for (int i = 0; i < 600; ++i) rig.Pass();
         const std::size_t mark = rig.device.played.size();
         for (int i = 0; i < 40; ++i) rig.Pass();
         return rig.RmsSince(mark) < 1e-4 && rig.control->PointerActive();
       },
       [](Rig& rig) {
         rig.pen->Replug(rig.board);
         rig.Pass();
       },
       "info pen: ok: pen tablet 'fake tablet' back",
       [](Rig& rig) { return !rig.control->PointerActive(); }},
      {"pen tablet absent at start, plugged in later",
       {true, false, Switches::kGpio},
       "pen",
       DeviceState::kMissing,
       "warn pen: missing: no pen tablet",
       nullptr,
       [](Rig& rig) { return rig.control->PointerActive(); },
       [](Rig& rig) {
         rig.pen->Replug(rig.board);
         rig.Pass();
       },
       "info pen: ok:",
       [](Rig& rig) { return !rig.control->PointerActive(); }},
  };
}

// The GPIO token lines and chip, and the microphone.
std::vector<DeviceRow> GpioAndMicrophoneRows() {
  return {
      {"GPIO token lines lost (POLLHUP), back",
       {},
       "switches",
       DeviceState::kLost,
       "warn switches: lost: GPIO lines lost (test chip",
       [](Rig& rig) {
         rig.chip.present = false;
         rig.gpio_source.load()->Fail();
         rig.PassUntil([&] { return rig.board.Get("switches").state == DeviceState::kLost; });
       },
       [](Rig& rig) {
         // The switch thread stays alive for the watchdog, and keys 1-4 still switch.
         const std::int64_t beat = rig.switches.hardware->HeartbeatNs();
         std::this_thread::sleep_for(std::chrono::milliseconds(600));
         return rig.switches.hardware->HeartbeatNs() > beat && TokenSwitches(1, 1)(rig);
       },
       [](Rig& rig) {
         rig.chip.high[1] = false;  // a token placed on switch 2 while the lines were away
         rig.chip.present = true;
         rig.PassUntil([&] { return rig.board.Get("switches").state == DeviceState::kOk; });
       },
       "info switches: ok: GPIO lines back",
       [](Rig& rig) {
         // The token placed meanwhile counts now; lifting it afterwards is seen on the new lines.
         if (!rig.PassUntil([&] { return rig.engine->surface().texture == 1; })) return false;
         rig.chip.high[1] = true;
         {
           std::lock_guard<std::mutex> lock(rig.chip.mutex);
           const platform::RawEdge edge{platform::MonotonicNowNs(), 1, true};
           if (write(rig.chip.write_fd, &edge, sizeof edge) != static_cast<ssize_t>(sizeof edge))
             return false;
         }
         return rig.PassUntil([&] { return rig.engine->surface().texture == 0; });
       }},
      {"GPIO chip missing at start (keys 1-4 stand in)",
       {true, true, Switches::kGpioMissing},
       "switches",
       DeviceState::kMissing,
       "warn switches: missing: GPIO chip '/nonexistent/gpiochip-missing' unusable",
       nullptr,
       TokenSwitches(1, 1),
       nullptr,
       nullptr,
       nullptr},
      {"microphone absent at start (recording disabled)",
       {true, true, Switches::kGpio, true},
       "audio_in",
       DeviceState::kMissing,
       "warn audio_in: missing: ",
       nullptr,
       [](Rig& rig) {
         // The record button (press: a spoken countdown, then the take) ends in "recording
         // unavailable", counted as a failed recording, instead of a silent take; the visit goes
         // on. Up to 20 s of loop passes for the countdown.
         const std::uint64_t from = rig.log.Count();
         const auto failed = rig.engine->session().counters().failed_recordings;
         rig.switches.keyboard->OnKey('r', true, rig.now);
         rig.Pass();
         rig.switches.keyboard->OnKey('r', false, rig.now);
         const auto said = [&] {
           return rig.Lines(from, "info session: recording unavailable (no microphone)",
                            LogLevel::kInfo);
         };
         for (int i = 0; i < 7500 && said() == 0; ++i) rig.Pass();
         return !rig.engine->recorder_present() && said() == 1 &&
                rig.engine->session().counters().failed_recordings == failed + 1;
       },
       // No "back": a microphone plugged in after start is not taken up (the input is opened
       // once, at start); the row checks what the kiosk keeps doing without one.
       nullptr,
       nullptr,
       nullptr},
  };
}

// The MCP2221A token board: unplugged, and absent at start.
std::vector<DeviceRow> TokenBoardRows() {
  return {
      {"MCP2221A token board unplugged, back",
       {true, true, Switches::kMcp2221},
       "switches",
       DeviceState::kLost,
       "warn switches: lost: MCP2221A adapter unplugged",
       [](Rig& rig) {
         rig.token_board.present = false;
         rig.PassUntil([&] { return rig.board.Get("switches").state == DeviceState::kLost; });
       },
       TokenSwitches(1, 1),
       [](Rig& rig) {
         rig.token_board.present = true;
         rig.PassUntil([&] { return rig.board.Get("switches").state == DeviceState::kOk; });
       },
       "info switches: ok: MCP2221A adapter back",
       [](Rig& rig) {
         rig.token_board.level[1] = 0;  // a token on pad 2 after the board came back
         const bool shown = rig.PassUntil([&] { return rig.engine->surface().texture == 1; });
         rig.token_board.level[1] = 1;
         return shown && rig.PassUntil([&] { return rig.engine->surface().texture == 0; });
       }},
      {"MCP2221A token board absent at start, plugged in later",
       {true, true, Switches::kMcp2221Absent},
       "switches",
       DeviceState::kMissing,
       "warn switches: missing: ",
       nullptr,
       TokenSwitches(1, 1),
       [](Rig& rig) {
         rig.token_board.present = true;
         rig.PassUntil([&] { return rig.board.Get("switches").state == DeviceState::kOk; });
       },
       "info switches: ok: MCP2221A adapter",
       [](Rig& rig) {
         rig.token_board.level[1] = 0;
         const bool shown = rig.PassUntil([&] { return rig.engine->surface().texture == 1; });
         rig.token_board.level[1] = 1;
         return shown;
       }},
  };
}

std::vector<DeviceRow> DeviceRows() {
  std::vector<DeviceRow> rows;
  for (auto part : {AudioRows(), PenRows(), GpioAndMicrophoneRows(), TokenBoardRows()}) {
    for (auto& row : part) rows.push_back(std::move(row));
  }
  return rows;
}

kiosk::UsageCounters OnDisk(const std::string& path) {
  kiosk::UsageCounters counters;
  std::string error;
  kiosk::LoadCounters(path, kTextureKeys, &counters, &error);
  return counters;
}

std::uint64_t Strokes(const kiosk::UsageCounters& counters) {
  std::uint64_t n = counters.voice_strokes;
  for (const auto s : counters.strokes_per_texture) n += s;
  return n;
}

}  // namespace

TEST_CASE(
    "fault matrix: devices - each device lost (or absent) and back is one warning and one info "
    "line, shown to staff, the kiosk runs on with what it has and every stroke is saved",
    "[kiosk][faults]") {
  int rows = 0;
  for (const auto& row : DeviceRows()) {
    ++rows;
    INFO("row: device, " << row.name);
    // The rig's start writes the "absent at start" line; the others start clean.
    Rig rig(row.options);
    const std::uint64_t at_start = 0;
    for (int i = 0; i < 20; ++i) rig.Pass();
    if (row.fault) {
      CHECK(rig.board.Get(row.device).state == DeviceState::kOk);
      rig.Stroke();  // a visitor at it when the fault comes
    }
    const std::uint64_t before = row.fault ? rig.log.Count() : at_start;
    if (row.fault) row.fault(rig);

    const auto status = rig.board.Get(row.device);
    CHECK(status.state == row.fault_state);
    CHECK(rig.Lines(before, row.fault_line, LogLevel::kWarn) == 1);
    rig.Stroke();  // the kiosk goes on: this stroke counts
    CHECK(row.during(rig));
    // One line for the state change, none per retry, callback or pass.
    CHECK(rig.LinesAbout(before, row.device) == 1);
    CHECK(rig.board.Get(row.device).state == row.fault_state);

    if (row.back) {
      const std::uint64_t at_back = rig.log.Count();
      row.back(rig);
      CHECK(rig.board.Get(row.device).state == DeviceState::kOk);
      CHECK(rig.Lines(at_back, row.back_line, LogLevel::kInfo) == 1);
      CHECK(rig.LinesAbout(at_back, row.device) == 1);
      CHECK(row.after(rig));
    }
    rig.Stroke();

    // Nothing lost: what the stop saves is what the visitors did.
    CHECK(rig.control->Shutdown());
    const auto saved = OnDisk(rig.engine_options.counters_path);
    CHECK(saved == rig.engine->session().counters());
    CHECK(Strokes(saved) == static_cast<std::uint64_t>(rig.strokes));
    CHECK(saved.sessions >= 1);
  }
  CHECK(rows == 9);
}
