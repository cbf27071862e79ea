// The kiosk's control loop body (KioskControl) with the real engine and fake devices: what a
// SIGHUP does to the usage counters, a tablet plugged in after start, input that piled up before
// the loop ran (taken a bounded share per pass); and the process's signal set-up (kiosk_signals.h).
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "files/counters_file.h"
#include "kiosk/device_configs.h"
#include "kiosk/kiosk_control.h"
#include "kiosk/kiosk_engine.h"
#include "kiosk/kiosk_signals.h"
#include "platform/audio/audio_input.h"
#include "platform/audio/audio_output.h"
#include "platform/pen/pen_source.h"
#include "support/temp_dir.h"
#include "tablet_rig.h"

using namespace sas;
using test::QuietLogger;
using test::TabletRig;
using test::VirtualClockOptions;

namespace {

constexpr std::int64_t kMs = 1'000'000;
const std::vector<std::string> kCounterKeys = {"bubble_wrap", "broken_glass", "wooden_board",
                                               "cracked_ground"};

kiosk::UsageCounters OnDisk(const std::string& path) {
  kiosk::UsageCounters counters;
  std::string error;
  REQUIRE(kiosk::LoadCounters(path, kCounterKeys, &counters, &error));
  return counters;
}

void Stroke(kiosk::KioskEngine& engine, std::int64_t t_ns) {
  for (int i = 0; i < 3; ++i) {
    platform::PenReading pen;
    pen.time_ns = t_ns + i * 3 * kMs;
    pen.x_px = 500.0 + 20.0 * i;
    pen.y_px = 500.0;
    pen.tip_down = i < 2;
    pen.pressure = pen.tip_down ? 0.8 : 0.0;
    pen.origin = platform::PenOrigin::kTablet;
    engine.OnPen(pen);
  }
}

}  // namespace

TEST_CASE(
    "control: SIGHUP saves the usage counters at once instead of at the next periodic save, "
    "says so in one info line and the loop goes on",
    "[kiosk]") {
  sas::test::TempDir dir;
  kiosk::KioskEngineOptions options;
  options.virtual_clock = true;
  options.cues_dir = "/nonexistent";
  options.counters_path = dir.file("counters.toml");
  kiosk::KioskEngine engine(options);
  platform::AudioOutputConfig output_config;
  platform::OfflineAudioOutput output(engine.audio(), output_config);
  REQUIRE(output.Start());
  platform::SwitchInputs switches;  // keys only
  platform::Logger log;
  log.SetEchoToStderr(false);
  kiosk::KioskControl control(engine, {&output, nullptr, &switches}, log);
  const auto on_pen = [](const platform::PenReading&) {};

  std::int64_t now = 1000 * kMs;
  Stroke(engine, now);
  control.Step(now, on_pen);  // the first change is saved at once
  const auto first = OnDisk(options.counters_path);
  REQUIRE(first == engine.session().counters());

  now += 1000 * kMs;
  Stroke(engine, now);
  control.Step(now, on_pen);  // within the 10 s interval: in memory only
  REQUIRE(engine.session().counters() != first);
  REQUIRE(OnDisk(options.counters_path) == first);

  const auto lines_before = log.Count();
  CHECK(control.Hangup());
  CHECK(OnDisk(options.counters_path) == engine.session().counters());
  REQUIRE(log.Count() == lines_before + 1);
  const auto line = log.Recent().back();
  CHECK(line.level == platform::LogLevel::kInfo);
  CHECK(line.Text() ==
        "info kiosk: SIGHUP: usage counters saved; the configuration is read at start (restart "
        "the unit to apply changes)");

  // The loop carries on counting after it.
  now += 1000 * kMs;
  Stroke(engine, now);
  control.Step(now, on_pen);
  CHECK(engine.session().counters() != OnDisk(options.counters_path));
  CHECK(control.Shutdown());  // and the stop saves the rest
  CHECK(OnDisk(options.counters_path) == engine.session().counters());
}

