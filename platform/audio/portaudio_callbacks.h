#pragma once
// The exact functions PortAudio calls on its audio thread, exposed so that the real-time test can
// call them with allocation and lock counting switched on. Internal to platform/audio.

#include <portaudio.h>

#include <atomic>
#include <cstdint>

#include "platform/audio/audio_output.h"
#include "platform/audio/voice_recorder.h"

namespace sas::platform::detail {

struct OutputCallbackContext {
  AudioCallbackCore* core = nullptr;
  int channels = 2;
};

int PortAudioOutputCallback(const void* input, void* output, unsigned long frames,
                            const PaStreamCallbackTimeInfo* time, PaStreamCallbackFlags flags,
                            void* user);

struct InputCallbackContext {
  VoiceRecorder* recorder = nullptr;
  int channels = 1;
  std::atomic<std::uint64_t> callbacks{0};  // the control thread's sign that sound still comes
};

int PortAudioInputCallback(const void* input, void* output, unsigned long frames,
                           const PaStreamCallbackTimeInfo* time, PaStreamCallbackFlags flags,
                           void* user);

}  // namespace sas::platform::detail
