// Pen source (fake tablet present/absent, plugged in later, unplugged and back; the libinput
// source on this machine) and the systemd watchdog, checked on a datagram socket the test owns
// (NOTIFY_SOCKET).
#include <catch2/catch.hpp>
#include <cstdlib>

#include "platform/common/clock.h"
#include "platform/log/log.h"
#include "platform/pen/pen_source.h"
#include "platform/watchdog/watchdog.h"
#include "support/notify_socket.h"

using namespace sas::platform;

TEST_CASE("no tablet: pen status says mouse fallback, one log line, no source", "[platform]") {
  Logger logger;
  logger.SetEchoToStderr(false);
  DeviceStatusBoard board(logger);
  auto pen = OpenPen(PenConfig{}, board, std::make_unique<FakePenSource>(false));
  CHECK(pen == nullptr);
  const auto status = board.Get("pen");
  CHECK(status.state == DeviceState::kMissing);
  CHECK(status.message.find("mouse/touch fallback") != std::string::npos);
  const auto lines = logger.Recent();
  REQUIRE(lines.size() == 1);
  CHECK(lines[0].Text().rfind("warn pen: missing: no pen tablet", 0) == 0);
}

TEST_CASE("a present tablet delivers its timestamped events in order", "[platform]") {
  Logger logger;
  logger.SetEchoToStderr(false);
  DeviceStatusBoard board(logger);
  auto fake = std::make_unique<FakePenSource>(true);
  FakePenSource* raw = fake.get();
  auto pen = OpenPen(PenConfig{}, board, std::move(fake));
  REQUIRE(pen != nullptr);
  CHECK(board.Get("pen").state == DeviceState::kOk);
  for (int i = 0; i < 10; ++i) {
    PenReading e;
    e.time_ns = 1000 + i;
    e.x_px = i;
    e.pressure = 0.1 * i;
    e.kind = i == 0 ? PenReadingKind::kTipDown : PenReadingKind::kMotion;
    REQUIRE(raw->Push(e));
  }
  PenReading e;
  for (int i = 0; i < 10; ++i) {
    REQUIRE(pen->Pop(e));
    CHECK(e.time_ns == 1000 + i);
    CHECK(e.x_px == i);
  }
  CHECK_FALSE(pen->Pop(e));
  CHECK(pen->HeartbeatNs() == 1009);
}

TEST_CASE("the libinput pen source reports this machine's tablet or its absence cleanly",
          "[platform]") {
  Logger logger;
  logger.SetEchoToStderr(false);
  DeviceStatusBoard board(logger);
  auto pen = OpenPen(PenConfig{}, board);
  const auto status = board.Get("pen");
  // CI has no tablet (and often no udev); a workstation may have one. Either way: one line, and
  // a source is returned whenever libinput runs (it then waits for a tablet).
  CHECK((status.state == DeviceState::kOk) == (pen != nullptr && pen->Connected()));
  CHECK(status.backend == "libinput");
  CHECK(logger.Count() == 1);
}

TEST_CASE("pen: a tablet absent at start is taken up when plugged in later, with one info line",
          "[platform]") {
  Logger logger;
  logger.SetEchoToStderr(false);
  DeviceStatusBoard board(logger);
  auto fake = std::make_unique<FakePenSource>(false, /*waits_for_tablet=*/true);
  FakePenSource* raw = fake.get();
  auto pen = OpenPen(PenConfig{}, board, std::move(fake));
  REQUIRE(pen != nullptr);  // running, waiting for a tablet
  CHECK_FALSE(pen->Connected());
  auto status = board.Get("pen");
  CHECK(status.state == DeviceState::kMissing);
  CHECK(status.message.find("mouse/touch fallback") != std::string::npos);
  CHECK(status.message.find("until one is plugged in") != std::string::npos);
  REQUIRE(logger.Count() == 1);
  CHECK(logger.Recent().back().level == LogLevel::kWarn);

  raw->AddDevice(false, "AT Translated Set 2 keyboard", board);  // not a tablet: nothing
  CHECK_FALSE(pen->Connected());
  CHECK(logger.Count() == 1);

  raw->Replug(board);
  CHECK(pen->Connected());
  status = board.Get("pen");
  CHECK(status.state == DeviceState::kOk);
  CHECK(status.reconnects == 0);  // a first arrival, not a reconnection
  REQUIRE(logger.Count() == 2);
  CHECK(logger.Recent().back().Text() == "info pen: ok: pen tablet 'fake tablet' plugged in");
  CHECK(pen->DeviceName() == "fake tablet");
  PenReading e;
  e.time_ns = 42;
  REQUIRE(raw->Push(e));
  REQUIRE(pen->Pop(e));
  CHECK(e.time_ns == 42);
}

