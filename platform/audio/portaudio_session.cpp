// PortAudio session with quiet start-up (see portaudio_session.h).
#include "platform/audio/portaudio_session.h"

#include <alsa/asoundlib.h>
#include <fcntl.h>
#include <portaudio.h>
#include <unistd.h>

#include <cstdarg>
#include <cstdio>

namespace sas::platform {
namespace {

void QuietAlsaErrorHandler(const char* /*file*/, int /*line*/, const char* /*function*/,
                           int /*err*/, const char* /*fmt*/, ...) {}

// Points fd 2 at /dev/null for its lifetime, restoring it afterwards.
class StderrMute {
 public:
  StderrMute() {
    std::fflush(stderr);
    saved_ = dup(STDERR_FILENO);
    const int null_fd = open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (saved_ >= 0 && null_fd >= 0) dup2(null_fd, STDERR_FILENO);
    if (null_fd >= 0) close(null_fd);
  }
  ~StderrMute() {
    std::fflush(stderr);
    if (saved_ >= 0) {
      dup2(saved_, STDERR_FILENO);
      close(saved_);
    }
  }
  StderrMute(const StderrMute&) = delete;
  StderrMute& operator=(const StderrMute&) = delete;

 private:
  int saved_ = -1;
};

}  // namespace

PortAudioSession::PortAudioSession() {
  snd_lib_error_set_handler(&QuietAlsaErrorHandler);
  PaError result;
  {
    StderrMute mute;
    result = Pa_Initialize();
  }
  if (result != paNoError) error_ = Pa_GetErrorText(result);
}

PortAudioSession::~PortAudioSession() {
  if (ok()) Pa_Terminate();
}

}  // namespace sas::platform