TEST_CASE(
    "control: a microphone that stops sending sound mid-recording ends the take as 'no "
    "microphone' and turns recording off, and when its sound comes back recording works again",
    "[kiosk]") {
  kiosk::KioskEngineOptions options = VirtualClockOptions();
  options.countdown_s = 0.5;
  kiosk::KioskEngine engine(options);
  platform::FakeAudioInput mic(kiosk::RecorderConfigFor(options.config));
  REQUIRE(mic.Start());
  engine.SetRecorder(&mic.recorder());
  platform::OfflineAudioOutput output(engine.audio(), platform::AudioOutputConfig{});
  REQUIRE(output.Start());
  platform::SwitchInputs switches;
  QuietLogger log;
  kiosk::KioskControl control(engine, {&output, nullptr, &switches, nullptr, &mic}, log);
  const auto on_pen = [](const platform::PenReading&) {};
  std::vector<float> voice(480);  // 10 ms of a 200 Hz tone per loop pass
  for (std::size_t i = 0; i < voice.size(); ++i) {
    voice[i] = static_cast<float>(
        0.3 * std::sin(2.0 * 3.14159265358979 * 200.0 * static_cast<double>(i) / 48000.0));
  }
  std::int64_t now = 1000 * kMs;
  // Passes of 10 ms for `seconds`, the microphone feeding sound or not.
  const auto run = [&](double seconds, bool feeding) {
    for (int i = 0; i < static_cast<int>(seconds * 100.0); ++i) {
      if (feeding) mic.Feed(voice.data(), voice.size());
      control.Step(now, on_pen);
      now += 10 * kMs;
    }
  };
  const auto press_record = [&] {
    engine.OnRecordButton(now, true);
    run(0.05, true);
    engine.OnRecordButton(now, false);
  };
  run(0.5, true);
  REQUIRE(engine.recorder_present());
  press_record();
  run(1.0, true);  // the countdown, then recording
  REQUIRE(engine.session().mode() == kiosk::SessionMode::kRecording);
  const auto failed = engine.session().counters().failed_recordings;

  run(0.9, false);  // pulled out: under a second of silence from the device is not yet a loss
  CHECK(engine.session().mode() == kiosk::SessionMode::kRecording);
  run(0.2, false);
  CHECK(engine.session().mode() != kiosk::SessionMode::kRecording);
  CHECK_FALSE(engine.recorder_present());
  CHECK_FALSE(engine.has_voice());
  CHECK(engine.session().counters().failed_recordings == failed + 1);
  press_record();  // the button now says there is no microphone
  run(1.0, false);
  CHECK(engine.session().mode() != kiosk::SessionMode::kRecording);

  run(0.1, true);  // plugged back in
  CHECK(engine.recorder_present());
  press_record();
  run(1.0, true);
  CHECK(engine.session().mode() == kiosk::SessionMode::kRecording);
}

TEST_CASE(
    "microphone watch: a started input is lost after 1 s without a callback and back at the next "
    "one, and a process that stood still does not lose it",
    "[kiosk]") {
  platform::InputWatch watch;
  const std::int64_t ms = 1'000'000;
  std::int64_t now = 5000 * ms;
  CHECK(watch.Update(0, now));  // the start: delivering until shown otherwise
  std::uint64_t count = 0;
  for (int i = 0; i < 10; ++i) CHECK(watch.Update(++count, now += 100 * ms));
  // No callback from here: still delivering at 0.9 s, lost at 1 s, and it stays lost.
  for (int i = 0; i < 9; ++i) CHECK(watch.Update(count, now += 100 * ms));
  CHECK_FALSE(watch.Update(count, now += 100 * ms));
  CHECK_FALSE(watch.Update(count, now += 100 * ms));
  CHECK_FALSE(watch.Update(count, now += 2000 * ms));  // a long pass does not bring it back
  CHECK(watch.Update(++count, now += 100 * ms));       // the next callback does
  // The whole process stopped for 5 s (no pass, no callback): not a loss once it runs again.
  CHECK(watch.Update(count, now += 5000 * ms));
  CHECK(watch.Update(++count, now += 10 * ms));
  watch.Reset();  // a restart starts afresh, whatever the count
  CHECK(watch.Update(count, now += 100 * ms));
}

