// The watchdog's stand-in while the control loop draws a slow frame (busy_keeper.h): it pings for
// a live loop inside a step, never for a dead one, and stops once the step has lasted too long.
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <thread>

#include "platform/common/clock.h"
#include "platform/watchdog/busy_keeper.h"

using sas::platform::BusyKeeper;

namespace {

constexpr std::int64_t kMs = 1'000'000;

// Waits for `done` (an event), bounded only so that a broken keeper ends the test.
template <typename Done>
bool WaitFor(Done done) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

}  // namespace

TEST_CASE("busy keeper: pings only inside a step a live loop began, until the step is too old",
          "[platform]") {
  const std::int64_t max = 60'000 * kMs;
  CHECK(BusyKeeper::ShouldPing(true, true, 0, 2'000 * kMs, max));
  CHECK(BusyKeeper::ShouldPing(true, true, 0, 59'999 * kMs, max));
  CHECK_FALSE(BusyKeeper::ShouldPing(true, true, 0, 60'000 * kMs, max));  // a hung step
  CHECK_FALSE(BusyKeeper::ShouldPing(false, true, 0, 2'000 * kMs, max));  // not in a step
  CHECK_FALSE(BusyKeeper::ShouldPing(true, false, 0, 2'000 * kMs, max));  // a thread had stalled
}

TEST_CASE("busy keeper: a step longer than several ping intervals is pinged through",
          "[platform]") {
  std::atomic<int> pings{0};
  BusyKeeper keeper([&] { ++pings; }, 5 * kMs, 3'600'000 * kMs);
  keeper.Begin(sas::platform::MonotonicNowNs(), true);
  // The loop stands inside one long step (a frame that takes seconds): the keeper pings for it.
  CHECK(WaitFor([&] { return pings.load() >= 3; }));
  keeper.End();
  CHECK(keeper.pings() >= 3);
}
