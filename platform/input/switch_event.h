#pragma once
// The token switches and the record button as timestamped events: whichever
// backend reads them (libgpiod lines, MCP2221A pins, keys 1-4 and R), the control thread sees the
// same small POD through an SPSC queue.

#include <cstdint>

namespace sas::platform {

inline constexpr int kTokenCount = 4;   // inputs 0..3: the four token switches
inline constexpr int kRecordInput = 4;  // input 4: the record button
inline constexpr int kSwitchInputCount = 5;

struct SwitchEvent {
  std::int64_t time_ns = 0;  // CLOCK_MONOTONIC, start of the (debounced) change
  std::int8_t input = 0;     // 0..3 token switch, 4 record button
  bool pressed = false;      // token present / button down
};

}  // namespace sas::platform
