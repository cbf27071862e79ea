#pragma once
// Monotonic time in nanoseconds (CLOCK_MONOTONIC): the one time base of every input event, the
// audio heartbeats and the watchdog, and the clock libgpiod and libinput stamp events with.
// Lock-free and allocation-free, so it is safe in the audio callback.

#include <time.h>

#include <cstdint>

namespace sas::platform {

inline std::int64_t MonotonicNowNs() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

inline constexpr std::int64_t kNsPerMs = 1'000'000;

}  // namespace sas::platform
