// libinput tablet-tool source (see pen_source.h). libinput's udev backend needs udev to have
// initialised the devices (fine on the appliance); the kiosk user needs group `input`. libinput
// opens every event node of the seat O_RDWR | O_NONBLOCK (OpenRestricted adds O_CLOEXEC) and
// skips a node it cannot open that way, so read-only access is not enough.
#include <fcntl.h>
#include <libinput.h>
#include <libudev.h>
#include <linux/input-event-codes.h>
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <thread>

#include "platform/common/clock.h"
#include "platform/common/wake_event.h"
#include "platform/pen/libinput_open.h"
#include "platform/pen/pen_source.h"

namespace sas::platform {
namespace {

struct UdevDeleter {
  void operator()(udev* u) const { udev_unref(u); }
};
struct LibinputDeleter {
  void operator()(libinput* li) const { libinput_unref(li); }
};

// The pen's barrel buttons (linux/input-event-codes.h) as bits; 0 for any other button.
std::uint32_t BarrelBit(std::uint32_t code) {
  switch (code) {
    case BTN_STYLUS:
      return 1U;
    case BTN_STYLUS2:
      return 2U;
    case BTN_STYLUS3:
      return 4U;
    default:
      return 0U;
  }
}

class LibinputPenSource final : public PenSource {
 public:
  LibinputPenSource(PenConfig config, DeviceStatusBoard& board)
      : config_(std::move(config)), board_(&board) {}
  ~LibinputPenSource() override { Stop(); }
  const char* Name() const override { return "libinput"; }

  bool Start(std::string* error) override {
    Stop();
    udev_.reset(udev_new());
    if (!udev_) return Fail(error, "udev unavailable");
    input_.reset(libinput_udev_create_context(LibinputOpenInterface(), nullptr, udev_.get()));
    if (!input_) return Fail(error, "libinput context failed");
    if (libinput_udev_assign_seat(input_.get(), config_.seat.c_str()) != 0)
      return Fail(error,
                  "cannot assign " + config_.seat + " (no udev, or no access to /dev/input)");
    libinput_dispatch(input_.get());
    ForgetDevices();
    int devices = 0;
    while (libinput_event* event = libinput_get_event(input_.get())) {
      if (libinput_event_get_type(event) == LIBINPUT_EVENT_DEVICE_ADDED) {
        ++devices;
        libinput_device* device = libinput_event_get_device(event);
        DeviceAdded(IsOurTablet(device), libinput_device_get_name(device), nullptr);
      }
      libinput_event_destroy(event);
    }
    // With no tablet yet the thread runs all the same: libinput's udev backend delivers
    // DEVICE_ADDED for a tablet plugged in later, and the kiosk takes it up then.
    if (!Connected() && error) {
      *error = "no pen tablet among " + std::to_string(devices) + " input devices";
    }
    stop_.Open();
    thread_ = std::thread([this] { Run(); });
    return true;
  }

  void Stop() override {
    if (thread_.joinable()) {
      stop_.Signal();
      thread_.join();
    }
    stop_.Close();
    input_.reset();
    udev_.reset();
  }

 private:
  bool Fail(std::string* error, const std::string& why) {
    if (error) *error = why;
    input_.reset();
    udev_.reset();
    return false;
  }

  bool IsOurTablet(libinput_device* device) const {
    if (!libinput_device_has_capability(device, LIBINPUT_DEVICE_CAP_TABLET_TOOL)) return false;
    return config_.device_name_contains.empty() ||
           std::string(libinput_device_get_name(device)).find(config_.device_name_contains) !=
               std::string::npos;
  }

  void Run() {
    pollfd fds[2] = {{libinput_get_fd(input_.get()), POLLIN, 0}, {stop_.fd(), POLLIN, 0}};
    for (;;) {
      heartbeat_ns_.store(MonotonicNowNs(), std::memory_order_relaxed);
      // A bounded wait keeps the heartbeat fresh for the watchdog while the pen is idle.
      const int n = poll(fds, 2, 250);
      if (n < 0 && errno != EINTR) return;
      if (fds[1].revents != 0) return;
      libinput_dispatch(input_.get());
      while (libinput_event* event = libinput_get_event(input_.get())) {
        Handle(event);
        libinput_event_destroy(event);
      }
    }
  }

