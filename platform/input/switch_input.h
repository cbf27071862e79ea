#pragma once
// One interface over every token-switch backend (libgpiod, MCP2221A over hidapi, keyboard). Each
// backend produces debounced SwitchEvents on its own thread (or the UI thread for keys) into an
// SPSC queue; the control thread drains it with Pop(). Start() failing means "use a fallback"
// (see switch_factory.h); the status board entry is "switches".

#include <atomic>
#include <cstdint>
#include <string>

#include "common/spsc_queue.h"
#include "platform/input/switch_event.h"

namespace sas::platform {

using SwitchQueue = SpscQueue<SwitchEvent, 256>;

class SwitchInput {
 public:
  virtual ~SwitchInput() = default;
  virtual const char* Name() const = 0;
  // Set-up: false with `error` when the device is not there (never throws).
  virtual bool Start(std::string* error) = 0;
  virtual void Stop() = 0;
  // Control thread: next debounced event, false when none is waiting.
  bool Pop(SwitchEvent& event) { return queue_.TryPop(event); }
  // CLOCK_MONOTONIC time the backend's thread last ran its loop, for the watchdog; -1 when the
  // backend has no thread of its own (keyboard: fed by the UI thread).
  virtual std::int64_t HeartbeatNs() const { return heartbeat_ns_.load(std::memory_order_relaxed); }

 protected:
  SwitchQueue queue_;
  std::atomic<std::int64_t> heartbeat_ns_{0};
};

// Keys 1-4 toggle tokens (press once to place, again to lift); R is the record button (down/up).
// OnKey is called from the UI thread (the single producer).
class KeyboardSwitchInput final : public SwitchInput {
 public:
  const char* Name() const override { return "keyboard"; }
  bool Start(std::string* /*error*/) override { return true; }
  void Stop() override {}
  // `key` is the character ('1'..'4', 'r'/'R'); other keys are ignored (returns false).
  bool OnKey(char key, bool down, std::int64_t time_ns);
  std::int64_t HeartbeatNs() const override { return -1; }

 private:
  bool placed_[kTokenCount] = {};
  bool record_down_ = false;
};

}  // namespace sas::platform
