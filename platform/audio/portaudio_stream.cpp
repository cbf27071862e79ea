// PortAudio stream RAII and device lookup (see portaudio_stream.h).
#include "platform/audio/portaudio_stream.h"

#include <vector>

namespace sas::platform {

PaDeviceIndex FindPortAudioDevice(const std::string& name, bool output, std::string* error) {
  const PaDeviceIndex count = Pa_GetDeviceCount();
  std::vector<PaDeviceIndex> partial;
  std::string available;
  for (PaDeviceIndex i = 0; i < count; ++i) {
    const PaDeviceInfo* info = Pa_GetDeviceInfo(i);
    if (info == nullptr) continue;
    if ((output ? info->maxOutputChannels : info->maxInputChannels) <= 0) continue;
    const std::string device_name = info->name ? info->name : "";
    if (device_name == name) return i;
    if (!name.empty() && device_name.find(name) != std::string::npos) partial.push_back(i);
    available += (available.empty() ? "" : ", ") + ("'" + device_name + "'");
  }
  if (partial.size() == 1) return partial.front();
  if (error) {
    *error = std::string(output ? "output" : "input") + " device '" + name + "' " +
             (partial.size() > 1 ? "is ambiguous" : "not found") +
             "; available: " + (available.empty() ? std::string("none") : available);
  }
  return paNoDevice;
}

void PortAudioStream::Reset() {
  if (stream_ == nullptr) return;
  Pa_StopStream(stream_);
  Pa_CloseStream(stream_);
  stream_ = nullptr;
}

void PortAudioStream::Abort() {
  if (stream_ == nullptr) return;
  Pa_AbortStream(stream_);
  Pa_CloseStream(stream_);
  stream_ = nullptr;
}

}  // namespace sas::platform