  void Handle(libinput_event* event) {
    const auto type = libinput_event_get_type(event);
    if (type == LIBINPUT_EVENT_DEVICE_REMOVED) {
      libinput_device* device = libinput_event_get_device(event);
      if (IsOurTablet(device)) {
        // No tip-up or proximity-out will come from it: a tablet plugged back must not start
        // with a stale tip-down (the kiosk lifts the stroke itself on the unplug).
        tip_down_ = false;
        in_proximity_ = false;
        barrel_buttons_ = 0;
      }
      DeviceRemoved(IsOurTablet(device), board_);
      return;
    }
    if (type == LIBINPUT_EVENT_DEVICE_ADDED) {
      libinput_device* device = libinput_event_get_device(event);
      DeviceAdded(IsOurTablet(device), libinput_device_get_name(device), board_);
      return;
    }
    if (type != LIBINPUT_EVENT_TABLET_TOOL_AXIS && type != LIBINPUT_EVENT_TABLET_TOOL_TIP &&
        type != LIBINPUT_EVENT_TABLET_TOOL_PROXIMITY && type != LIBINPUT_EVENT_TABLET_TOOL_BUTTON)
      return;
    libinput_event_tablet_tool* tool = libinput_event_get_tablet_tool_event(event);
    if (type == LIBINPUT_EVENT_TABLET_TOOL_BUTTON) {
      // A pen may have two or three barrel buttons; any of them held rolls. Other tools' buttons
      // (a puck's, an airbrush's) are no barrel button.
      const std::uint32_t bit = BarrelBit(libinput_event_tablet_tool_get_button(tool));
      if (bit == 0) return;
      if (libinput_event_tablet_tool_get_button_state(tool) == LIBINPUT_BUTTON_STATE_PRESSED)
        barrel_buttons_ |= bit;
      else
        barrel_buttons_ &= ~bit;
    }
    PenReading pen;
    pen.time_ns = static_cast<std::int64_t>(libinput_event_tablet_tool_get_time_usec(tool)) * 1000;
    pen.origin = PenOrigin::kTablet;
    pen.x_px = libinput_event_tablet_tool_get_x_transformed(
        tool, static_cast<uint32_t>(config_.screen_width_px));
    pen.y_px = libinput_event_tablet_tool_get_y_transformed(
        tool, static_cast<uint32_t>(config_.screen_height_px));
    libinput_tablet_tool* t = libinput_event_tablet_tool_get_tool(tool);
    pen.pressure =
        libinput_tablet_tool_has_pressure(t) ? libinput_event_tablet_tool_get_pressure(tool) : 0.0;
    if (libinput_tablet_tool_has_tilt(t)) {
      pen.tilt_x_deg = libinput_event_tablet_tool_get_tilt_x(tool);
      pen.tilt_y_deg = libinput_event_tablet_tool_get_tilt_y(tool);
    }
    if (type == LIBINPUT_EVENT_TABLET_TOOL_TIP) {
      tip_down_ = libinput_event_tablet_tool_get_tip_state(tool) == LIBINPUT_TABLET_TOOL_TIP_DOWN;
      pen.kind = tip_down_ ? PenReadingKind::kTipDown : PenReadingKind::kTipUp;
    } else if (type == LIBINPUT_EVENT_TABLET_TOOL_PROXIMITY) {
      in_proximity_ = libinput_event_tablet_tool_get_proximity_state(tool) ==
                      LIBINPUT_TABLET_TOOL_PROXIMITY_STATE_IN;
      pen.kind = in_proximity_ ? PenReadingKind::kProximityIn : PenReadingKind::kProximityOut;
      if (!in_proximity_) tip_down_ = false;
      if (!in_proximity_) barrel_buttons_ = 0;
    } else if (type == LIBINPUT_EVENT_TABLET_TOOL_BUTTON) {
      pen.kind = PenReadingKind::kButton;
    }
    pen.tip_down = tip_down_;
    pen.in_proximity = in_proximity_;
    pen.barrel_button = barrel_buttons_ != 0;
    queue_.TryPush(pen);
  }

  PenConfig config_;
  DeviceStatusBoard* board_;
  std::unique_ptr<udev, UdevDeleter> udev_;
  std::unique_ptr<libinput, LibinputDeleter> input_;
  WakeEvent stop_;
  std::thread thread_;
  bool tip_down_ = false;
  bool in_proximity_ = false;
  std::uint32_t barrel_buttons_ = 0;  // BarrelBit of each barrel button held
};

}  // namespace

std::unique_ptr<PenSource> MakeLibinputPenSource(const PenConfig& config,
                                                 DeviceStatusBoard& board) {
  return std::make_unique<LibinputPenSource>(config, board);
}

std::unique_ptr<PenSource> OpenPen(const PenConfig& config, DeviceStatusBoard& board,
                                   std::unique_ptr<PenSource> source) {
  if (!source) source = MakeLibinputPenSource(config, board);
  std::string error;
  if (!source->Start(&error)) {
    board.Set("pen", DeviceState::kMissing, error + "; mouse/touch fallback (no pressure or tilt)",
              source->Name());
    return nullptr;
  }
  source->ReportStarted(board, error);
  return source;
}

}  // namespace sas::platform
