#pragma once
// The pen: libinput tablet-tool events (SDL2 2.26 has no pen pressure or tilt; reference
// platform.md) on their own thread, timestamped (CLOCK_MONOTONIC, libinput's clock), into an SPSC
// queue the control thread drains, one PenReading (pen_reading.h) each. x/y come from
// libinput_event_tablet_tool_get_x/y_transformed scaled to the screen size in pixels; pressure
// 0..1 after libinput's pressure offset; tilt in degrees; whether a barrel button (BTN_STYLUS,
// BTN_STYLUS2, BTN_STYLUS3) is held, a reading of its own each time one is pressed or released
// (libinput's TABLET_TOOL_BUTTON, which carries the axes too). When no tablet is present the source
// reports it cleanly ("missing") and the UI uses SDL2 mouse/touch instead — that fallback lives in
// app/ui, not here. A tablet unplugged, plugged back or plugged in for the first time after start
// is picked up by the same event thread (one status line each). Status key "pen".

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include "common/spsc_queue.h"
#include "platform/device_status.h"
#include "platform/pen/pen_reading.h"

namespace sas::platform {

using PenQueue = SpscQueue<PenReading, 1024>;

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
  // The tablet's own name once one was seen (for the status line), else Name().
  std::string DeviceName() const;
  // False with `error` when the source cannot run at all (no udev, no access to the seat); never
  // throws. True when it runs: with no tablet there yet, Connected() is false, `error` says why,
  // and a tablet plugged in later is taken up.
  virtual bool Start(std::string* error) = 0;
  virtual void Stop() = 0;
  // The next reading, as every backend's readings leave the platform: a tablet's (its tilt
  // counts), the tip down and a barrel button held only in proximity, pressure 0 while the tip is
  // up.
  bool Pop(PenReading& reading);
  // CLOCK_MONOTONIC time the event thread last ran its loop (watchdog), 0 before start.
  std::int64_t HeartbeatNs() const { return heartbeat_ns_.load(std::memory_order_relaxed); }
  // False while no tablet is there (unplugged, or not yet plugged in): the kiosk then takes
  // mouse/touch input and lifts a stroke the tablet left with its tip down.
  bool Connected() const { return connected_.load(std::memory_order_acquire); }
  // The status at start (OpenPen): ok with the tablet's name, or missing with `absent_reason`
  // while the source waits for one. From then on every arrival and departure is reported.
  void ReportStarted(DeviceStatusBoard& board, const std::string& absent_reason);

 protected:
  // One of the seat's input devices came or went (libinput's DEVICE_ADDED / DEVICE_REMOVED) on
  // the device thread, or during Start's first scan; `ours`: it is the configured tablet. A
  // tablet may be several event nodes (pen and pad, say): it is there while any one of them is,
  // so its arrival and its departure are one status line each however many nodes it has, the
  // same words for every backend. Nothing is reported before ReportStarted.
  void DeviceAdded(bool ours, const std::string& tablet, DeviceStatusBoard* board);
  void DeviceRemoved(bool ours, DeviceStatusBoard* board);
  // A (re)start's first scan sees every device anew: forget the ones counted before.
  void ForgetDevices();

  PenQueue queue_;
  std::atomic<std::int64_t> heartbeat_ns_{0};

 private:
  std::atomic<bool> connected_{false};
  mutable std::mutex presence_mutex_;  // the device thread vs. ReportStarted and DeviceName
  int tablet_nodes_ = 0;
  std::string tablet_name_;
  bool reported_ = false;  // ReportStarted has run
  bool ever_connected_ = false;
};

std::unique_ptr<PenSource> MakeLibinputPenSource(const PenConfig& config, DeviceStatusBoard& board);

// Test fake: a tablet that is there or not; Push() delivers events as the thread would, and
// Unplug/Replug (and AddDevice/RemoveDevice for other devices or a tablet's extra nodes) go
// through the same presence reporting as libinput's DEVICE_REMOVED / DEVICE_ADDED.
class FakePenSource final : public PenSource {
 public:
  // `present`: a tablet is plugged in at start. Without one, Start fails (no libinput) unless
  // `waits_for_tablet`: then it runs like the libinput source and Replug plugs one in.
  explicit FakePenSource(bool present, bool waits_for_tablet = false)
      : present_(present), waits_(waits_for_tablet) {}
  const char* Name() const override { return "fake"; }
  bool Start(std::string* error) override {
    if (present_) {
      DeviceAdded(true, "fake tablet", nullptr);
      return true;
    }
    if (error) *error = "no pen tablet (fake)";
    return waits_;
  }
  void Stop() override {}
  bool Push(const PenReading& reading) {
    heartbeat_ns_.store(reading.time_ns, std::memory_order_relaxed);
    return queue_.TryPush(reading);
  }
  void Unplug(DeviceStatusBoard& board) { DeviceRemoved(true, &board); }
  void Replug(DeviceStatusBoard& board) { DeviceAdded(true, "fake tablet", &board); }
  void AddDevice(bool ours, const std::string& name, DeviceStatusBoard& board) {
    DeviceAdded(ours, name, &board);
  }
  void RemoveDevice(bool ours, DeviceStatusBoard& board) { DeviceRemoved(ours, &board); }

 private:
  bool present_;
  bool waits_;
};

// Starts `source` (the libinput one when null) and sets the "pen" status: ok with the tablet's
// name, or missing ("no pen tablet ...; mouse/touch fallback"). Returns null only when the source
// cannot run at all; with no tablet yet it returns the running source, which takes up a tablet
// plugged in later (the UI uses SDL2 pointer input while Connected() is false).
std::unique_ptr<PenSource> OpenPen(const PenConfig& config, DeviceStatusBoard& board,
                                   std::unique_ptr<PenSource> source = nullptr);

}  // namespace sas::platform