TEST_CASE(
    "signals: SIGHUP and SIGTERM only raise flags for the loop, and a write into a closed pipe "
    "fails with EPIPE instead of ending the process",
    "[kiosk]") {
  struct sigaction saved[5]{};
  const int signals[5] = {SIGHUP, SIGPIPE, SIGXFSZ, SIGTERM, SIGINT};
  for (int i = 0; i < 5; ++i) sigaction(signals[i], nullptr, &saved[i]);
  kiosk::CatchHangupAndIgnoreWriteSignals();
  kiosk::CatchStopSignals();

  CHECK_FALSE(kiosk::TakeHangupRequest());
  raise(SIGHUP);
  raise(SIGHUP);
  CHECK(kiosk::TakeHangupRequest());  // two before the loop came round: one save
  CHECK_FALSE(kiosk::TakeHangupRequest());
  CHECK_FALSE(kiosk::StopRequested());
  raise(SIGTERM);
  CHECK(kiosk::StopRequested());

  // From a thread of its own (some audio libraries block SIGPIPE in the thread that set them up,
  // a device thread does not): without the ignore, this write would end the process.
  int fds[2];
  REQUIRE(pipe2(fds, O_CLOEXEC) == 0);
  close(fds[0]);
  ssize_t written = 0;
  int error = 0;
  std::thread writer([&] {
    sigset_t none;
    sigemptyset(&none);
    pthread_sigmask(SIG_SETMASK, &none, nullptr);
    written = write(fds[1], "x", 1);
    error = errno;
  });
  writer.join();
  close(fds[1]);
  CHECK(written == -1);
  CHECK(error == EPIPE);

  for (int i = 0; i < 5; ++i) sigaction(signals[i], &saved[i], nullptr);
}

TEST_CASE(
    "control: with no tablet at start mouse/touch drive the kiosk, and a tablet plugged in later "
    "takes over with its events reaching the loop",
    "[kiosk]") {
  TabletRig rig(std::make_unique<platform::FakePenSource>(false, /*waits_for_tablet=*/true));
  std::vector<platform::PenReading> seen;
  const auto on_pen = [&](const platform::PenReading& e) { seen.push_back(e); };

  rig.control.Step(1000 * kMs, on_pen);
  CHECK(rig.control.PointerActive());
  CHECK(rig.board.Get("pen").state == platform::DeviceState::kMissing);

  rig.fake->Replug(rig.board);
  platform::PenReading e;
  e.time_ns = 1001 * kMs;
  e.kind = platform::PenReadingKind::kTipDown;
  e.tip_down = e.in_proximity = true;
  e.pressure = 0.5;
  REQUIRE(rig.fake->Push(e));
  rig.control.Step(1002 * kMs, on_pen);
  CHECK_FALSE(rig.control.PointerActive());
  CHECK(rig.board.Get("pen").state == platform::DeviceState::kOk);
  REQUIRE(seen.size() == 1);
  CHECK(seen[0].time_ns == 1001 * kMs);
}

