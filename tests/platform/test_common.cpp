// SPSC queue, log ring, the journal priorities, device status board and memory kept out of core
// dumps.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cerrno>
#include <cstdlib>
#include <memory_resource>
#include <string>
#include <thread>
#include <vector>

#include "common/spsc_queue.h"
#include "platform/common/no_dump_buffer.h"
#include "platform/device_status.h"
#include "platform/log/log.h"
#include "support/smaps.h"

using namespace sas::platform;

TEST_CASE("SPSC queue delivers every message in order across threads and never overfills",
          "[platform]") {
  struct Msg {
    std::uint64_t seq;
    double payload;
  };
  sas::SpscQueue<Msg, 64> q;
  constexpr std::uint64_t kCount = 200'000;
  std::thread producer([&] {
    for (std::uint64_t i = 0; i < kCount;) {
      if (q.TryPush({i, static_cast<double>(i) * 0.5})) ++i;
    }
  });
  std::uint64_t expected = 0;
  bool in_order = true;
  Msg m{};
  while (expected < kCount) {
    if (q.TryPop(m)) {
      in_order = in_order && m.seq == expected && m.payload == static_cast<double>(expected) * 0.5;
      ++expected;
    }
    if (q.SizeApprox() > q.Capacity()) in_order = false;
  }
  producer.join();
  CHECK(in_order);
  CHECK_FALSE(q.TryPop(m));
}

TEST_CASE("SPSC queue refuses the push after capacity messages", "[platform]") {
  sas::SpscQueue<int, 4> q;
  for (int i = 0; i < 4; ++i) CHECK(q.TryPush(i));
  CHECK_FALSE(q.TryPush(99));
  int v = -1;
  REQUIRE(q.TryPop(v));
  CHECK(v == 0);
  CHECK(q.TryPush(4));
}

TEST_CASE("log ring keeps the newest lines and counts all of them", "[platform]") {
  Logger logger(3);
  logger.SetEchoToStderr(false);
  for (int i = 0; i < 5; ++i) logger.Info("test", "line " + std::to_string(i));
  logger.Debug("test", "dropped below the minimum level");
  const auto lines = logger.Recent();
  REQUIRE(lines.size() == 3);
  CHECK(lines[0].Text() == "info test: line 2");
  CHECK(lines[2].Text() == "info test: line 4");
  CHECK(logger.Count() == 5);
}

TEST_CASE("device status logs one line per change and none for repeats", "[platform]") {
  Logger logger;
  logger.SetEchoToStderr(false);
  DeviceStatusBoard board(logger);
  board.Set("pen", DeviceState::kMissing, "no tablet", "libinput");
  board.Set("pen", DeviceState::kMissing, "no tablet");
  board.Set("pen", DeviceState::kOk, "tablet X");
  const auto lines = logger.Recent();
  REQUIRE(lines.size() == 2);
  CHECK(lines[0].Text() == "warn pen: missing: no tablet");
  CHECK(lines[1].Text() == "info pen: ok: tablet X");
  const auto status = board.Get("pen");
  CHECK(status.backend == "libinput");
  CHECK(board.All().size() == 1);
}

TEST_CASE("log lines reach stderr while a library has fd 2 muted", "[platform]") {
  int pipe_fds[2];
  REQUIRE(pipe2(pipe_fds, O_CLOEXEC | O_NONBLOCK) == 0);
  const int saved = dup(STDERR_FILENO);
  dup2(pipe_fds[1], STDERR_FILENO);  // "the journal"
  {
    Logger logger;  // takes its own copy of stderr now
    const int null_fd = open("/dev/null", O_WRONLY | O_CLOEXEC);
    dup2(null_fd, STDERR_FILENO);  // PortAudio start-up mutes fd 2...
    close(null_fd);
    logger.Warn("audio_out", "lost: device gone");  // ...while another thread logs
  }
  dup2(saved, STDERR_FILENO);
  close(saved);
  char buf[256] = {};
  const ssize_t n = read(pipe_fds[0], buf, sizeof buf - 1);
  close(pipe_fds[0]);
  close(pipe_fds[1]);
  REQUIRE(n > 0);
  CHECK(std::string(buf, static_cast<std::size_t>(n)) == "warn audio_out: lost: device gone\n");
}

