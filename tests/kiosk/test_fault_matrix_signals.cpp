// The fault matrix, signals: every signal the kiosk may be sent (TERM, INT, HUP, USR1, PIPE), each
// in a child process that runs the kiosk's own control-loop body after a visit; the real binary's
// half of these rows is tests/e2e/kiosk_faults_e2e.sh. Devices are test_fault_matrix_devices.cpp.
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

}  // namespace

// ---------------------------------------------------------------------------------------------
// Signals. Each row runs in a child process of its own (a stop request cannot be taken back, and
// a signal whose default action ends the process must be seen to end only the child): the kiosk's
// signal set-up (kiosk_signals.h), a visit, the signal, then the loop as app/live_kiosk.cpp runs
// it (HandleSignals between passes). The child reports what happened through a pipe; the real
// binary gets the same signals in tests/e2e/kiosk_faults_e2e.sh.

namespace {

struct SignalRow {
  const char* name;
  int signal;
  bool stops;        // the loop ends (counters saved by the stop), else it runs on
  const char* line;  // the one info line it writes, or null for none
};

// The child: returns its report ("stopped N", "passes N", "on_disk_equal N", "strokes N", then
// the journal lines). Exits; never returns to Catch.
[[noreturn]] void SignalChild(const SignalRow& row, const std::string& counters_path, int out_fd) {
  kiosk::CatchHangupAndIgnoreWriteSignals();
  kiosk::CatchStopSignals();
  platform::Logger log;
  log.SetEchoToStderr(false);
  platform::DeviceStatusBoard board(log);
  kiosk::KioskEngineOptions options;
  options.virtual_clock = true;
  options.cues_dir = "/nonexistent";
  options.texture_paths = {test::TexturePath("wooden_board")};
  options.counters_path = counters_path;
  kiosk::KioskEngine engine(options);
  engine.SetStatusBoard(&board);
  platform::OfflineAudioOutput output(engine.audio(), {});
  output.Start();
  platform::SwitchInputs switches;
  board.Set("switches", DeviceState::kOk, "keys 1-4 toggle tokens, R records", "keyboard");
  kiosk::KioskControl control(engine, {&output, nullptr, &switches, &board}, log);
  std::int64_t now = 1000 * kMs;
  int strokes = 0;
  const auto stroke = [&] {
    for (int i = 0; i <= 10; ++i) {
      platform::PenReading pen;
      pen.time_ns = now;
      pen.x_px = 300.0 + 5.0 * i;
      pen.y_px = 300.0;
      pen.tip_down = i < 10;
      pen.pressure = pen.tip_down ? 0.8 : 0.0;
      engine.OnPen(pen);
      control.Step(now += 3 * kMs, [](const platform::PenReading&) {});
      output.RenderBlocks(1);
    }
    ++strokes;
  };
  stroke();
  stroke();
  const std::uint64_t lines_before = log.Count();
  if (row.signal == SIGPIPE) {
    // A closed pipe written to, as when the journal's reader goes: EPIPE, not the end.
    int fds[2];
    if (pipe2(fds, O_CLOEXEC) == 0) {
      close(fds[0]);
      const bool epipe = write(fds[1], "x", 1) == -1 && errno == EPIPE;
      close(fds[1]);
      if (!epipe) _exit(3);
    }
  }
  raise(row.signal);
  int passes = 0;
  bool stopped = false;
  int on_disk_equal = -1;
  for (; passes < 100; ++passes) {
    if (control.HandleSignals()) {
      stopped = true;
      break;
    }
    if (passes == 0) {
      kiosk::UsageCounters disk;
      std::string error;
      kiosk::LoadCounters(counters_path, {"wooden_board"}, &disk, &error);
      on_disk_equal = disk == engine.session().counters() ? 1 : 0;
    }
    control.Step(now += 3 * kMs, [](const platform::PenReading&) {});
  }
  if (!stopped) stroke();  // the kiosk runs on and counts
  control.Shutdown();      // the stop that comes later (or now)
  std::string report = "stopped " + std::to_string(stopped ? 1 : 0) + "\npasses " +
                       std::to_string(passes) + "\non_disk_equal " + std::to_string(on_disk_equal) +
                       "\nstrokes " + std::to_string(strokes) + "\n";
  const auto recent = log.Recent();
  for (std::size_t i = 0; i < recent.size(); ++i) {
    if (log.Count() - recent.size() + i >= lines_before) report += recent[i].Text() + "\n";
  }
  std::size_t done = 0;
  while (done < report.size()) {
    const ssize_t n = write(out_fd, report.data() + done, report.size() - done);
    if (n <= 0) _exit(4);
    done += static_cast<std::size_t>(n);
  }
  _exit(0);
}

int ReportValue(const std::string& report, const std::string& key) {
  const auto at = report.find(key + " ");
  return at == std::string::npos ? -99 : std::stoi(report.substr(at + key.size() + 1));
}

int CountLines(const std::string& report, const std::string& text) {
  int n = 0;
  for (std::size_t at = report.find(text); at != std::string::npos;
       at = report.find(text, at + 1)) {
    ++n;
  }
  return n;
}

}  // namespace