TEST_CASE(
    "a corrupt configuration at start is one journal line and a staff status naming file, "
    "line, key and the fallback in use",
    "[kiosk]") {
  sas::test::TempDir dir;
  const auto path = dir.Write("kiosk.toml", "[gains]\nsound_gain_db = 12\n");
  const auto last_good = dir.file("last-good.toml");
  sas::platform::Logger log;
  log.SetEchoToStderr(false);
  sas::platform::DeviceStatusBoard board(log);

  // Garbled by an editor: a syntax error on line 3. The copy from the good start is used.
  REQUIRE(sas::kiosk::LoadKioskConfigWithFallback(path, last_good).problem.empty());
  dir.Write("kiosk.toml", "[gains]\nsound_gain_db = 12\nhaptic_gain_db = = 3\n");
  const auto loaded = sas::kiosk::LoadKioskConfigWithFallback(path, last_good);
  sas::kiosk::ReportConfig(board, loaded);
  const auto status = board.Get("config");
  CHECK(status.state == sas::platform::DeviceState::kMissing);
  CHECK_THAT(status.message, Catch::StartsWith("rejected: " + path + ":3:") &&
                                 Catch::Contains("(using the last good configuration)"));
  REQUIRE(log.Recent().size() == 1);
  CHECK_THAT(log.Recent()[0].Text(),
             Catch::StartsWith("warn config: missing: rejected: " + path + ":3:"));
  CHECK_THAT(sas::kiosk::ConfigStatusLine(path, loaded),
             Catch::StartsWith("Configuration: " + path +
                               " rejected, running on the last good copy: " + path + ":3:"));

  // No last good copy: the built-in defaults, and it says so, key included.
  sas::platform::DeviceStatusBoard fresh(log);
  dir.Write("kiosk.toml", "[session]\nidle_timeout_s = \"soon\"\n");
  const auto defaults = sas::kiosk::LoadKioskConfigWithFallback(path, dir.file("none.toml"));
  CHECK(defaults.source == sas::kiosk::ConfigLoadResult::Source::kDefaults);
  CHECK(defaults.config.idle_timeout_s == sas::kiosk::KioskConfig{}.idle_timeout_s);
  sas::kiosk::ReportConfig(fresh, defaults);
  CHECK_THAT(fresh.Get("config").message,
             Catch::StartsWith("rejected: " + path + ":2: session.idle_timeout_s: ") &&
                 Catch::EndsWith("(using the built-in defaults)"));
  CHECK_THAT(sas::kiosk::ConfigStatusLine(path, defaults),
             Catch::Contains(" rejected, running on the built-in defaults: " + path +
                             ":2: session.idle_timeout_s: "));
}

namespace {

// One stroke of a tablet pen leaning `tilt_x_deg`, on a fresh kiosk, rendered block by block:
// pushed into the pen source and carried by the control loop (`through_pen_source`), or handed to
// the engine directly as the readings the source hands out.
std::vector<float> TabletStroke(double tilt_x_deg, bool through_pen_source) {
  TabletRig rig(std::make_unique<platform::FakePenSource>(true));
  const platform::AudioOutputConfig output_config;
  const auto block_ns = static_cast<std::int64_t>(
      std::llround(output_config.frames_per_buffer * 1e9 / output_config.sample_rate_hz));
  for (int i = 0; i < 80; ++i) {
    const std::int64_t now = i * block_ns;
    platform::PenReading reading;
    reading.time_ns = now;
    reading.x_px = 400.0 + 6.0 * i;
    reading.y_px = 500.0;
    reading.tip_down = i < 60;
    reading.in_proximity = true;
    reading.pressure = reading.tip_down ? 0.7 : 0.0;
    reading.tilt_x_deg = tilt_x_deg;
    if (through_pen_source) {
      REQUIRE(rig.fake->Push(reading));
      rig.control.Step(now, [&](const platform::PenReading& r) { rig.engine.OnPen(r); });
    } else {
      reading.origin = platform::PenOrigin::kTablet;
      rig.engine.OnPen(reading);
      rig.control.Step(now, [](const platform::PenReading&) {});
    }
    rig.output.RenderBlocks(1);
  }
  return rig.output.buffer();
}

}  // namespace

TEST_CASE(
    "control: a leaning tablet's tilt reaches the probe - a stroke through the pen source and "
    "the loop sounds exactly as its readings do handed to the engine, and unlike the same stroke "
    "upright",
    "[kiosk]") {
  const std::vector<float> leaning = TabletStroke(50.0, true);
  const std::vector<float> upright = TabletStroke(0.0, true);
  const std::vector<float> direct = TabletStroke(50.0, false);
  REQUIRE(leaning.size() == direct.size());
  CHECK(leaning == direct);
  CHECK(leaning != upright);
}