TEST_CASE("journal entries carry the level's syslog priority and the stderr line as MESSAGE",
          "[platform]") {
  CHECK(JournalPriority(LogLevel::kError) == 3);
  CHECK(JournalPriority(LogLevel::kWarn) == 4);
  CHECK(JournalPriority(LogLevel::kInfo) == 6);
  CHECK(JournalPriority(LogLevel::kDebug) == 7);
  const LogLine line{0, LogLevel::kWarn, "gpio", "chip gpiochip0 absent; 100% keys"};
  const auto fields = JournalFields(line, "sketch-a-scratch");
  REQUIRE(fields.size() == 4);
  CHECK(fields[0] == "MESSAGE=warn gpio: chip gpiochip0 absent; 100% keys");
  CHECK(fields[1] == "PRIORITY=4");
  CHECK(fields[2] == "SAS_COMPONENT=gpio");
  CHECK(fields[3] == "SYSLOG_IDENTIFIER=sketch-a-scratch");
}

TEST_CASE("stderr counts as the journal only when JOURNAL_STREAM names fd 2's device and inode",
          "[platform]") {
  CHECK(StderrIsJournal("64769:123456", 64769, 123456));
  CHECK_FALSE(StderrIsJournal(nullptr, 64769, 123456));
  CHECK_FALSE(StderrIsJournal("", 64769, 123456));
  CHECK_FALSE(StderrIsJournal("64769:123457", 64769, 123456));  // stderr redirected since
  CHECK_FALSE(StderrIsJournal("64770:123456", 64769, 123456));
  CHECK_FALSE(StderrIsJournal("64769:123456x", 64769, 123456));
  CHECK_FALSE(StderrIsJournal("64769", 64769, 123456));
  CHECK_FALSE(StderrIsJournal(":123456", 64769, 123456));

  // The logger's own check, on a pipe standing in for the journal's stream socket.
  int pipe_fds[2];
  REQUIRE(pipe2(pipe_fds, O_CLOEXEC | O_NONBLOCK) == 0);
  struct stat st {};
  REQUIRE(fstat(pipe_fds[1], &st) == 0);
  const std::string matching = std::to_string(static_cast<std::uint64_t>(st.st_dev)) + ":" +
                               std::to_string(static_cast<std::uint64_t>(st.st_ino));
  const char* old = std::getenv("JOURNAL_STREAM");
  const std::string saved_env = old ? old : "";
  const int saved = dup(STDERR_FILENO);
  dup2(pipe_fds[1], STDERR_FILENO);
  setenv("JOURNAL_STREAM", matching.c_str(), 1);
  const bool detected = Logger().ToJournal();
  setenv("JOURNAL_STREAM", (matching + "0").c_str(), 1);
  const bool detected_other_inode = Logger().ToJournal();
  dup2(saved, STDERR_FILENO);
  close(saved);
  const bool detected_after_redirect = [&] {
    setenv("JOURNAL_STREAM", matching.c_str(), 1);
    return Logger().ToJournal();
  }();
  if (old) {
    setenv("JOURNAL_STREAM", saved_env.c_str(), 1);
  } else {
    unsetenv("JOURNAL_STREAM");
  }
  close(pipe_fds[0]);
  close(pipe_fds[1]);
  CHECK(detected);
  CHECK_FALSE(detected_other_inode);
  CHECK_FALSE(detected_after_redirect);
}

