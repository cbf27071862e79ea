// The pen source's presence reporting, shared by every backend (see pen_source.h).
#include "platform/pen/pen_source.h"

namespace sas::platform {

bool PenSource::Pop(PenReading& reading) {
  if (!queue_.TryPop(reading)) return false;
  // Whatever a backend queued, a reading leaves here meaning one thing for the screen and the
  // probe: a tip out of range is up, and an up tip presses with nothing; a pen out of range holds
  // no button (the next stroke must not start rolling on a release that never came).
  reading.origin = PenOrigin::kTablet;
  reading.tip_down = reading.tip_down && reading.in_proximity;
  reading.barrel_button = reading.barrel_button && reading.in_proximity;
  if (!reading.tip_down) reading.pressure = 0.0;
  return true;
}

std::string PenSource::DeviceName() const {
  std::lock_guard lock(presence_mutex_);
  return tablet_name_.empty() ? std::string(Name()) : tablet_name_;
}

void PenSource::ReportStarted(DeviceStatusBoard& board, const std::string& absent_reason) {
  // Under the presence lock: a tablet the device thread sees meanwhile is reported after this
  // line, never overwritten by it.
  std::lock_guard lock(presence_mutex_);
  reported_ = true;
  if (tablet_nodes_ > 0) {
    ever_connected_ = true;
    board.Set("pen", DeviceState::kOk, "pen tablet '" + tablet_name_ + "' via " + Name(), Name());
    return;
  }
  board.Set("pen", DeviceState::kMissing,
            absent_reason + "; mouse/touch fallback (no pressure or tilt) until one is plugged in",
            Name());
}

void PenSource::DeviceAdded(bool ours, const std::string& tablet, DeviceStatusBoard* board) {
  if (!ours) return;
  std::lock_guard lock(presence_mutex_);
  if (tablet_nodes_++ > 0) return;  // another node of a tablet already there
  tablet_name_ = tablet;
  connected_.store(true, std::memory_order_release);
  if (board == nullptr || !reported_) return;
  if (ever_connected_) {
    board->AddReconnect("pen");
    board->Set("pen", DeviceState::kOk, "pen tablet '" + tablet + "' back", Name());
  } else {
    board->Set("pen", DeviceState::kOk, "pen tablet '" + tablet + "' plugged in", Name());
  }
  ever_connected_ = true;
}

void PenSource::DeviceRemoved(bool ours, DeviceStatusBoard* board) {
  if (!ours) return;
  std::lock_guard lock(presence_mutex_);
  if (tablet_nodes_ == 0 || --tablet_nodes_ > 0) return;  // some node of it is still there
  connected_.store(false, std::memory_order_release);
  if (board == nullptr || !reported_) return;
  board->AddFailure("pen");
  board->Set("pen", DeviceState::kLost,
             "pen tablet '" + tablet_name_ + "' unplugged; mouse/touch fallback", Name());
}

void PenSource::ForgetDevices() {
  std::lock_guard lock(presence_mutex_);
  tablet_nodes_ = 0;
  connected_.store(false, std::memory_order_release);
}

}  // namespace sas::platform
