#pragma once
// Move-only RAII over a PortAudio stream (Pa_OpenStream ... Pa_CloseStream) and device lookup by
// name. Names are ALSA PCM names as PortAudio lists them ("default", "kiosk_out", or
// "USB Audio: - (hw:1,0)"); an exact match wins, otherwise a unique substring match, so a
// configuration can say "hw:CARD=Device" or "USB Audio". A miss lists every candidate.

#include <portaudio.h>

#include <string>
#include <utility>

namespace sas::platform {

// PortAudio must be initialised. Returns the device index or paNoDevice with `error` naming the
// device asked for and listing the devices that have the wanted direction.
PaDeviceIndex FindPortAudioDevice(const std::string& name, bool output, std::string* error);

class PortAudioStream {
 public:
  PortAudioStream() = default;
  explicit PortAudioStream(PaStream* stream) : stream_(stream) {}
  ~PortAudioStream() { Reset(); }
  PortAudioStream(PortAudioStream&& other) noexcept
      : stream_(std::exchange(other.stream_, nullptr)) {}
  PortAudioStream& operator=(PortAudioStream&& other) noexcept {
    if (this != &other) {
      Reset();
      stream_ = std::exchange(other.stream_, nullptr);
    }
    return *this;
  }
  PortAudioStream(const PortAudioStream&) = delete;
  PortAudioStream& operator=(const PortAudioStream&) = delete;

  PaStream* get() const { return stream_; }
  explicit operator bool() const { return stream_ != nullptr; }
  // Stops (waiting for pending buffers) and closes.
  void Reset();
  // Aborts (dropping pending buffers: the device may be gone) and closes.
  void Abort();

 private:
  PaStream* stream_ = nullptr;
};

}  // namespace sas::platform
