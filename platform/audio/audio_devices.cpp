// PortAudio device discovery (see audio_devices.h).
#include "platform/audio/audio_devices.h"

#include <portaudio.h>

#include "platform/audio/portaudio_session.h"

namespace sas::platform {

std::vector<AudioDeviceInfo> ListAudioDevices(std::string* error) {
  std::vector<AudioDeviceInfo> devices;
  PortAudioSession session;
  if (!session.ok()) {
    if (error) *error = session.error();
    return devices;
  }
  const PaDeviceIndex count = Pa_GetDeviceCount();
  for (PaDeviceIndex i = 0; i < count; ++i) {
    const PaDeviceInfo* info = Pa_GetDeviceInfo(i);
    if (info == nullptr) continue;
    AudioDeviceInfo device;
    device.index = i;
    device.name = info->name ? info->name : "";
    if (const PaHostApiInfo* api = Pa_GetHostApiInfo(info->hostApi)) device.host_api = api->name;
    device.max_output_channels = info->maxOutputChannels;
    device.max_input_channels = info->maxInputChannels;
    device.default_sample_rate_hz = info->defaultSampleRate;
    devices.push_back(std::move(device));
  }
  if (count < 0 && error) *error = Pa_GetErrorText(count);
  return devices;
}

void ReportAudioDevices(DeviceReport& report) {
  std::string error;
  const auto devices = ListAudioDevices(&error);
  if (devices.empty()) {
    report.push_back({"audio", false,
                      "no audio device" + (error.empty() ? std::string() : " (" + error + ")") +
                          ": the kiosk runs silent until one appears"});
    return;
  }
  for (const auto& device : devices) {
    report.push_back({"audio", true,
                      device.name + " [" + device.host_api + "] out " +
                          std::to_string(device.max_output_channels) + " ch, in " +
                          std::to_string(device.max_input_channels) + " ch"});
  }
}

}  // namespace sas::platform
