#pragma once
// The microphone behind one interface: PortAudio capture (the product) and a fake that feeds
// given samples through the same VoiceRecorder (tests). The input stream runs whenever the kiosk
// runs (so the level meter is live); VoiceRecorder::Arm/Stop decide what is kept.

#include <cstdint>
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

// Whether a started input still delivers: a USB microphone pulled out mid-run leaves its stream
// open, and ALSA simply stops calling back. Fed the callback count on the control thread; no
// new callback for kStallNs makes it lost, the next one brings it back. A gap of kLoopGapNs
// between two calls means the whole process stood still (SIGSTOP, a suspended machine), the
// device's thread with it: the watch then starts afresh instead of calling the microphone lost.
class InputWatch {
 public:
  static constexpr std::int64_t kStallNs = 1'000'000'000;
  static constexpr std::int64_t kLoopGapNs = 500'000'000;
  // True while delivering. The first call only takes the count and the time as its start.
  bool Update(std::uint64_t callbacks, std::int64_t now_ns);
  void Reset() { started_ = false; }

 private:
  bool started_ = false;
  bool live_ = true;
  std::uint64_t callbacks_ = 0;
  std::int64_t changed_ns_ = 0;
  std::int64_t called_ns_ = 0;
};

class AudioInput {
 public:
  virtual ~AudioInput() = default;
  // False (status "missing", one log line listing the devices) when the microphone is absent:
  // the record button is then disabled by the kiosk.
  virtual bool Start() = 0;
  virtual void Stop() = 0;
  virtual VoiceRecorder& recorder() = 0;
  // Control thread, once per loop pass: whether sound is coming in (InputWatch); false when the
  // input never started. Reads an atomic, never waits on the device. The PortAudio input also
  // puts a loss and a return on the status board ("audio_in": lost, then ok), so the journal and
  // the staff panel say it.
  virtual bool Delivering(std::int64_t now_ns) = 0;
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
  void Stop() override {
    started_ = false;
    watch_.Reset();
  }
  VoiceRecorder& recorder() override { return recorder_; }
  bool Delivering(std::int64_t now_ns) override {
    return started_ && watch_.Update(blocks_, now_ns);
  }
  // One call per block, as the device's callback would; a test that stops feeding is a microphone
  // pulled out.
  void Feed(const float* mono, std::size_t count);

 private:
  VoiceRecorder recorder_;
  int frames_per_buffer_;
  bool started_ = false;
  std::uint64_t blocks_ = 0;
  InputWatch watch_;
};

}  // namespace sas::platform
