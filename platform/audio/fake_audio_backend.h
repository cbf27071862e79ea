#pragma once
// Test fake for AudioStreamBackend: a "device" that can be unplugged and replugged, and whose
// audio thread is the test itself (Pump runs the callback core like a device callback would).
// Lets the supervisor's lost-device / back-off / reopen logic be tested deterministically.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>
#include <vector>

#include "platform/audio/audio_output.h"

namespace sas::platform {

class FakeAudioStreamBackend final : public AudioStreamBackend {
 public:
  struct Shared {  // kept by the test after the backend moved into the supervisor
    bool present = true;
    bool healthy = true;
    int opens = 0;
    int open_attempts = 0;
    int aborts = 0;
    AudioCallbackCore* core = nullptr;
    AudioOutputConfig config;
    std::vector<float> played;  // everything the "device" received
  };

  explicit FakeAudioStreamBackend(Shared& shared) : shared_(&shared) {}
  const char* Name() const override { return "fake"; }
  bool Open(const AudioOutputConfig& config, AudioCallbackCore& core, std::string* error) override {
    ++shared_->open_attempts;
    if (!shared_->present) {
      if (error) *error = "output device '" + config.device + "' not found; available: none";
      return false;
    }
    ++shared_->opens;
    shared_->healthy = true;
    shared_->core = &core;
    shared_->config = config;
    return true;
  }
  void Close() override { shared_->core = nullptr; }
  void Abort() override {
    ++shared_->aborts;
    Close();
  }
  bool Healthy() override { return shared_->healthy && shared_->present; }

  // The device's audio thread: `blocks` callbacks if a stream is open, nothing otherwise.
  static void Pump(Shared& shared, int blocks, bool xrun = false) {
    if (shared.core == nullptr || !shared.present) return;
    std::vector<float> block(
        static_cast<std::size_t>(shared.config.frames_per_buffer * shared.config.channels));
    for (int b = 0; b < blocks; ++b) {
      shared.core->Run(block.data(), shared.config.frames_per_buffer, shared.config.channels, xrun);
      shared.played.insert(shared.played.end(), block.begin(), block.end());
    }
  }
  static void Unplug(Shared& shared) {
    shared.present = false;
    shared.healthy = false;
  }
  static void Replug(Shared& shared) { shared.present = true; }

 private:
  Shared* shared_;
};

// A device with an audio thread of its own (one callback per block period while a stream is
// open), removed and returned from any thread, whose every open attempt can take as long as
// PortAudio's open sat in ALSA after a card vanished (> 3 s). For the background supervision
// (BackgroundAudioOutput) in tests and in the UI latency measurement, where the supervisor runs
// on another thread than the one that unplugs.
class ThreadedFakeAudioStreamBackend final : public AudioStreamBackend {
 public:
  struct Shared {  // kept by the test after the backend moved into the supervisor
    std::atomic<bool> present{true};
    std::atomic<int> open_delay_ms{0};  // each open attempt takes this long
    std::atomic<int> open_attempts{0};
    std::atomic<std::uint64_t> blocks{0};  // callbacks run
  };

  explicit ThreadedFakeAudioStreamBackend(Shared& shared) : shared_(&shared) {}
  ~ThreadedFakeAudioStreamBackend() override { Close(); }
  const char* Name() const override { return "threaded fake"; }
  bool Open(const AudioOutputConfig& config, AudioCallbackCore& core, std::string* error) override {
    Close();
    shared_->open_attempts.fetch_add(1);
    std::this_thread::sleep_for(std::chrono::milliseconds(shared_->open_delay_ms.load()));
    if (!shared_->present.load()) {
      if (error) *error = "output device '" + config.device + "' not found; available: none";
      return false;
    }
    running_.store(true);
    thread_ = std::thread([this, config, &core] { Run(config, core); });
    return true;
  }
  void Close() override {
    running_.store(false);
    if (thread_.joinable()) thread_.join();
  }
  bool Healthy() override { return shared_->present.load(); }

 private:
  // The device's thread: real-time paced blocks until closed or removed.
  void Run(const AudioOutputConfig& config, AudioCallbackCore& core) {
    std::vector<float> block(static_cast<std::size_t>(config.frames_per_buffer * config.channels));
    const auto period = std::chrono::nanoseconds(1'000'000'000LL * config.frames_per_buffer /
                                                 config.sample_rate_hz);
    auto next = std::chrono::steady_clock::now();
    while (running_.load() && shared_->present.load()) {
      core.Run(block.data(), config.frames_per_buffer, config.channels, false);
      shared_->blocks.fetch_add(1);
      next += period;
      std::this_thread::sleep_until(next);
    }
  }

  Shared* shared_;
  std::atomic<bool> running_{false};
  std::thread thread_;
};

}  // namespace sas::platform
