#pragma once
// The microphone behind one interface: PortAudio capture (the product) and a fake that feeds
// given samples through the same VoiceRecorder (tests). The input stream runs whenever the kiosk
// runs (so the level meter is live); VoiceRecorder::Arm/Stop decide what is kept.

#include <memory>
#include <string>

#include "platform/audio/voice_recorder.h"
#include "platform/device_status.h"

namespace sas::platform {

struct AudioInputConfig {
  std::string device = "default";
  int sample_rate_hz = 48000;
  int channels = 1;  // channel 0 is recorded
  int frames_per_buffer = 256;
};

class AudioInput {
 public:
  virtual ~AudioInput() = default;
  // False (status "missing", one log line listing the devices) when the microphone is absent:
  // the record button is then disabled by the kiosk.
  virtual bool Start() = 0;
  virtual void Stop() = 0;
  virtual VoiceRecorder& recorder() = 0;
};

// Status key "audio_in".
std::unique_ptr<AudioInput> MakePortAudioInput(const AudioInputConfig& config,
                                               const VoiceRecorderConfig& recorder_config,
                                               DeviceStatusBoard& board);

// Test fake: Feed() pushes samples in blocks exactly as a device callback would.
class FakeAudioInput final : public AudioInput {
 public:
  explicit FakeAudioInput(VoiceRecorderConfig config = {}, int frames_per_buffer = 256)
      : recorder_(config), frames_per_buffer_(frames_per_buffer) {}
  bool Start() override { return started_ = true; }
  void Stop() override { started_ = false; }
  VoiceRecorder& recorder() override { return recorder_; }
  void Feed(const float* mono, std::size_t count);

 private:
  VoiceRecorder recorder_;
  int frames_per_buffer_;
  bool started_ = false;
};

}  // namespace sas::platform
