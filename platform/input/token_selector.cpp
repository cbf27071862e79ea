// Token selection (see token_selector.h).
#include "platform/input/token_selector.h"

namespace sas::platform {

bool TokenSelector::Apply(const SwitchEvent& event) {
  if (event.input < 0 || event.input >= kTokenCount) return false;
  auto& slot = order_[static_cast<std::size_t>(event.input)];
  if (event.pressed) {
    if (slot == 0) slot = next_order_++;
  } else {
    slot = 0;
  }
  const int before = selected_;
  selected_ = Recompute();
  return selected_ != before;
}

int TokenSelector::Recompute() const {
  int best = kDefaultTexture;
  std::uint64_t best_order = 0;
  for (int i = 0; i < kTokenCount; ++i) {
    if (order_[static_cast<std::size_t>(i)] > best_order) {
      best_order = order_[static_cast<std::size_t>(i)];
      best = i;
    }
  }
  return best;
}

}  // namespace sas::platform
