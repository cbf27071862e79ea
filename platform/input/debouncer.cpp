// Debouncer (see debouncer.h).
#include "platform/input/debouncer.h"

namespace sas::platform {

void Debouncer::SetInitial(int input, bool pressed) {
  Line& line = lines_[static_cast<std::size_t>(input)];
  line.stable = pressed;
  line.candidate = pressed;
  line.pending = false;
}

std::int64_t Debouncer::NextDeadlineNs() const {
  std::int64_t deadline = -1;
  for (const Line& line : lines_) {
    if (!line.pending) continue;
    const std::int64_t t = line.last_edge_ns + debounce_ns_;
    if (deadline < 0 || t < deadline) deadline = t;
  }
  return deadline;
}

}  // namespace sas::platform
