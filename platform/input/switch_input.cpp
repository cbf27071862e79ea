// Keyboard token fallback (see switch_input.h).
#include "platform/input/switch_input.h"

namespace sas::platform {

bool KeyboardSwitchInput::OnKey(char key, bool down, std::int64_t time_ns) {
  if (key >= '1' && key <= '4') {
    if (!down) return true;  // toggles on key down; key repeat is the UI's to filter
    const int token = key - '1';
    placed_[token] = !placed_[token];
    queue_.TryPush(SwitchEvent{time_ns, static_cast<std::int8_t>(token), placed_[token]});
    return true;
  }
  if (key == 'r' || key == 'R') {
    if (down == record_down_) return true;
    record_down_ = down;
    queue_.TryPush(SwitchEvent{time_ns, static_cast<std::int8_t>(kRecordInput), down});
    return true;
  }
  return false;
}

}  // namespace sas::platform
