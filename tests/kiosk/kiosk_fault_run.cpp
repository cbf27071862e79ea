// Fault injection, the in-process half of one scripted run
// (tests/e2e/kiosk_faults_e2e.sh runs this, then the process-level half with the real binary):
// the kiosk's own control loop body (KioskControl::Step, as app/live_kiosk.cpp runs it) and the
// real KioskEngine, with the platform fakes in place of the devices, go through every fault in
// turn. After each: the loop keeps running, exactly one clear log line said it, the status board
// (what the staff panel lists) shows it, and it recovers when the device returns.
//   start: corrupt kiosk.toml (defaults + "file:line: key: what"), corrupt picture and corrupt
//          material file (the kiosk comes up with the other textures and names the failures),
//          GPIO chip missing (adapter or keys take over)
//   audio device lost and back; tablet unplugged mid-stroke and back; token board (MCP2221A)
//   unplugged and back; disk full while saving counters (RLIMIT_FSIZE) and while logging
//   (/dev/full).
#include <fcntl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <thread>

#include "files/counters_file.h"
#include "files/kiosk_config.h"
#include "kiosk/kiosk_control.h"
#include "kiosk/kiosk_engine.h"
#include "kiosk_test_fakes.h"
#include "platform/audio/audio_output.h"
#include "platform/audio/fake_audio_backend.h"
#include "platform/common/clock.h"
#include "platform/hid/mcp2221.h"
#include "platform/input/switch_factory.h"
#include "platform/pen/pen_source.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;
using namespace sas;
using platform::DeviceState;

namespace {

constexpr std::int64_t kMs = 1'000'000;

using sas::test::TokenBoard;
using sas::test::TokenBoardHid;

// Lines the logger wrote since `from` (its total count) that contain `text`.
int LinesSince(const platform::Logger& log, std::uint64_t from, const std::string& text) {
  const auto recent = log.Recent();
  const std::uint64_t total = log.Count();
  int n = 0;
  for (std::size_t i = 0; i < recent.size(); ++i) {
    const std::uint64_t index = total - recent.size() + i;
    if (index >= from && recent[i].Text().find(text) != std::string::npos) ++n;
  }
  return n;
}

// Polls until the condition holds. The deadline is for a condition that never comes: the threads
// behind it (audio output, device watchers) start late on a busy machine, which is no fault.
bool WaitFor(const std::function<bool()>& condition, const std::function<void()>& step,
             double timeout_s = 120.0) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < deadline) {
    step();
    if (condition()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return condition();
}

double Rms(const std::vector<float>& stereo, std::size_t from_frame) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 2 * from_frame; i < stereo.size(); i += 2, ++n) sum += stereo[i] * stereo[i];
  return n ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
}

std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A copy of the shipped textures (symlinks) with broken_glass's picture truncated and the wood
// material garbled: two of the four fail at start.
void PrepareDamagedTextures(const fs::path& root) {
  const fs::path source = fs::path(kSasSourceDir) / "textures";
  for (const char* key : {"bubble_wrap", "broken_glass", "wooden_board", "cracked_ground"}) {
    fs::create_directories(root / key);
    for (const char* file : {"texture.toml", "picture.png", "height.png"}) {
      fs::create_symlink(source / key / file, root / key / file);
    }
  }
  fs::remove(root / "broken_glass" / "picture.png");
  {
    const std::string png = ReadFile((source / "broken_glass" / "picture.png").string());
    std::ofstream cut(root / "broken_glass" / "picture.png", std::ios::binary);
    cut << png.substr(0, 2000);  // a copy cut short (disk full while it was copied)
  }
  fs::create_directories(root / "materials");
  for (const auto& entry : fs::directory_iterator(source / "materials")) {
    if (entry.path().extension() == ".toml") {
      fs::create_symlink(entry.path(), root / "materials" / entry.path().filename());
    }
  }
  fs::remove(root / "materials" / "wood.toml");
  std::ofstream(root / "materials" / "wood.toml") << "name = \"wood\"\nmodes = [ 1, 2,\n";
}

}  // namespace

