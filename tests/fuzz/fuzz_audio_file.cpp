// libFuzzer target : arbitrary bytes as a sound file (WAV, FLAC, OGG, or
// anything libsndfile recognises) through ReadAudioFile, which documents LoadError for every bad
// file. ReadAudioFile takes a path, so the bytes go into an anonymous memory file (memfd) opened
// through /proc/self/fd: no disk writes per input. The kiosk's own limits are used unchanged.
#include <sys/mman.h>
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "surface/audio_file.h"
#include "surface/image_loader.h"  // LoadError

// libsndfile 1.2.0 leaks libvorbis's header state when sf_open fails on a corrupt Ogg file
// (reported upstream as libsndfile #922; see tests/surface/test_loader_fuzz.cpp): suppressed
// inside libvorbis only, so a leak of ours is still reported.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libvorbis.so\n";
}

namespace {

// One memfd for the whole run, rewritten for each input.
int MemoryFile() {
  static const int fd = memfd_create("sas-fuzz-audio", 0);
  if (fd < 0) __builtin_trap();
  return fd;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const int fd = MemoryFile();
  if (ftruncate(fd, 0) != 0 || lseek(fd, 0, SEEK_SET) != 0) __builtin_trap();
  std::size_t written = 0;
  while (written < size) {
    const ssize_t n = write(fd, data + written, size - written);
    if (n <= 0) __builtin_trap();
    written += static_cast<std::size_t>(n);
  }
  const std::string path = "/proc/self/fd/" + std::to_string(fd);
  try {
    const sas::surface::AudioClip clip = sas::surface::ReadAudioFile(path);
    if (clip.samples.empty() || clip.sample_rate_hz != 48000.0) __builtin_trap();
    for (const float s : clip.samples) {
      if (!std::isfinite(s)) __builtin_trap();
    }
  } catch (const sas::surface::LoadError&) {
    // documented rejection of a bad file
  }
  return 0;
}
