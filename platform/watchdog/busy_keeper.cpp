// The watchdog's stand-in during a long loop step (busy_keeper.h).
#include "platform/watchdog/busy_keeper.h"

#include <chrono>
#include <utility>

#include "platform/common/clock.h"

namespace sas::platform {

BusyKeeper::BusyKeeper(std::function<void()> ping, std::int64_t interval_ns,
                       std::int64_t max_busy_ns)
    : ping_(std::move(ping)),
      interval_ns_(interval_ns),
      max_busy_ns_(max_busy_ns),
      thread_([this] { Run(); }) {}

BusyKeeper::~BusyKeeper() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void BusyKeeper::Begin(std::int64_t now_ns, bool alive) {
  {
    std::lock_guard lock(mutex_);
    busy_ = true;
    alive_ = alive;
    begin_ns_ = now_ns;
  }
  wake_.notify_all();
}

void BusyKeeper::End() {
  std::lock_guard lock(mutex_);
  busy_ = false;
}

std::uint64_t BusyKeeper::pings() const {
  std::lock_guard lock(mutex_);
  return pings_;
}

bool BusyKeeper::ShouldPing(bool busy, bool alive, std::int64_t begin_ns, std::int64_t now_ns,
                            std::int64_t max_busy_ns) {
  return busy && alive && now_ns - begin_ns < max_busy_ns;
}

void BusyKeeper::Run() {
  std::unique_lock lock(mutex_);
  while (!stop_) {
    // Idle until a step begins; inside one, wake every interval. The first ping comes one
    // interval into the step: the loop's own tick covered the time before it.
    if (!busy_) {
      wake_.wait(lock, [this] { return stop_ || busy_; });
      continue;
    }
    const std::int64_t begun = begin_ns_;
    wake_.wait_for(lock, std::chrono::nanoseconds(interval_ns_),
                   [this, begun] { return stop_ || !busy_ || begin_ns_ != begun; });
    if (stop_ || !busy_ || begin_ns_ != begun) continue;
    if (!ShouldPing(busy_, alive_, begin_ns_, MonotonicNowNs(), max_busy_ns_)) continue;
    ++pings_;
    lock.unlock();
    ping_();
    lock.lock();
  }
}

}  // namespace sas::platform
