// GPIO token switches (see gpio_switches.h).
#include "platform/gpio/gpio_switches.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <gpiod.hpp>

#include "platform/common/clock.h"

namespace sas::platform {
namespace {

constexpr int kHeartbeatMs = 250;

bool IsOffset(const std::string& spec) {
  return !spec.empty() && std::all_of(spec.begin(), spec.end(),
                                      [](unsigned char c) { return std::isdigit(c) != 0; });
}

// What a configuration can name on the opened chip: its size and its lines' names.
GpioChipInfo InfoOf(const gpiod::chip& chip) {
  GpioChipInfo info{chip.name(), chip.label(), chip.num_lines(), {}};
  for (unsigned offset = 0; offset < chip.num_lines(); ++offset)
    info.line_names.push_back(chip.get_line(offset).name());
  return info;
}

class LibgpiodEventSource final : public GpioEventSource {
 public:
  explicit LibgpiodEventSource(const GpioSwitchConfig& config)
      : chip_(config.chip, gpiod::chip::OPEN_LOOKUP) {
    if (!chip_) throw std::runtime_error("GPIO chip '" + config.chip + "' not found");
    // Resolved against this chip object, so all lines belong to one chip (one request), and
    // every line it lacks is named at once rather than libgpiod's first out_of_range.
    const std::vector<unsigned> offsets = ResolveGpioLines(InfoOf(chip_), config);
    for (int i = 0; i < kSwitchInputCount; ++i) {
      if (!config.lines[static_cast<std::size_t>(i)].empty()) inputs_.push_back(i);
    }
    bulk_ = chip_.get_lines(offsets);
    bulk_.request({"sketch-a-scratch", gpiod::line_request::EVENT_BOTH_EDGES,
                   gpiod::line_request::FLAG_BIAS_PULL_UP});
    describe_ = chip_.name() + " '" + chip_.label() + "' lines";
    for (unsigned offset : offsets) describe_ += " " + std::to_string(offset);
  }

  std::vector<pollfd> Fds() const override {
    std::vector<pollfd> fds;
    for (unsigned i = 0; i < bulk_.size(); ++i) fds.push_back({bulk_[i].event_get_fd(), POLLIN, 0});
    return fds;
  }

  bool Read(const std::vector<pollfd>& ready, std::vector<RawEdge>& out) override {
    for (std::size_t i = 0; i < ready.size() && i < bulk_.size(); ++i) {
      if ((ready[i].revents & (POLLERR | POLLHUP | POLLNVAL)) != 0) return false;
      if ((ready[i].revents & POLLIN) == 0) continue;
      try {
        for (const auto& event : bulk_[static_cast<unsigned>(i)].event_read_multiple()) {
          out.push_back({static_cast<std::int64_t>(event.timestamp.count()), inputs_[i],
                         event.event_type == gpiod::line_event::RISING_EDGE});
        }
      } catch (const std::exception&) {
        return false;
      }
    }
    return true;
  }

  std::array<bool, kSwitchInputCount> InitialLevels() override {
    std::array<bool, kSwitchInputCount> high;
    high.fill(true);
    const auto values = bulk_.get_values();
    for (std::size_t i = 0; i < values.size() && i < inputs_.size(); ++i)
      high[static_cast<std::size_t>(inputs_[i])] = values[i] != 0;
    return high;
  }

  std::string Describe() const override { return describe_; }

