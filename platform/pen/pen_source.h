#pragma once
// The pen: libinput tablet-tool events (SDL2 2.26 has no pen pressure or tilt; reference
// platform.md) on their own thread, timestamped (CLOCK_MONOTONIC, libinput's clock), into an SPSC
// queue the control thread drains. x/y come from libinput_event_tablet_tool_get_x/y_transformed
// scaled to the screen size in pixels; pressure 0..1 after libinput's pressure offset; tilt in
// degrees. When no tablet is present the source reports it cleanly ("missing") and the UI uses
// SDL2 mouse/touch instead — that fallback lives in app/ui, not here. Status key "pen".

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "platform/common/spsc_queue.h"
#include "platform/device_status.h"

namespace sas::platform {

enum class PenEventKind : std::uint8_t {
  kMotion,  // axes changed (tip up or down)
  kTipDown,
  kTipUp,
  kProximityIn,
  kProximityOut,
};

struct PenEvent {
  std::int64_t time_ns = 0;  // CLOCK_MONOTONIC
  PenEventKind kind = PenEventKind::kMotion;
  float x_px = 0.0f;
  float y_px = 0.0f;
  float pressure = 0.0f;  // 0..1
  float tilt_x_deg = 0.0f;
  float tilt_y_deg = 0.0f;
  bool tip_down = false;
  bool in_proximity = false;
};

using PenQueue = SpscQueue<PenEvent, 1024>;

struct PenConfig {
  int screen_width_px = 1920;
  int screen_height_px = 1080;
  std::string seat = "seat0";
  std::string device_name_contains;  // empty: the first tablet-tool device
};

class PenSource {
 public:
  virtual ~PenSource() = default;
  virtual const char* Name() const = 0;
  // The tablet's own name once started (for the status line).
  virtual std::string DeviceName() const { return Name(); }
  // False with `error` when there is no tablet (never throws).
  virtual bool Start(std::string* error) = 0;
  virtual void Stop() = 0;
  bool Pop(PenEvent& event) { return queue_.TryPop(event); }
  // CLOCK_MONOTONIC time the event thread last ran its loop (watchdog), 0 before start.
  std::int64_t HeartbeatNs() const { return heartbeat_ns_.load(std::memory_order_relaxed); }
  // False while the started tablet is unplugged: the kiosk then takes mouse/touch input and
  // lifts a stroke the tablet left with its tip down.
  bool Connected() const { return connected_.load(std::memory_order_acquire); }

 protected:
  // The device thread saw the tablet go or come back: flag, status line and counters (one log
  // line per change, the same words for every backend).
  void ReportConnected(bool connected, DeviceStatusBoard& board, const std::string& tablet) {
    if (connected_.exchange(connected, std::memory_order_acq_rel) == connected) return;
    if (connected) {
      board.AddReconnect("pen");
      board.Set("pen", DeviceState::kOk, "pen tablet '" + tablet + "' back", Name());
    } else {
      board.AddFailure("pen");
      board.Set("pen", DeviceState::kLost,
                "pen tablet '" + tablet + "' unplugged; mouse/touch fallback", Name());
    }
  }

  PenQueue queue_;
  std::atomic<std::int64_t> heartbeat_ns_{0};
  std::atomic<bool> connected_{true};
};

std::unique_ptr<PenSource> MakeLibinputPenSource(const PenConfig& config, DeviceStatusBoard& board);

// Test fake: a tablet that is there or not; Push() delivers events as the thread would.
class FakePenSource final : public PenSource {
 public:
  explicit FakePenSource(bool present) : present_(present) {}
  const char* Name() const override { return "fake"; }
  bool Start(std::string* error) override {
    if (!present_ && error) *error = "no pen tablet (fake)";
    return present_;
  }
  void Stop() override {}
  bool Push(const PenEvent& event) {
    heartbeat_ns_.store(event.time_ns, std::memory_order_relaxed);
    return queue_.TryPush(event);
  }
  // What libinput's DEVICE_REMOVED / DEVICE_ADDED do to the real source.
  void Unplug(DeviceStatusBoard& board) { ReportConnected(false, board, "fake tablet"); }
  void Replug(DeviceStatusBoard& board) { ReportConnected(true, board, "fake tablet"); }
  std::string DeviceName() const override { return "fake tablet"; }

 private:
  bool present_;
};

// Starts `source` (the libinput one when null) and sets the "pen" status: ok with the tablet's
// name, or missing ("no pen tablet ...; mouse/touch fallback"). Returns null when there is no
// tablet: the UI then takes pointer input from SDL2.
std::unique_ptr<PenSource> OpenPen(const PenConfig& config, DeviceStatusBoard& board,
                                   std::unique_ptr<PenSource> source = nullptr);

}  // namespace sas::platform
