#pragma once
// Which texture the tokens select: exactly one token on a switch -> its texture; none ->
// the default texture; several -> the one placed last (when it is lifted, the most recently placed
// of those still on their switches). Control-thread logic fed by SwitchEvents.

#include <array>
#include <cstdint>

#include "platform/input/switch_event.h"

namespace sas::platform {

class TokenSelector {
 public:
  static constexpr int kDefaultTexture = -1;

  // Applies a token event (record-button events are ignored). True when the selection changed.
  bool Apply(const SwitchEvent& event);
  // Token index 0..3 whose texture is shown, or kDefaultTexture.
  int Selected() const { return selected_; }
  bool Present(int token) const { return order_[static_cast<std::size_t>(token)] != 0; }

 private:
  int Recompute() const;
  std::array<std::uint64_t, kTokenCount> order_{};  // placement sequence number, 0 = absent
  std::uint64_t next_order_ = 1;
  int selected_ = kDefaultTexture;
};

}  // namespace sas::platform