TEST_CASE(
    "fault matrix: signals - TERM and INT stop with the counters saved, HUP saves them and runs "
    "on, USR1 writes the status and runs on, PIPE is ignored, none loses a stroke",
    "[kiosk][faults]") {
  const std::vector<SignalRow> rows = {
      {"SIGTERM (systemd's stop)", SIGTERM, true, "info kiosk: stopping"},
      {"SIGINT (ctrl-c on a console)", SIGINT, true, "info kiosk: stopping"},
      {"SIGHUP (the unit's reload)", SIGHUP, false, "info kiosk: SIGHUP: usage counters saved"},
      {"SIGUSR1 (status request)", SIGUSR1, false,
       "info kiosk: SIGUSR1: status: storage ok; switches ok (keyboard); audio running; visits "
       "1"},
      {"SIGPIPE (the journal's reader gone)", SIGPIPE, false, nullptr},
  };
  for (const auto& row : rows) {
    INFO("row: signal, " << row.name);
    sas::test::TempDir dir;
    const std::string counters_path = dir.file("counters.toml");
    int fds[2];
    REQUIRE(pipe2(fds, O_CLOEXEC) == 0);
    std::fflush(nullptr);
    const pid_t child = fork();
    REQUIRE(child >= 0);
    if (child == 0) {
      close(fds[0]);
      SignalChild(row, counters_path, fds[1]);
    }
    close(fds[1]);
    std::string report;
    char buffer[4096];
    for (ssize_t n; (n = read(fds[0], buffer, sizeof buffer)) > 0;)
      report.append(buffer, static_cast<std::size_t>(n));
    close(fds[0]);
    int status = 0;
    REQUIRE(waitpid(child, &status, 0) == child);
    INFO("child report:\n" << report);
    // The process was not ended by the signal: it finished its loop and its stop.
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 0);
    CHECK(ReportValue(report, "stopped") == (row.stops ? 1 : 0));
    // A stop ends the loop at the first pass after the signal; otherwise the loop runs on.
    CHECK(ReportValue(report, "passes") == (row.stops ? 0 : 100));
    if (row.line != nullptr) CHECK(CountLines(report, row.line) == 1);
    if (row.signal == SIGHUP) CHECK(ReportValue(report, "on_disk_equal") == 1);
    // No other line than the row's (and the stop's); SIGPIPE none besides the stop.
    const int expected_lines = (row.line != nullptr ? 1 : 0) + (row.stops ? 0 : 1);
    CHECK(CountLines(report, "\ninfo ") + CountLines(report, "\nwarn ") +
              CountLines(report, "\nerror ") ==
          expected_lines);
    CHECK(CountLines(report, "warn ") == 0);
    // Nothing lost: every stroke the child made is in the file its stop saved.
    kiosk::UsageCounters saved;
    std::string error;
    REQUIRE(kiosk::LoadCounters(counters_path, {"wooden_board"}, &saved, &error));
    CHECK(static_cast<int>(saved.strokes_per_texture.at(0)) == ReportValue(report, "strokes"));
    CHECK(ReportValue(report, "strokes") == (row.stops ? 2 : 3));
    CHECK(saved.sessions >= 1);
  }
}
