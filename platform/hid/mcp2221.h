#pragma once
// Token switches on a Microchip MCP2221A USB-HID adapter (GP0-GP3), for kiosk PCs without a GPIO
// header. Protocol from the MCP2221A datasheet (DS20005565): 64-byte reports with no report ID
// (hidapi writes 65 bytes, byte 0 = 0); the response echoes the command in byte 0 and a status in
// byte 1 (0 = ok).
//  - 0x60 SET SRAM SETTINGS: byte 7 = alter-GP-designation flag, bytes 8..11 = GP0..3 setting
//    (bits 2:0 designation, 0 = GPIO; bit 3 direction, 1 = input). SRAM is lost at power-up, so
//    it is sent at every (re)connect.
//  - 0x51 GET GPIO VALUES: pin p value at response[2+2p] (0xEE: pin is not a GPIO), direction at
//    response[3+2p] (1 = input).
// The adapter has no interrupt pin we could use through hidapi, so the poller asks every
// 10-20 ms and feeds the samples to the same Debouncer as the GPIO backend. Unplugging shows up
// as a failed write/read: status "lost", the poller retries opening; on replug it sends 0x60
// again and resumes ("ok", reconnects + 1). The record button is key R (the adapter has 4 pins).

#include <array>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "platform/device_status.h"
#include "platform/input/debouncer.h"
#include "platform/input/switch_input.h"

namespace sas::platform {

inline constexpr std::size_t kMcp2221ReportSize = 64;
using Mcp2221Report = std::array<std::uint8_t, kMcp2221ReportSize>;

inline constexpr std::uint8_t kMcp2221CmdGetGpio = 0x51;
inline constexpr std::uint8_t kMcp2221CmdSetSram = 0x60;
inline constexpr std::uint8_t kMcp2221NotGpio = 0xEE;

// SET SRAM SETTINGS making GP0..3 GPIO inputs, touching nothing else.
Mcp2221Report BuildSetSramGpioInputs();
Mcp2221Report BuildGetGpioValues();

struct Mcp2221GpioState {
  std::array<bool, 4> high{};
  std::array<bool, 4> input{};
};
// Decodes a GET GPIO VALUES response; nullopt when it is not one, reports an error status, or a
// pin is not configured as GPIO.
std::optional<Mcp2221GpioState> DecodeGetGpioValues(const Mcp2221Report& response);
// True when `response` acknowledges SET SRAM SETTINGS.
bool DecodeSetSramAck(const Mcp2221Report& response);

// The HID device, move-only and RAII in the real implementation; faked in tests.
class HidTransport {
 public:
  virtual ~HidTransport() = default;
  // Sends one 64-byte output report. False when the device is gone.
  virtual bool Write(const Mcp2221Report& report) = 0;
  // Reads one 64-byte input report within `timeout_ms`. False on error or timeout.
  virtual bool Read(Mcp2221Report& report, int timeout_ms) = 0;
};

// Opens the first MCP2221A (or the one at `path` when non-empty); null when absent.
using HidOpener = std::function<std::unique_ptr<HidTransport>()>;
HidOpener MakeHidapiOpener(const std::string& path = {});

struct Mcp2221SwitchConfig {
  std::string path;  // hidraw path; empty = first 04d8:00dd found
  bool active_low = true;
  double debounce_ms = 30.0;
  double poll_interval_ms = 15.0;
  double reopen_interval_ms = 500.0;
  int read_timeout_ms = 100;
};

class Mcp2221SwitchInput final : public SwitchInput {
 public:
  Mcp2221SwitchInput(Mcp2221SwitchConfig config, HidOpener opener, DeviceStatusBoard& board);
  ~Mcp2221SwitchInput() override;
  const char* Name() const override { return "mcp2221"; }
  // Opens the adapter once; false (error set) when it is absent. Then starts the poll thread.
  bool Start(std::string* error) override;
  // Starts the poll thread without an adapter: it connects whenever one is plugged in (status
  // "ok" then). For backend = "mcp2221" when the adapter enumerates after the kiosk started.
  void StartWaiting();
  void Stop() override;

  // One poll step at `now_ns` (what the thread does every poll interval); public so tests can
  // drive the protocol, debounce and unplug handling without a thread or a clock.
  void Step(std::int64_t now_ns);
  bool Connected() const { return transport_ != nullptr; }
  bool OpenForTest(std::string* error) { return Connect(error); }

 private:
  bool Connect(std::string* error);
  void Lost(const std::string& why);
  void Run();

  Mcp2221SwitchConfig config_;
  HidOpener opener_;
  DeviceStatusBoard* board_;
  std::unique_ptr<HidTransport> transport_;
  Debouncer debouncer_;
  bool ever_connected_ = false;
  bool primed_ = false;  // first sample after (re)connect sets the level without events
  std::int64_t next_reopen_ns_ = 0;
  std::uint64_t polls_ = 0;

  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace sas::platform
