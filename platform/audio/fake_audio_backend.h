#pragma once
// Test fake for AudioStreamBackend: a "device" that can be unplugged and replugged, and whose
// audio thread is the test itself (Pump runs the callback core like a device callback would).
// Lets the supervisor's lost-device / back-off / reopen logic be tested deterministically.

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

}  // namespace sas::platform
