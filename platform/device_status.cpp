// Device status board (see device_status.h).
#include "platform/device_status.h"

namespace sas::platform {

const char* DeviceStateName(DeviceState state) {
  switch (state) {
    case DeviceState::kOk:
      return "ok";
    case DeviceState::kMissing:
      return "missing";
    case DeviceState::kLost:
      return "lost";
    case DeviceState::kReconnecting:
      return "reconnecting";
    case DeviceState::kDisabled:
      return "disabled";
  }
  return "?";
}

void DeviceStatusBoard::Set(const std::string& device, DeviceState state,
                            const std::string& message, const std::string& backend) {
  bool changed = false;
  {
    std::lock_guard lock(mutex_);
    auto [it, inserted] = table_.try_emplace(device);
    DeviceStatus& status = it->second;
    status.device = device;
    changed = inserted || status.state != state || status.message != message ||
              (!backend.empty() && status.backend != backend);
    status.state = state;
    status.message = message;
    if (!backend.empty()) status.backend = backend;
  }
  if (!changed) return;
  // Logged outside our mutex: the logger has its own, and never calls back into us.
  const LogLevel level = (state == DeviceState::kOk || state == DeviceState::kDisabled)
                             ? LogLevel::kInfo
                             : LogLevel::kWarn;
  logger_->Write(level, device, std::string(DeviceStateName(state)) + ": " + message);
}

void DeviceStatusBoard::AddReconnect(const std::string& device) {
  std::lock_guard lock(mutex_);
  ++table_[device].reconnects;
}

void DeviceStatusBoard::AddFailure(const std::string& device) {
  std::lock_guard lock(mutex_);
  ++table_[device].failures;
}

void DeviceStatusBoard::SetEvents(const std::string& device, std::uint64_t events) {
  std::lock_guard lock(mutex_);
  table_[device].events = events;
}

DeviceStatus DeviceStatusBoard::Get(const std::string& device) const {
  std::lock_guard lock(mutex_);
  auto it = table_.find(device);
  if (it == table_.end()) {
    DeviceStatus unknown;
    unknown.device = device;
    return unknown;
  }
  return it->second;
}

std::vector<DeviceStatus> DeviceStatusBoard::All() const {
  std::lock_guard lock(mutex_);
  std::vector<DeviceStatus> out;
  for (const auto& [name, status] : table_) out.push_back(status);
  return out;
}

}  // namespace sas::platform
