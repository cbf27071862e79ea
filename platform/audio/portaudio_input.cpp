// PortAudio capture into the VoiceRecorder (see audio_input.h). The input callback only copies
// channel 0 into the recorder's preallocated buffer and updates the meter.
#include <portaudio.h>

#include <optional>

#include "platform/audio/audio_input.h"
#include "platform/audio/portaudio_callbacks.h"
#include "platform/audio/portaudio_session.h"
#include "platform/audio/portaudio_stream.h"

namespace sas::platform {

namespace detail {

int PortAudioInputCallback(const void* input, void* /*output*/, unsigned long frames,
                           const PaStreamCallbackTimeInfo* /*time*/,
                           PaStreamCallbackFlags /*flags*/, void* user) {
  auto* context = static_cast<InputCallbackContext*>(user);
  context->callbacks.fetch_add(1, std::memory_order_relaxed);
  if (input != nullptr) {
    context->recorder->PushInterleaved(static_cast<const float*>(input), static_cast<int>(frames),
                                       context->channels);
  }
  return paContinue;
}

}  // namespace detail

namespace {

class PortAudioInput final : public AudioInput {
 public:
  PortAudioInput(const AudioInputConfig& config, const VoiceRecorderConfig& recorder_config,
                 DeviceStatusBoard& board)
      : config_(config), recorder_(recorder_config), board_(&board) {}
  ~PortAudioInput() override { Stop(); }

  bool Start() override {
    Stop();
    std::string error;
    if (!Open(&error)) {
      Stop();
      board_->AddFailure("audio_in");
      board_->Set("audio_in", DeviceState::kMissing, error + "; recording disabled", "portaudio");
      return false;
    }
    board_->Set(
        "audio_in", DeviceState::kOk,
        "listening on '" + config_.device + "' " + std::to_string(config_.sample_rate_hz) + " Hz",
        "portaudio");
    return true;
  }

  void Stop() override {
    stream_.Reset();
    session_.reset();
    watch_.Reset();
  }

  VoiceRecorder& recorder() override { return recorder_; }

  bool Delivering(std::int64_t now_ns) override {
    if (!stream_) return false;
    const bool live = watch_.Update(context_.callbacks.load(std::memory_order_relaxed), now_ns);
    if (live != live_) {
      live_ = live;
      if (live) {
        board_->AddReconnect("audio_in");
        board_->Set("audio_in", DeviceState::kOk,
                    "sound from '" + config_.device + "' again; recording possible", "portaudio");
      } else {
        board_->AddFailure("audio_in");
        board_->Set("audio_in", DeviceState::kLost,
                    "no sound from '" + config_.device +
                        "' for 1 s (unplugged?); recording is off until it comes back",
                    "portaudio");
      }
    }
    return live;
  }

 private:
  bool Open(std::string* error) {
    session_.emplace();
    if (!session_->ok()) {
      *error = "PortAudio: " + session_->error();
      return false;
    }
    const PaDeviceIndex device = FindPortAudioDevice(config_.device, false, error);
    if (device == paNoDevice) return false;
    PaStreamParameters params{};
    params.device = device;
    params.channelCount = config_.channels;
    params.sampleFormat = paFloat32;
    params.suggestedLatency = Pa_GetDeviceInfo(device)->defaultLowInputLatency;
    context_.recorder = &recorder_;
    context_.channels = config_.channels;
    PaStream* raw = nullptr;
    PaError result =
        Pa_OpenStream(&raw, &params, nullptr, config_.sample_rate_hz,
                      static_cast<unsigned long>(config_.frames_per_buffer),
                      paClipOff | paDitherOff, &detail::PortAudioInputCallback, &context_);
    if (result == paNoError) {
      stream_ = PortAudioStream(raw);
      result = Pa_StartStream(stream_.get());
    }
    if (result != paNoError) {
      *error = "cannot open input '" + config_.device + "': " + Pa_GetErrorText(result);
      return false;
    }
    return true;
  }

  AudioInputConfig config_;
  VoiceRecorder recorder_;
  DeviceStatusBoard* board_;
  std::optional<PortAudioSession> session_;
  PortAudioStream stream_;
  detail::InputCallbackContext context_;
  InputWatch watch_;
  bool live_ = true;
};

}  // namespace

std::unique_ptr<AudioInput> MakePortAudioInput(const AudioInputConfig& config,
                                               const VoiceRecorderConfig& recorder_config,
                                               DeviceStatusBoard& board) {
  return std::make_unique<PortAudioInput>(config, recorder_config, board);
}

void FakeAudioInput::Feed(const float* mono, std::size_t count) {
  for (std::size_t i = 0; i < count; i += static_cast<std::size_t>(frames_per_buffer_)) {
    const std::size_t n = std::min(count - i, static_cast<std::size_t>(frames_per_buffer_));
    recorder_.Push(mono + i, static_cast<int>(n));
    ++blocks_;
  }
}

bool InputWatch::Update(std::uint64_t callbacks, std::int64_t now_ns) {
  const bool loop_stood_still = started_ && now_ns - called_ns_ > kLoopGapNs;
  called_ns_ = now_ns;
  if (!started_ || callbacks != callbacks_) {
    started_ = true;
    live_ = true;
    callbacks_ = callbacks;
    changed_ns_ = now_ns;
  } else if (loop_stood_still) {
    changed_ns_ = now_ns;  // judged from now on; a lost input stays lost
  } else if (now_ns - changed_ns_ >= kStallNs) {
    live_ = false;
  }
  return live_;
}

}  // namespace sas::platform
