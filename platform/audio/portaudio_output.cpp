// PortAudio output backend for SupervisedAudioOutput (see audio_output.h). The callback below is
// the whole audio-thread path: hand PortAudio's buffer to the callback core and return.
#include <portaudio.h>

#include <atomic>
#include <optional>

#include "platform/audio/audio_output.h"
#include "platform/audio/portaudio_callbacks.h"
#include "platform/audio/portaudio_session.h"
#include "platform/audio/portaudio_stream.h"

namespace sas::platform {

namespace detail {

int PortAudioOutputCallback(const void* /*input*/, void* output, unsigned long frames,
                            const PaStreamCallbackTimeInfo* /*time*/, PaStreamCallbackFlags flags,
                            void* user) {
  auto* context = static_cast<OutputCallbackContext*>(user);
  context->core->Run(static_cast<float*>(output), static_cast<int>(frames), context->channels,
                     (flags & (paOutputUnderflow | paOutputOverflow)) != 0);
  return paContinue;
}

}  // namespace detail

namespace {

class PortAudioOutputBackend final : public AudioStreamBackend {
 public:
  ~PortAudioOutputBackend() override { Close(); }
  const char* Name() const override { return "portaudio"; }

  bool Open(const AudioOutputConfig& config, AudioCallbackCore& core, std::string* error) override {
    Close();
    // Fresh PortAudio session per attempt: a replugged device only shows up after re-init.
    session_.emplace();
    if (!session_->ok()) {
      if (error) *error = "PortAudio: " + session_->error();
      session_.reset();
      return false;
    }
    const PaDeviceIndex device = FindPortAudioDevice(config.device, true, error);
    if (device == paNoDevice) {
      session_.reset();
      return false;
    }
    const PaDeviceInfo* info = Pa_GetDeviceInfo(device);
    PaStreamParameters params{};
    params.device = device;
    params.channelCount = config.channels;
    params.sampleFormat = paFloat32;
    params.suggestedLatency =
        config.suggested_latency_s > 0 ? config.suggested_latency_s : info->defaultLowOutputLatency;
    context_.core = &core;
    context_.channels = config.channels;
    PaStream* raw = nullptr;
    PaError result =
        Pa_OpenStream(&raw, nullptr, &params, config.sample_rate_hz,
                      static_cast<unsigned long>(config.frames_per_buffer), paClipOff | paDitherOff,
                      &detail::PortAudioOutputCallback, &context_);
    if (result == paNoError) {
      stream_ = PortAudioStream(raw);
      result = Pa_StartStream(stream_.get());
    }
    if (result != paNoError) {
      if (error) {
        *error = "cannot open '" + config.device + "' (" + std::to_string(config.channels) +
                 " ch, " + std::to_string(config.sample_rate_hz) +
                 " Hz): " + Pa_GetErrorText(result);
      }
      Close();
      return false;
    }
    return true;
  }

  void Close() override {
    stream_.Reset();
    session_.reset();
  }

  void Abort() override {
    stream_.Abort();
    session_.reset();
  }

  bool Healthy() override { return stream_ && Pa_IsStreamActive(stream_.get()) == 1; }

 private:
  std::optional<PortAudioSession> session_;
  PortAudioStream stream_;
  detail::OutputCallbackContext context_;
};

}  // namespace

std::unique_ptr<AudioStreamBackend> MakePortAudioOutputBackend() {
  return std::make_unique<PortAudioOutputBackend>();
}

std::unique_ptr<AudioOutput> MakePortAudioOutput(AudioRenderer& renderer,
                                                 const AudioOutputConfig& config,
                                                 DeviceStatusBoard& board) {
  return std::make_unique<SupervisedAudioOutput>(MakePortAudioOutputBackend(), renderer, config,
                                                 board);
}

}  // namespace sas::platform