TEST_CASE(
    "with stderr on the journal a line is one entry with its priority, and a refused "
    "entry falls back to the plain stderr line",
    "[platform]") {
  int pipe_fds[2];
  REQUIRE(pipe2(pipe_fds, O_CLOEXEC | O_NONBLOCK) == 0);
  const int saved = dup(STDERR_FILENO);
  dup2(pipe_fds[1], STDERR_FILENO);
  std::vector<std::vector<std::string>> entries;
  int refuse = 0;
  {
    Logger logger;
    dup2(saved, STDERR_FILENO);
    logger.SetJournalSender([&](const std::vector<std::string>& fields) {
      if (refuse != 0) return refuse;
      entries.push_back(fields);
      return 0;
    });
    CHECK(logger.ToJournal());
    logger.Warn("pen", "lost: pen tablet 'X' unplugged");
    logger.Info("pen", "ok: pen tablet 'X' back");
    refuse = -ECONNREFUSED;
    logger.Error("display", "cannot open the kiosk window");
    CHECK(logger.Count() == 3);  // the ring has every line either way
  }
  close(saved);
  char buf[256] = {};
  const ssize_t n = read(pipe_fds[0], buf, sizeof buf - 1);
  close(pipe_fds[0]);
  close(pipe_fds[1]);
  REQUIRE(entries.size() == 2);
  CHECK(entries[0][0] == "MESSAGE=warn pen: lost: pen tablet 'X' unplugged");
  CHECK(entries[0][1] == "PRIORITY=4");
  CHECK(entries[0][2] == "SAS_COMPONENT=pen");
  CHECK(entries[1][1] == "PRIORITY=6");
  REQUIRE(n > 0);  // only the refused line reached stderr, as the plain line
  CHECK(std::string(buf, static_cast<std::size_t>(n)) ==
        "error display: cannot open the kiosk window\n");
}

TEST_CASE("a no-dump buffer's pages are marked dd in smaps, and Wipe zeroes every sample",
          "[platform]") {
  NoDumpBuffer<float> buffer(240'000);  // 5 s at 48 kHz
  REQUIRE(buffer.size() == 240'000);
  CHECK(sas::test::AllDontDump(sas::test::VmFlagsOf(buffer.data(), buffer.size() * sizeof(float))));
  // The check tells the two apart: an ordinary block of the same size is dumped.
  std::vector<float> ordinary(240'000, 1.0f);
  const auto ordinary_flags =
      sas::test::VmFlagsOf(ordinary.data(), ordinary.size() * sizeof(float));
  REQUIRE_FALSE(ordinary_flags.empty());
  CHECK_FALSE(sas::test::AllDontDump(ordinary_flags));

  for (std::size_t i = 0; i < buffer.size(); ++i) buffer[i] = 0.25f + static_cast<float>(i % 7);
  buffer.Wipe();
  CHECK(
      std::all_of(buffer.data(), buffer.data() + buffer.size(), [](float x) { return x == 0.0f; }));

  // Moving hands the pages over; the moved-from buffer holds none.
  const float* pages = buffer.data();
  NoDumpBuffer<float> moved(std::move(buffer));
  CHECK(moved.data() == pages);
  CHECK(buffer.empty());
  CHECK(sas::test::AllDontDump(sas::test::VmFlagsOf(moved.data(), moved.size() * sizeof(float))));
}

TEST_CASE("containers on the no-dump memory resource keep their elements in dd pages",
          "[platform]") {
  std::pmr::vector<float> samples(100'000, 0.5f, NoDumpMemory());
  CHECK(
      sas::test::AllDontDump(sas::test::VmFlagsOf(samples.data(), samples.size() * sizeof(float))));
  std::pmr::vector<double> small(3, 1.0, NoDumpMemory());  // less than a page: a page of its own
  CHECK(sas::test::AllDontDump(sas::test::VmFlagsOf(small.data(), small.size() * sizeof(double))));
  // A move keeps the resource, and so the pages.
  std::pmr::vector<float> moved(std::move(samples));
  CHECK(moved.get_allocator().resource() == NoDumpMemory());
  CHECK(sas::test::AllDontDump(sas::test::VmFlagsOf(moved.data(), moved.size() * sizeof(float))));
}