TEST_CASE(
    "pen: unplugged and plugged back the status goes ok, lost, ok with one warning and one info "
    "line, however many of the tablet's nodes come and go",
    "[platform]") {
  Logger logger;
  logger.SetEchoToStderr(false);
  DeviceStatusBoard board(logger);
  auto fake = std::make_unique<FakePenSource>(true);
  FakePenSource* raw = fake.get();
  auto pen = OpenPen(PenConfig{}, board, std::move(fake));
  REQUIRE(pen != nullptr);
  REQUIRE(board.Get("pen").state == DeviceState::kOk);
  CHECK(logger.Recent().back().Text() == "info pen: ok: pen tablet 'fake tablet' via fake");
  const auto lines_before = logger.Count();

  raw->AddDevice(true, "fake tablet Pad", board);  // a second node of the same tablet
  raw->AddDevice(false, "USB mouse", board);
  raw->RemoveDevice(false, board);
  raw->RemoveDevice(true, board);  // one node gone, the other still there
  CHECK(pen->Connected());
  CHECK(logger.Count() == lines_before);

  raw->Unplug(board);  // the last node
  CHECK_FALSE(pen->Connected());
  auto status = board.Get("pen");
  CHECK(status.state == DeviceState::kLost);
  CHECK(status.failures == 1);
  REQUIRE(logger.Count() == lines_before + 1);
  const auto lost = logger.Recent().back();
  CHECK(lost.level == LogLevel::kWarn);  // journal priority 4: `journalctl -p warning` shows it
  CHECK(lost.Text() == "warn pen: lost: pen tablet 'fake tablet' unplugged; mouse/touch fallback");
  raw->Unplug(board);  // a stray second removal
  CHECK(logger.Count() == lines_before + 1);

  raw->Replug(board);
  raw->AddDevice(true, "fake tablet Pad", board);
  CHECK(pen->Connected());
  status = board.Get("pen");
  CHECK(status.state == DeviceState::kOk);
  CHECK(status.reconnects == 1);
  REQUIRE(logger.Count() == lines_before + 2);
  CHECK(logger.Recent().back().Text() == "info pen: ok: pen tablet 'fake tablet' back");
}

using sas::test::NotifySocket;

TEST_CASE("watchdog pings only while audio and input heartbeats are recent", "[platform]") {
  NotifySocket socket;
  constexpr std::int64_t kMs = 1'000'000;
  std::int64_t audio_beat = 0;
  std::int64_t input_beat = 0;
  WatchdogSupervisor watchdog(500 * kMs);
  watchdog.Watch("audio callback", [&] { return audio_beat; });
  watchdog.Watch("input thread", [&] { return input_beat; });
  watchdog.Ready("kiosk up");
  auto messages = socket.Drain();
  REQUIRE(messages.size() == 1);
  CHECK(messages[0] == "READY=1\nSTATUS=kiosk up");

  const std::int64_t now = 10'000 * kMs;
  audio_beat = now - 100 * kMs;
  input_beat = now - 200 * kMs;
  CHECK(watchdog.Tick(now));
  messages = socket.Drain();
  CHECK(messages == std::vector<std::string>{"STATUS=running", "WATCHDOG=1"});

  // The audio callback stops beating: no ping, one STATUS naming it, not repeated.
  CHECK_FALSE(watchdog.Tick(now + 700 * kMs));
  CHECK_FALSE(watchdog.Tick(now + 800 * kMs));
  messages = socket.Drain();
  CHECK(messages == std::vector<std::string>{"STATUS=stalled: audio callback, input thread"});
  input_beat = now + 790 * kMs;
  CHECK_FALSE(watchdog.Tick(now + 800 * kMs));
  CHECK(socket.Drain() == std::vector<std::string>{"STATUS=stalled: audio callback"});

  // Audio legitimately stopped (device lost, running silent): exempt, pings resume.
  audio_beat = WatchdogSupervisor::kExempt;
  CHECK(watchdog.Tick(now + 810 * kMs));
  CHECK(socket.Drain() == std::vector<std::string>{"STATUS=running", "WATCHDOG=1"});
}

TEST_CASE("watchdog is a silent no-op without NOTIFY_SOCKET", "[platform]") {
  unsetenv("NOTIFY_SOCKET");
  WatchdogSupervisor watchdog(1'000'000'000);
  watchdog.Watch("audio", [] { return MonotonicNowNs(); });
  watchdog.Ready("up");
  CHECK(watchdog.Tick(MonotonicNowNs()));
  CHECK_FALSE(SystemdNotifier{}.UnderSystemd());
}

TEST_CASE("a withheld watchdog ping is a journal warning naming the silent thread and its age",
          "[platform]") {
  NotifySocket socket;
  constexpr std::int64_t kMs = 1'000'000;
  Logger log;
  log.SetEchoToStderr(false);
  std::int64_t audio_beat = 0;
  WatchdogSupervisor watchdog(2'000 * kMs);
  watchdog.ReportTo(&log);
  watchdog.Watch("audio", [&] { return audio_beat; });
  watchdog.Watch("pen", [] { return WatchdogSupervisor::kExempt; });
  const std::int64_t now = 100'000 * kMs;
  audio_beat = now - 10 * kMs;
  CHECK(watchdog.Tick(now));
  CHECK(log.Count() == 0);  // a first healthy tick says nothing

  CHECK_FALSE(watchdog.Tick(now + 3'500 * kMs));
  CHECK_FALSE(watchdog.Tick(now + 4'000 * kMs));  // not repeated while nothing changes
  auto lines = log.Recent();
  REQUIRE(lines.size() == 1);
  CHECK(lines[0].level == LogLevel::kWarn);
  CHECK(lines[0].component == "watchdog");
  CHECK(lines[0].message.find("audio (3.5 s)") != std::string::npos);
  CHECK(lines[0].message.find("pen") == std::string::npos);  // exempt threads are not named

  audio_beat = now + 4'000 * kMs;
  CHECK(watchdog.Tick(now + 4'100 * kMs));
  lines = log.Recent();
  REQUIRE(lines.size() == 2);
  CHECK(lines[1].level == LogLevel::kInfo);
  CHECK(lines[1].message.find("alive again") != std::string::npos);
}
