// MCP2221A token switches (see mcp2221.h).
#include "platform/hid/mcp2221.h"

#include <hidapi/hidapi.h>

#include <chrono>

#include "platform/common/clock.h"
#include "platform/hid/hid_devices.h"

namespace sas::platform {

Mcp2221Report BuildSetSramGpioInputs() {
  Mcp2221Report r{};
  r[0] = kMcp2221CmdSetSram;
  // Bytes 2..6 (clock divider, DAC, ADC, interrupt) keep bit 7 clear: "do not alter".
  r[7] = 0xFF;  // alter GP designation (bit 7), as checked on the device
  for (int p = 0; p < 4; ++p) r[8 + static_cast<std::size_t>(p)] = 0x08;  // GPIO, input
  return r;
}

Mcp2221Report BuildGetGpioValues() {
  Mcp2221Report r{};
  r[0] = kMcp2221CmdGetGpio;
  return r;
}

std::optional<Mcp2221GpioState> DecodeGetGpioValues(const Mcp2221Report& response) {
  if (response[0] != kMcp2221CmdGetGpio || response[1] != 0) return std::nullopt;
  Mcp2221GpioState state;
  for (std::size_t p = 0; p < 4; ++p) {
    const std::uint8_t value = response[2 + 2 * p];
    const std::uint8_t direction = response[3 + 2 * p];
    if (value == kMcp2221NotGpio || direction == kMcp2221NotGpio) return std::nullopt;
    state.high[p] = value != 0;
    state.input[p] = direction == 1;
  }
  return state;
}

bool DecodeSetSramAck(const Mcp2221Report& response) {
  return response[0] == kMcp2221CmdSetSram && response[1] == 0;
}

namespace {

// RAII over hid_device*; hid_init/hid_exit are reference-free in hidapi, so init once per process.
class HidapiTransport final : public HidTransport {
 public:
  explicit HidapiTransport(hid_device* device) : device_(device) {}
  ~HidapiTransport() override { hid_close(device_); }
  HidapiTransport(const HidapiTransport&) = delete;
  HidapiTransport& operator=(const HidapiTransport&) = delete;

  bool Write(const Mcp2221Report& report) override {
    std::array<unsigned char, kMcp2221ReportSize + 1> out{};  // byte 0: no report ID
    std::copy(report.begin(), report.end(), out.begin() + 1);
    return hid_write(device_, out.data(), out.size()) == static_cast<int>(out.size());
  }
  bool Read(Mcp2221Report& report, int timeout_ms) override {
    return hid_read_timeout(device_, report.data(), report.size(), timeout_ms) ==
           static_cast<int>(report.size());
  }

 private:
  hid_device* device_;
};

}  // namespace

HidOpener MakeHidapiOpener(const std::string& path) {
  return [path]() -> std::unique_ptr<HidTransport> {
    static const int init = hid_init();
    if (init != 0) return nullptr;
    hid_device* device = path.empty() ? hid_open(kMcp2221VendorId, kMcp2221ProductId, nullptr)
                                      : hid_open_path(path.c_str());
    if (device == nullptr) return nullptr;
    return std::make_unique<HidapiTransport>(device);
  };
}

Mcp2221SwitchInput::Mcp2221SwitchInput(Mcp2221SwitchConfig config, HidOpener opener,
                                       DeviceStatusBoard& board)
    : config_(std::move(config)),
      opener_(std::move(opener)),
      board_(&board),
      debouncer_(static_cast<std::int64_t>(config_.debounce_ms * 1e6)) {}

Mcp2221SwitchInput::~Mcp2221SwitchInput() {
  Stop();
}

bool Mcp2221SwitchInput::Connect(std::string* error) {
  auto transport = opener_();
  if (!transport) {
    if (error) *error = "no MCP2221A USB adapter (04d8:00dd) found";
    return false;
  }
  Mcp2221Report response{};
  if (!transport->Write(BuildSetSramGpioInputs()) ||
      !transport->Read(response, config_.read_timeout_ms) || !DecodeSetSramAck(response)) {
    if (error) *error = "MCP2221A did not accept the GPIO input settings (SET SRAM 0x60)";
    return false;
  }
  transport_ = std::move(transport);
  primed_ = false;
  return true;
}

void Mcp2221SwitchInput::Lost(const std::string& why) {
  transport_.reset();
  board_->AddFailure("switches");
  board_->Set("switches", DeviceState::kLost,
              "MCP2221A adapter " + why + "; tokens frozen, waiting for it to return", "mcp2221");
}

void Mcp2221SwitchInput::Step(std::int64_t now_ns) {
  heartbeat_ns_.store(now_ns, std::memory_order_relaxed);
  if (!transport_) {
    if (now_ns < next_reopen_ns_) return;
    next_reopen_ns_ = now_ns + static_cast<std::int64_t>(config_.reopen_interval_ms * 1e6);
    if (!Connect(nullptr)) return;  // still away: no new log line
    if (ever_connected_) board_->AddReconnect("switches");
    board_->Set(
        "switches", DeviceState::kOk,
        ever_connected_ ? "MCP2221A adapter back, GP0-3 polled" : "MCP2221A adapter, GP0-3 polled",
        "mcp2221");
    ever_connected_ = true;
  }
  Mcp2221Report response{};
  if (!transport_->Write(BuildGetGpioValues()) ||
      !transport_->Read(response, config_.read_timeout_ms)) {
    Lost("unplugged (USB write/read failed)");
    next_reopen_ns_ = now_ns + static_cast<std::int64_t>(config_.reopen_interval_ms * 1e6);
    return;
  }
  const auto state = DecodeGetGpioValues(response);
  if (!state) return;  // a malformed answer is skipped, the next poll asks again
  ++polls_;
  auto sink = [this](const SwitchEvent& e) { queue_.TryPush(e); };
  for (int p = 0; p < kTokenCount; ++p) {
    const bool pressed = state->high[static_cast<std::size_t>(p)] != config_.active_low;
    if (!primed_) {
      // After (re)connect: tokens on their pads count as placed now, lifted ones as lifted.
      if (pressed != debouncer_.Stable(p))
        queue_.TryPush(SwitchEvent{now_ns, static_cast<std::int8_t>(p), pressed});
      debouncer_.SetInitial(p, pressed);
    } else {
      debouncer_.Feed(p, pressed, now_ns, sink);
    }
  }
  primed_ = true;
  debouncer_.Advance(now_ns, sink);
}

bool Mcp2221SwitchInput::Start(std::string* error) {
  Stop();
  if (!transport_ && !Connect(error)) return false;
  ever_connected_ = true;
  board_->Set("switches", DeviceState::kOk, "MCP2221A adapter, GP0-3 polled", "mcp2221");
  StartWaiting();
  return true;
}

void Mcp2221SwitchInput::StartWaiting() {
  if (thread_.joinable()) return;
  {
    std::lock_guard lock(mutex_);
    stop_ = false;
  }
  thread_ = std::thread([this] { Run(); });
}

void Mcp2221SwitchInput::Stop() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void Mcp2221SwitchInput::Run() {
  const auto period = std::chrono::microseconds(static_cast<long>(config_.poll_interval_ms * 1e3));
  auto next = std::chrono::steady_clock::now();
  std::unique_lock lock(mutex_);
  while (!stop_) {
    lock.unlock();
    Step(MonotonicNowNs());
    lock.lock();
    next += period;
    wake_.wait_until(lock, next, [this] { return stop_; });
  }
}

}  // namespace sas::platform
