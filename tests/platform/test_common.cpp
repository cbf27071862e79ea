// SPSC queue, log ring and device status board.
#include <fcntl.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <thread>

#include "platform/common/spsc_queue.h"
#include "platform/device_status.h"
#include "platform/log/log.h"

using namespace sas::platform;

TEST_CASE("SPSC queue delivers every message in order across threads and never overfills",
          "[platform]") {
  struct Msg {
    std::uint64_t seq;
    double payload;
  };
  SpscQueue<Msg, 64> q;
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
  SpscQueue<int, 4> q;
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