 private:
  gpiod::chip chip_;
  mutable gpiod::line_bulk bulk_;  // libgpiod 1.6 has no const operator[]
  std::vector<int> inputs_;        // bulk index -> input 0..4
  std::string describe_;
};

}  // namespace

std::vector<unsigned> ResolveGpioLines(const GpioChipInfo& chip, const GpioSwitchConfig& config) {
  const auto missing = MissingGpioLines(chip, config.lines);
  if (!missing.empty()) throw GpioLinesMissing(DescribeMissingGpioLines(chip, missing));
  std::vector<unsigned> offsets;
  for (const std::string& spec : config.lines) {
    if (spec.empty()) continue;
    if (IsOffset(spec)) {
      offsets.push_back(static_cast<unsigned>(std::stoul(spec)));
    } else {
      const auto it = std::find(chip.line_names.begin(), chip.line_names.end(), spec);
      offsets.push_back(static_cast<unsigned>(it - chip.line_names.begin()));
    }
  }
  return offsets;
}

std::unique_ptr<GpioEventSource> MakeLibgpiodEventSource(const GpioSwitchConfig& config) {
  return std::make_unique<LibgpiodEventSource>(config);
}

void GpioEdgeProcessor::SetInitialLevels(const std::array<bool, kSwitchInputCount>& high) {
  for (int i = 0; i < kSwitchInputCount; ++i)
    debouncer_.SetInitial(i, high[static_cast<std::size_t>(i)] != active_low_);
}

GpioSwitchInput::GpioSwitchInput(GpioSwitchConfig config, std::unique_ptr<GpioEventSource> source)
    : config_(std::move(config)),
      source_(std::move(source)),
      processor_(config_.active_low, static_cast<std::int64_t>(config_.debounce_ms * 1e6)) {}

GpioSwitchInput::~GpioSwitchInput() {
  Stop();
}

bool GpioSwitchInput::Start(std::string* error) {
  Stop();
  lines_missing_ = false;
  if (!source_) {
    try {
      source_ = factory_ ? factory_() : MakeLibgpiodEventSource(config_);
      if (!source_) throw std::runtime_error("GPIO lines unavailable");
    } catch (const GpioLinesMissing& e) {
      lines_missing_ = true;
      if (error) *error = e.what();
      return false;
    } catch (const std::exception& e) {
      if (error) *error = e.what();
      return false;
    }
  }
  describe_ = source_->Describe();
  lost_.store(false, std::memory_order_release);
  const auto levels = source_->InitialLevels();
  processor_.SetInitialLevels(levels);
  for (int i = 0; i < kSwitchInputCount; ++i)
    initial_[static_cast<std::size_t>(i)] = processor_.Pressed(i);
  // Tokens already on their switches at start count as placed now.
  const std::int64_t now_ns = MonotonicNowNs();
  for (int i = 0; i < kTokenCount; ++i) {
    if (initial_[static_cast<std::size_t>(i)])
      queue_.TryPush(SwitchEvent{now_ns, static_cast<std::int8_t>(i), true});
  }
  if (!stop_.Open()) {
    if (error) *error = "eventfd failed";
    return false;
  }
  thread_ = std::thread([this] { Run(); });
  return true;
}

void GpioSwitchInput::Stop() {
  if (thread_.joinable()) {
    stop_.Signal();
    thread_.join();
  }
  stop_.Close();
}

void GpioSwitchInput::Run() {
  for (;;) {
    if (!Listen()) return;  // Stop()
    // The lines failed: the fds are dead (poll would report them again at once), so close them
    // and say it once; tokens stay as they were, the keyboard still works.
    source_.reset();
    lost_.store(true, std::memory_order_release);
    if (board_ != nullptr) {
      board_->AddFailure("switches");
      board_->Set("switches", DeviceState::kLost,
                  "GPIO lines lost (" + describe_ +
                      "); tokens frozen, keys 1-4 (R records) still work, waiting for them to "
                      "return",
                  "gpio");
    }
    // Retry quietly, the thread's heartbeat going on for the watchdog: no line per attempt.
    int waited_ms = 0;
    for (;;) {
      heartbeat_ns_.store(MonotonicNowNs(), std::memory_order_relaxed);
      if (WaitForStop(kHeartbeatMs)) return;
      waited_ms += kHeartbeatMs;
      if (waited_ms < kReopenIntervalMs) continue;
      waited_ms = 0;
      if (Reopen(MonotonicNowNs())) break;
    }
    lost_.store(false, std::memory_order_release);
    if (board_ != nullptr) {
      board_->AddReconnect("switches");
      board_->Set("switches", DeviceState::kOk, "GPIO lines back (" + describe_ + ")", "gpio");
    }
  }
}

bool GpioSwitchInput::Listen() {
  std::vector<pollfd> fds = source_->Fds();
  fds.push_back({stop_.fd(), POLLIN, 0});
  std::vector<pollfd> ready;
  std::vector<RawEdge> edges;
  auto sink = [this](const SwitchEvent& e) { queue_.TryPush(e); };
  for (;;) {
    const std::int64_t deadline_ns = processor_.NextDeadlineNs();
    const std::int64_t now_ns = MonotonicNowNs();
    heartbeat_ns_.store(now_ns, std::memory_order_relaxed);
    // Wake at least every 250 ms so the watchdog sees this thread alive while nobody touches a
    // token; sooner when a debounce deadline is due.
    int timeout_ms = kHeartbeatMs;
    if (deadline_ns >= 0) {
      const std::int64_t wait_ns = std::max<std::int64_t>(0, deadline_ns - now_ns);
      timeout_ms = std::min(kHeartbeatMs, static_cast<int>((wait_ns + kNsPerMs - 1) / kNsPerMs));
    }
    for (auto& fd : fds) fd.revents = 0;
    const int n = poll(fds.data(), static_cast<nfds_t>(fds.size()), timeout_ms);
    if (n < 0 && errno != EINTR) return true;
    if (fds.back().revents != 0) return false;  // Stop()
    if (n > 0) {
      ready.assign(fds.begin(), fds.end() - 1);
      edges.clear();
      if (!source_->Read(ready, edges)) return true;
      // Lines are read fd by fd: restore global time order before the state machines see them.
      std::stable_sort(edges.begin(), edges.end(),
                       [](const RawEdge& a, const RawEdge& b) { return a.time_ns < b.time_ns; });
      for (const RawEdge& edge : edges) processor_.OnEdge(edge, sink);
      edges_.fetch_add(edges.size(), std::memory_order_relaxed);
    }
    processor_.Advance(MonotonicNowNs(), sink);
  }
}

bool GpioSwitchInput::Reopen(std::int64_t now_ns) {
  try {
    source_ = factory_ ? factory_() : MakeLibgpiodEventSource(config_);
    if (!source_) return false;
    const auto levels = source_->InitialLevels();
    // Whatever changed while nobody listened is a change now, so the token rule sees it.
    GpioEdgeProcessor fresh(config_.active_low, 0);
    fresh.SetInitialLevels(levels);
    for (int i = 0; i < kSwitchInputCount; ++i) {
      if (fresh.Pressed(i) != processor_.Pressed(i))
        queue_.TryPush(SwitchEvent{now_ns, static_cast<std::int8_t>(i), fresh.Pressed(i)});
    }
    processor_.SetInitialLevels(levels);
    describe_ = source_->Describe();
    return true;
  } catch (const std::exception&) {
    source_.reset();
    return false;
  }
}

bool GpioSwitchInput::WaitForStop(int timeout_ms) {
  pollfd stop{stop_.fd(), POLLIN, 0};
  return poll(&stop, 1, timeout_ms) > 0 && stop.revents != 0;
}

}  // namespace sas::platform
