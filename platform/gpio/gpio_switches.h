#pragma once
// Token switches and record button on GPIO lines (libgpiod 1.6, v1 character-device API).
//
// Split in two so tests drive the real event processing with a fake fd source:
//  - GpioEventSource: the fds to poll and a Read() that turns ready fds into raw edges
//    (timestamp, input, rising). LibgpiodEventSource is the real one: one chip object looked up
//    once, lines resolved by offset or name on that same object (requesting lines from separate
//    find_line() calls fails with EINVAL), one request with pull-up bias and both edges.
//  - GpioSwitchInput: the event thread. It blocks in poll() on the source's fds plus a stop
//    eventfd, with the debouncer's next deadline as timeout; edges are processed in timestamp
//    order through GpioEdgeProcessor (edge -> level -> active-low -> Debouncer) into the queue.
// Switches close to ground against the pull-up, so a token present reads low (active_low).

#include <poll.h>

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "platform/common/wake_event.h"
#include "platform/device_status.h"
#include "platform/gpio/gpio_chips.h"
#include "platform/input/debouncer.h"
#include "platform/input/switch_input.h"

namespace sas::platform {

struct RawEdge {
  std::int64_t time_ns = 0;  // CLOCK_MONOTONIC (the kernel's event timestamp)
  int input = 0;             // 0..3 token, 4 record
  bool rising = false;
};

struct GpioSwitchConfig {
  std::string chip = "gpiochip0";  // name, path or label (libgpiod lookup)
  // Five entries: tokens 1-4 then the record button; each an offset ("17") or a line name
  // ("GPIO17"). An empty record entry means no record button on GPIO.
  std::array<std::string, kSwitchInputCount> lines = {"17", "27", "22", "23", "24"};
  bool active_low = true;  // switch to ground, pull-up: pressed = low
  double debounce_ms = 30.0;
};

class GpioEventSource {
 public:
  virtual ~GpioEventSource() = default;
  // One pollfd per fd to wait on (events = POLLIN).
  virtual std::vector<pollfd> Fds() const = 0;
  // Appends the edges behind the ready fds (revents set by poll). Returns false on a fatal error.
  virtual bool Read(const std::vector<pollfd>& ready, std::vector<RawEdge>& out) = 0;
  // Raw line levels (true = high) at start, per input; missing inputs read as high.
  virtual std::array<bool, kSwitchInputCount> InitialLevels() = 0;
  virtual std::string Describe() const = 0;
};

// The configured chip is there but lacks configured lines: a mistake in the configuration (or a
// chip other than the one it was written for), not a device that is absent.
class GpioLinesMissing : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The offsets of the configured lines on `chip`, in input order (empty entries left out). Throws
// GpioLinesMissing naming every line the chip lacks (DescribeMissingGpioLines).
std::vector<unsigned> ResolveGpioLines(const GpioChipInfo& chip, const GpioSwitchConfig& config);

// Set-up: throws std::system_error / std::runtime_error when the chip is missing, and
// GpioLinesMissing when it lacks a configured line.
std::unique_ptr<GpioEventSource> MakeLibgpiodEventSource(const GpioSwitchConfig& config);

// The event-processing unit: raw edges in timestamp order -> debounced SwitchEvents.
class GpioEdgeProcessor {
 public:
  GpioEdgeProcessor(bool active_low, std::int64_t debounce_ns)
      : active_low_(active_low), debouncer_(debounce_ns) {}
  void SetInitialLevels(const std::array<bool, kSwitchInputCount>& high);
  template <typename Sink>
  void OnEdge(const RawEdge& edge, Sink&& sink) {
    debouncer_.Feed(edge.input, edge.rising != active_low_, edge.time_ns, sink);
  }
  template <typename Sink>
  void Advance(std::int64_t now_ns, Sink&& sink) {
    debouncer_.Advance(now_ns, sink);
  }
  std::int64_t NextDeadlineNs() const { return debouncer_.NextDeadlineNs(); }
  bool Pressed(int input) const { return debouncer_.Stable(input); }

 private:
  bool active_low_;
  Debouncer debouncer_;
};

// Lines that fail once running (a chip on a removable board, a driver unbound: poll reports
// POLLERR or reading an event fails) are a lost device, not the end of the thread: one "lost"
// status line (tokens frozen, keys 1-4 still work), then the thread stays alive for the watchdog
// and tries to open the lines again every `kReopenIntervalMs`; when they answer, the switches'
// levels at that moment count as changes (a token placed meanwhile is placed now) and one "ok"
// line says they are back.
class GpioSwitchInput final : public SwitchInput {
 public:
  using SourceFactory = std::function<std::unique_ptr<GpioEventSource>()>;
  static constexpr int kReopenIntervalMs = 1000;

  // `source` may be null: Start() then builds the libgpiod source from `config` (and reports a
  // missing chip as an error rather than an exception).
  GpioSwitchInput(GpioSwitchConfig config, std::unique_ptr<GpioEventSource> source = nullptr);
  ~GpioSwitchInput() override;
  const char* Name() const override { return "gpio"; }
  // Where loss and return are reported (status key "switches"); set before Start.
  void ReportTo(DeviceStatusBoard* board) { board_ = board; }
  // How the lines are opened again after a loss (may throw); default: libgpiod from `config`.
  void SetSourceFactory(SourceFactory factory) { factory_ = std::move(factory); }
  bool Start(std::string* error) override;
  void Stop() override;
  std::uint64_t EdgesSeen() const { return edges_.load(std::memory_order_relaxed); }
  // Debounced state at start (after Start): which switches are closed.
  bool InitiallyPressed(int input) const { return initial_[static_cast<std::size_t>(input)]; }

  // True while the lines are lost (after a failure, until they are opened again).
  bool lost() const { return lost_.load(std::memory_order_acquire); }
  // True when Start failed because the chip lacks configured lines (GpioLinesMissing): the
  // configuration is wrong, which deserves a warning even when another backend takes over.
  bool lines_missing() const { return lines_missing_; }

 private:
  void Run();
  // Waits for edges until Stop() (returns false) or the lines fail (returns true).
  bool Listen();
  // After a failure: true when the lines opened again (events for what changed meanwhile queued).
  bool Reopen(std::int64_t now_ns);
  // Waits up to `timeout_ms` for Stop(); true when it came.
  bool WaitForStop(int timeout_ms);

  GpioSwitchConfig config_;
  std::unique_ptr<GpioEventSource> source_;
  SourceFactory factory_;
  DeviceStatusBoard* board_ = nullptr;
  std::string describe_;
  std::atomic<bool> lost_{false};
  bool lines_missing_ = false;
  GpioEdgeProcessor processor_;
  std::array<bool, kSwitchInputCount> initial_{};
  WakeEvent stop_;
  std::thread thread_;
  std::atomic<std::uint64_t> edges_{0};
};

}  // namespace sas::platform
