#pragma once
// Software debounce on event timestamps, one state machine per input (libgpiod's v1 kernel API
// has no debounce and conductive-ink token contacts chatter).
// A change is accepted once the input has stayed at the new level for `debounce_ns` since its last
// edge; the emitted event carries the time of the first edge of the burst (closest to the real
// contact time). Bursts that return to the old level before the quiet period emit nothing.
// Edges must be fed in timestamp order; Advance(t) commits what was stable by time t.
// Pure logic, no clock and no I/O: the GPIO and MCP2221A backends and the tests drive the same
// code.

#include <array>
#include <cstdint>

#include "platform/input/switch_event.h"

namespace sas::platform {

class Debouncer {
 public:
  explicit Debouncer(std::int64_t debounce_ns = 30'000'000) : debounce_ns_(debounce_ns) {}

  // Sets the debounced level without an event (the level read at start-up).
  void SetInitial(int input, bool pressed);
  // One raw edge/sample of `input` at level `pressed` observed at `time_ns`. Commits pending
  // changes of every input that were stable before `time_ns` first (emits into `sink`).
  template <typename Sink>
  void Feed(int input, bool pressed, std::int64_t time_ns, Sink&& sink) {
    Advance(time_ns, sink);
    Line& line = lines_[static_cast<std::size_t>(input)];
    if (!line.pending) {
      if (pressed == line.stable) return;
      line.pending = true;
      line.burst_start_ns = time_ns;
    } else if (pressed == line.candidate) {
      return;  // a repeated sample (or a missed opposite edge) is no new edge
    }
    line.candidate = pressed;
    line.last_edge_ns = time_ns;
    // Back at the stable level: still pending until quiet, then dropped without an event.
  }
  // Commits every pending change whose quiet period ended by `now_ns`.
  template <typename Sink>
  void Advance(std::int64_t now_ns, Sink&& sink) {
    for (std::size_t i = 0; i < lines_.size(); ++i) {
      Line& line = lines_[i];
      if (!line.pending || now_ns - line.last_edge_ns < debounce_ns_) continue;
      line.pending = false;
      if (line.candidate == line.stable) continue;
      line.stable = line.candidate;
      sink(SwitchEvent{line.burst_start_ns, static_cast<std::int8_t>(i), line.stable});
    }
  }
  // Earliest time at which Advance could emit, or -1 when nothing is pending (poll timeout).
  std::int64_t NextDeadlineNs() const;
  bool Stable(int input) const { return lines_[static_cast<std::size_t>(input)].stable; }
  std::int64_t debounce_ns() const { return debounce_ns_; }

 private:
  struct Line {
    bool stable = false;
    bool candidate = false;
    bool pending = false;
    std::int64_t burst_start_ns = 0;
    std::int64_t last_edge_ns = 0;
  };
  std::int64_t debounce_ns_;
  std::array<Line, kSwitchInputCount> lines_{};
};

}  // namespace sas::platform