TEST_CASE(
    "fault injection: every device fault keeps the kiosk running, is logged once, shown "
    "to staff and recovered from",
    "[kiosk][e2e]") {
  // The live kiosk ignores SIGXFSZ for the same reason (app/live_kiosk.cpp).
  std::signal(SIGXFSZ, SIG_IGN);
  sas::test::TempDir dir;
  PrepareDamagedTextures(dir.path() / "data");
  const std::string state = (dir.path() / "state").string();
  fs::create_directories(state);
  platform::Logger& log = platform::DefaultLogger();  // the engine's and the board's, as live

  // ---- start: corrupt configuration, damaged textures, GPIO chip missing
  const std::string config_path =
      dir.Write("kiosk.toml", "[audio]\nbuffer_frames = 3\n[session]\nidle_timeout_s = 30\n");
  const std::uint64_t at_start = log.Count();
  const auto loaded = kiosk::LoadKioskConfigWithFallback(
      config_path, (fs::path(state) / "last-good.toml").string());
  REQUIRE(loaded.source == kiosk::ConfigLoadResult::Source::kDefaults);
  platform::DeviceStatusBoard board(log);  // outlives the engine, which reports to it
  kiosk::ReportConfig(board, loaded);      // as live_kiosk.cpp does, before the window opens
  CHECK(LinesSince(log, at_start,
                   "warn config: missing: rejected: " + config_path +
                       ":2: audio.buffer_frames: 3 is out of range [16, 4096] "
                       "(using the built-in defaults)") == 1);
  CHECK(LinesSince(log, at_start, "config") == 1);
  const std::string staff_line = kiosk::ConfigStatusLine(config_path, loaded);
  CHECK(staff_line.find("rejected, running on the built-in defaults: " + config_path +
                        ":2: audio.buffer_frames") != std::string::npos);

  kiosk::KioskEngineOptions engine_options;
  engine_options.config = loaded.config;
  engine_options.materials_dir = (dir.path() / "data" / "materials").string();
  for (const char* key : {"bubble_wrap", "broken_glass", "wooden_board", "cracked_ground"}) {
    engine_options.texture_paths.push_back((dir.path() / "data" / key / "texture.toml").string());
  }
  engine_options.counters_path = (fs::path(state) / "counters.toml").string();
  engine_options.cues_dir = "/nonexistent";
  kiosk::KioskEngine engine(engine_options);
  engine.SetStatusBoard(&board);
  kiosk::ReportTextures(board, engine);
  REQUIRE(engine.textures().size() == 2);
  CHECK(LinesSince(log, at_start, "error textures: broken_glass left out") == 1);
  CHECK(LinesSince(log, at_start, "error textures: wooden_board left out") == 1);
  {
    const auto textures = board.Get("textures");
    CHECK(textures.state == DeviceState::kMissing);
    CHECK(textures.message.find("2 of 4 textures loaded") != std::string::npos);
    CHECK(textures.message.find("broken_glass: image") != std::string::npos);
    CHECK(textures.message.find("wooden_board: ") != std::string::npos);
    CHECK(textures.message.find("wood.toml") != std::string::npos);
    const auto config = board.Get("config");
    CHECK(config.state == DeviceState::kMissing);
    CHECK(config.message.find("rejected: " + config_path + ":2: audio.buffer_frames") !=
          std::string::npos);
    CHECK(config.message.find("(using the built-in defaults)") != std::string::npos);
  }

  // Audio: the fake device.
  platform::FakeAudioStreamBackend::Shared device;
  platform::AudioOutputConfig output_config;
  output_config.reopen_backoff_initial_s = 0.05;
  output_config.reopen_backoff_max_s = 0.2;
  output_config.stall_timeout_s = 60.0;  // this test is the audio thread: it pumps by hand
  platform::SupervisedAudioOutput output(std::make_unique<platform::FakeAudioStreamBackend>(device),
                                         engine.audio(), output_config, board);
  REQUIRE(output.Start());
  // Pen: the fake tablet.
  auto pen_owned = platform::OpenPen({}, board, std::make_unique<platform::FakePenSource>(true));
  REQUIRE(pen_owned);
  auto* pen = static_cast<platform::FakePenSource*>(pen_owned.get());
  // Switches: GPIO chip missing at start, with and without the token board.
  platform::SwitchesConfig switches_config;
  switches_config.backend = "auto";
  switches_config.gpio.chip = "/nonexistent/gpiochip-missing";
  TokenBoard token_board;
  {
    platform::DeviceStatusBoard alone(log);
    token_board.present = false;
    const std::uint64_t before = log.Count();
    auto keys_only = platform::OpenSwitchInputs(switches_config, alone, nullptr, [&] {
      return token_board.present ? std::make_unique<TokenBoardHid>(token_board) : nullptr;
    });
    CHECK(keys_only.hardware == nullptr);
    CHECK(alone.Get("switches").state == DeviceState::kMissing);
    CHECK(alone.Get("switches").message.find("GPIO chip '/nonexistent/gpiochip-missing'") !=
          std::string::npos);
    CHECK(LinesSince(log, before, "warn switches: missing: GPIO chip") == 1);
    token_board.present = true;
  }
  switches_config.mcp2221.poll_interval_ms = 5;
  switches_config.mcp2221.reopen_interval_ms = 20;
  const std::uint64_t before_switches = log.Count();
  auto switches = platform::OpenSwitchInputs(switches_config, board, nullptr, [&]() {
    return token_board.present ? std::make_unique<TokenBoardHid>(token_board) : nullptr;
  });
  REQUIRE(switches.hardware);
  CHECK(board.Get("switches").state == DeviceState::kOk);
  CHECK(LinesSince(log, before_switches, "GPIO chip '/nonexistent/gpiochip-missing' unusable") ==
        1);

  kiosk::KioskControl control(engine, {&output, pen, &switches}, log);
  std::int64_t now = platform::MonotonicNowNs();
  std::vector<float> played_mark;
  // The visitor's pen leans (a rub): each reading must reach the engine leaning as it was pushed.
  constexpr double kTiltXDeg = 30.0, kTiltYDeg = 25.0;
  int tilted_readings = 0;
  const auto to_engine = [&](const platform::PenReading& e) {
    if (e.HasTilt() && e.tilt_x_deg == kTiltXDeg && e.tilt_y_deg == kTiltYDeg) ++tilted_readings;
    engine.OnPen(e);
  };
  // One pass of the loop and one audio block (2.67 ms of the fake device's thread).
  const auto pass = [&] {
    now += 2667 * 1000;
    control.Step(now, to_engine);
    platform::FakeAudioStreamBackend::Pump(device, 1);
  };
  double x = 300.0;
  const auto stroke_sample = [&](bool down) {
    platform::PenReading e;
    e.time_ns = now;
    e.x_px = (x += 4.0);
    e.y_px = 500.0;
    e.pressure = down ? 0.8 : 0.0;
    e.tilt_x_deg = kTiltXDeg;
    e.tilt_y_deg = kTiltYDeg;
    e.tip_down = down;
    e.in_proximity = true;
    pen->Push(e);
  };
  const auto stroke = [&](int passes) {
    for (int i = 0; i < passes; ++i) {
      stroke_sample(true);
      pass();
    }
    stroke_sample(false);
    pass();
  };
  const auto played_since = [&](std::size_t frame) { return Rms(device.played, frame); };
  for (int i = 0; i < 20; ++i) pass();
  std::size_t mark = device.played.size() / 2;
  stroke(60);
  CHECK(played_since(mark) > 1e-3);  // the kiosk sounds before any fault
  CHECK(tilted_readings == 61);      // 60 readings down and the lift, all still leaning

  // ---- audio device lost and back
  {
    const std::uint64_t before = log.Count();
    platform::FakeAudioStreamBackend::Unplug(device);
    pass();
    CHECK_FALSE(output.Running());
    CHECK(board.Get("audio_out").state == DeviceState::kLost);
    stroke(40);  // the visitor carries on: no callback runs, the engine keeps its queue drained
    engine.OnToken(now, 0);
    for (int i = 0; i < 10; ++i) pass();
    CHECK(LinesSince(log, before, "warn audio_out: lost: stream stopped: device gone") == 1);
    CHECK(LinesSince(log, before, "audio_out") == 1);  // silent retries: no more lines
    platform::FakeAudioStreamBackend::Replug(device);
    REQUIRE(WaitFor([&] { return output.Running(); }, [&] { now += 50 * kMs, pass(); }));
    CHECK(board.Get("audio_out").state == DeviceState::kOk);
    CHECK(board.Get("audio_out").reconnects == 1);
    CHECK(LinesSince(log, before, "info audio_out: ok: reopened") == 1);
    mark = device.played.size() / 2;
    stroke(60);
    CHECK(played_since(mark) > 1e-3);  // sound again on the reopened device
  }

  // ---- tablet unplugged mid-stroke and back
  {
    const std::uint64_t before = log.Count();
    for (int i = 0; i < 40; ++i) {
      stroke_sample(true);
      pass();
    }
    CHECK_FALSE(control.PointerActive());
    pen->Unplug(board);  // as libinput's DEVICE_REMOVED: no tip-up will come
    pass();
    CHECK(board.Get("pen").state == DeviceState::kLost);
    CHECK(control.PointerActive());  // mouse/touch stand in
    CHECK(LinesSince(log, before, "warn pen: lost: pen tablet 'fake tablet' unplugged") == 1);
    // The stroke was lifted: the sound decays to silence instead of scraping on forever.
    for (int i = 0; i < 600; ++i) pass();
    mark = device.played.size() / 2;
    for (int i = 0; i < 40; ++i) pass();
    CHECK(played_since(mark) < 1e-4);
    pen->Replug(board);
    pass();
    CHECK(board.Get("pen").state == DeviceState::kOk);
    CHECK_FALSE(control.PointerActive());
    CHECK(LinesSince(log, before, "info pen: ok: pen tablet 'fake tablet' back") == 1);
    mark = device.played.size() / 2;
    stroke(60);
    CHECK(played_since(mark) > 1e-3);
  }

  // ---- token board unplugged and back; a token placed afterwards still switches the texture
  {
    const std::uint64_t before = log.Count();
    token_board.present = false;
    REQUIRE(WaitFor([&] { return board.Get("switches").state == DeviceState::kLost; }, pass));
    CHECK(LinesSince(log, before, "warn switches: lost: MCP2221A adapter unplugged") == 1);
    stroke(20);  // the kiosk goes on meanwhile
    token_board.present = true;
    REQUIRE(WaitFor([&] { return board.Get("switches").state == DeviceState::kOk; }, pass));
    CHECK(LinesSince(log, before, "info switches: ok: MCP2221A adapter back") == 1);
    CHECK(LinesSince(log, before, "switches") == 2);
    const int cracked = 1;  // token 4's texture is the second loaded one (2 and 3 failed)
    REQUIRE(engine.textures()[cracked].key == "cracked_ground");
    token_board.level[3] = 0;  // token on switch 4
    CHECK(WaitFor([&] { return !engine.surface().voice && engine.surface().texture == cracked; },
                  pass));
    token_board.level[3] = 1;
  }

  // ---- disk full while saving the counters: reported once, counting goes on, saved later
  {
    std::string error;
    REQUIRE(engine.SaveCounters(&error));
    const std::string saved_before = ReadFile(engine_options.counters_path);
    const std::uint64_t before = log.Count();
    rlimit original{};
    REQUIRE(getrlimit(RLIMIT_FSIZE, &original) == 0);
    rlimit tiny = original;
    tiny.rlim_cur = 16;  // any file write past 16 bytes fails (EFBIG), as on a full disk
    REQUIRE(setrlimit(RLIMIT_FSIZE, &tiny) == 0);
    for (int round = 0; round < 3; ++round) {
      stroke(10);
      now += 11'000 * kMs;  // past the engine's 10 s save interval
      pass();
    }
    REQUIRE(setrlimit(RLIMIT_FSIZE, &original) == 0);
    CHECK(board.Get("storage").state == DeviceState::kLost);
    CHECK(board.Get("storage").message.find("usage counters not saved (writing ") !=
          std::string::npos);
    CHECK(LinesSince(log, before, "warn storage: lost: usage counters not saved") == 1);
    CHECK(LinesSince(log, before, "storage") == 1);  // three failed saves, one line
    // The file on disk is the complete previous one, never a piece; no temporary is left.
    CHECK(ReadFile(engine_options.counters_path) == saved_before);
    for (const auto& entry : fs::directory_iterator(state)) {
      CHECK(entry.path().filename().string().rfind(".counters.toml.", 0) != 0);
    }
    stroke(10);
    now += 11'000 * kMs;
    pass();
    CHECK(board.Get("storage").state == DeviceState::kOk);
    CHECK(LinesSince(log, before, "info storage: ok: usage counters saved") == 1);
    kiosk::UsageCounters on_disk;
    REQUIRE(kiosk::LoadCounters(engine_options.counters_path, {"bubble_wrap", "cracked_ground"},
                                &on_disk, &error));
    CHECK(on_disk == engine.session().counters());
  }

  // ---- disk full while logging: the journal's writes fail, the kiosk and the staff panel's
  // ring of recent lines carry on.
  {
    const int saved_stderr = dup(STDERR_FILENO);
    const int full = open("/dev/full", O_WRONLY | O_CLOEXEC);
    REQUIRE(full >= 0);
    dup2(full, STDERR_FILENO);
    platform::Logger full_log;  // takes its private copy of stderr: /dev/full
    dup2(saved_stderr, STDERR_FILENO);
    close(full);
    close(saved_stderr);
    platform::DeviceStatusBoard full_board(full_log);
    platform::FakeAudioStreamBackend::Shared second;
    platform::SupervisedAudioOutput second_output(
        std::make_unique<platform::FakeAudioStreamBackend>(second), engine.audio(), output_config,
        full_board);
    REQUIRE(second_output.Start());
    platform::FakeAudioStreamBackend::Unplug(second);
    second_output.Poll(now += 10 * kMs);
    CHECK(full_board.Get("audio_out").state == DeviceState::kLost);
    REQUIRE(full_log.Recent().size() == 2);
    CHECK(full_log.Recent().back().Text().find("warn audio_out: lost") == 0);
    second_output.Stop();
  }

  // The loop ran through it all: a last stroke sounds and the clean stop saves the counters.
  mark = device.played.size() / 2;
  stroke(60);
  CHECK(played_since(mark) > 1e-3);
  CHECK(control.Shutdown());
  switches.hardware->Stop();
}
