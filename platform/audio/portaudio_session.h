#pragma once
// RAII over Pa_Initialize / Pa_Terminate. Debian's PortAudio probes every ALSA PCM and the JACK
// server on start-up and both libraries print pages of harmless noise to stderr ("cannot find
// card '0'", "jack server is not running"); the session routes ALSA's messages to a quiet handler
// and mutes stderr only while Pa_Initialize runs, so the journal shows our own clear lines.

#include <string>

namespace sas::platform {

class PortAudioSession {
 public:
  PortAudioSession();
  ~PortAudioSession();
  PortAudioSession(const PortAudioSession&) = delete;
  PortAudioSession& operator=(const PortAudioSession&) = delete;

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }

 private:
  std::string error_;
};

}  // namespace sas::platform
