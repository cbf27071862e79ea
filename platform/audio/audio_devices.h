#pragma once
// Audio device discovery through PortAudio (ALSA host API on Debian 12).

#include <string>
#include <vector>

#include "platform/device_finding.h"

namespace sas::platform {

struct AudioDeviceInfo {
  int index = -1;
  std::string name;
  std::string host_api;
  int max_output_channels = 0;
  int max_input_channels = 0;
  double default_sample_rate_hz = 0.0;
};

// Lists every device PortAudio sees. Empty (with `error` set) when PortAudio cannot initialise.
std::vector<AudioDeviceInfo> ListAudioDevices(std::string* error = nullptr);

// Appends audio findings: one per device, or one "not found" line saying why.
void ReportAudioDevices(DeviceReport& report);

}  // namespace sas::platform