TEST_CASE(
    "control: a flood of pen readings queued before the loop ran is taken at most 64 a pass, in "
    "order with its own timestamps and none lost, and a tablet unplugged behind it is lifted only "
    "after its last reading",
    "[kiosk]") {
  TabletRig rig(std::make_unique<platform::FakePenSource>(true));
  std::vector<platform::PenReading> seen;
  const auto on_pen = [&](const platform::PenReading& r) { seen.push_back(r); };
  // A tablet at 1 kHz while the kiosk was still starting: a second of readings, tip down.
  constexpr int kFlood = 1000;
  const std::int64_t t0 = 1000 * kMs;
  for (int i = 0; i < kFlood; ++i) {
    platform::PenReading r;
    r.time_ns = t0 + i * kMs;
    r.kind = i == 0 ? platform::PenReadingKind::kTipDown : platform::PenReadingKind::kMotion;
    r.x_px = 100.0 + 0.5 * i;
    r.y_px = 300.0;
    r.tip_down = r.in_proximity = true;
    r.pressure = 0.5;
    r.origin = platform::PenOrigin::kTablet;
    REQUIRE(rig.fake->Push(r));
  }
  rig.fake->Unplug(rig.board);  // pulled out with its tip down: no tip-up will come

  std::vector<std::size_t> per_pass;
  std::int64_t now = t0 + 2000 * kMs;
  do {
    const std::size_t before = seen.size();
    rig.control.Step(now, on_pen);
    per_pass.push_back(seen.size() - before);
    now += 16 * kMs;
  } while (rig.control.Backlog() && per_pass.size() < 100);

  INFO(::Catch::Detail::stringify(per_pass));
  REQUIRE(per_pass.size() == 16);  // ceil(1000 / 64)
  CHECK(std::all_of(per_pass.begin(), per_pass.end() - 1, [](std::size_t n) { return n == 64; }));
  CHECK(per_pass.back() == 40 + 1);  // the rest, and the lift
  REQUIRE(seen.size() == kFlood + 1);
  for (int i = 0; i < kFlood; ++i) {
    INFO("reading " << i);
    REQUIRE(seen[static_cast<std::size_t>(i)].time_ns == t0 + i * kMs);
    REQUIRE(seen[static_cast<std::size_t>(i)].tip_down);
  }
  const auto& lift = seen.back();
  CHECK(lift.kind == platform::PenReadingKind::kTipUp);
  CHECK_FALSE(lift.tip_down);
  CHECK(lift.time_ns == now - 16 * kMs);  // the pass that took the last reading
  CHECK(lift.x_px == seen[kFlood - 1].x_px);
  rig.control.Step(now, on_pen);
  CHECK(seen.size() == kFlood + 1);  // lifted once
  CHECK_FALSE(rig.control.Backlog());
}

TEST_CASE(
    "control: switch events queued before the loop ran are taken at most 16 a pass, in order, "
    "the rest at the next pass",
    "[kiosk]") {
  TabletRig rig(std::make_unique<platform::FakePenSource>(true));
  const auto on_pen = [](const platform::PenReading&) {};
  // Token 1 placed and lifted 8 times, then placed: 17 events.
  for (int i = 0; i < 17; ++i) REQUIRE(rig.switches.keyboard->OnKey('1', true, (10 + i) * kMs));
  rig.control.Step(100 * kMs, on_pen);
  CHECK(rig.control.Backlog());
  // The 16th event, a lift, was the last one taken.
  CHECK(rig.control.selector().Selected() == platform::TokenSelector::kDefaultTexture);
  rig.control.Step(116 * kMs, on_pen);
  CHECK_FALSE(rig.control.Backlog());
  CHECK(rig.control.selector().Selected() == 0);
}
