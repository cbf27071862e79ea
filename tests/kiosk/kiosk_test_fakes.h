#pragma once
// Fakes the kiosk's device tests share: an MCP2221A token board.

#include <array>
#include <atomic>
#include <cstdint>

#include "platform/hid/mcp2221.h"

namespace sas::test {

// The MCP2221A token board: answers SET SRAM and GET GPIO like the datasheet; `present` false =
// unplugged (every USB transfer fails). Read from the adapter's poll thread, hence atomics.
struct TokenBoard {
  std::atomic<bool> present{true};
  std::array<std::atomic<int>, 4> level{1, 1, 1, 1};  // active low: 0 = token on the pad
};

class TokenBoardHid final : public platform::HidTransport {
 public:
  explicit TokenBoardHid(TokenBoard& board) : board_(&board) {}
  bool Write(const platform::Mcp2221Report& report) override {
    if (!board_->present) return false;
    last_ = report[0];
    return true;
  }
  bool Read(platform::Mcp2221Report& out, int /*timeout_ms*/) override {
    if (!board_->present) return false;
    out = platform::Mcp2221Report{};
    out[0] = last_;
    if (last_ == platform::kMcp2221CmdGetGpio) {
      for (std::size_t p = 0; p < 4; ++p) {
        out[2 + 2 * p] = static_cast<std::uint8_t>(board_->level[p].load());
        out[3 + 2 * p] = 1;  // input
      }
    }
    return true;
  }

 private:
  TokenBoard* board_;
  std::uint8_t last_ = 0;
};

}  // namespace sas::test
