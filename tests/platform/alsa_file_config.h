#pragma once
// A private ALSA configuration for running the real PortAudio path with no sound card
// (so CI needs none): ALSA's `file` plugin writes what is played to out.raw and
// reads capture from in.raw, both float32 LE interleaved in the stream's own format. Setting
// ALSA_CONFIG_PATH replaces the system's alsa.conf, so pcm.null is defined here too.

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "support/temp_dir.h"

namespace sas::test {

class AlsaFileConfig {
 public:
  AlsaFileConfig() {
    out_ = dir_.file("out.raw");
    in_ = dir_.file("in.raw");
    dir_.Write("in.raw", "");
    const auto conf =
        dir_.Write("asound.conf",
                   "pcm.null { type null }\n"
                   "pcm.kiosk_out { type file slave.pcm \"null\" file \"" +
                       out_ +
                       "\" format \"raw\" }\n"
                       "pcm.kiosk_in { type file slave.pcm \"null\" file \"/dev/null\" "
                       "infile \"" +
                       in_ +
                       "\" format \"raw\" }\n"
                       "pcm.!default { type asym playback.pcm \"kiosk_out\" capture.pcm "
                       "\"kiosk_in\" }\n");
    setenv("ALSA_CONFIG_PATH", conf.c_str(), 1);
  }
  ~AlsaFileConfig() { unsetenv("ALSA_CONFIG_PATH"); }
  AlsaFileConfig(const AlsaFileConfig&) = delete;
  AlsaFileConfig& operator=(const AlsaFileConfig&) = delete;

  const std::string& out_path() const { return out_; }
  void WriteCaptureInput(const std::vector<float>& samples) const {
    std::ofstream f(in_, std::ios::binary);
    f.write(reinterpret_cast<const char*>(samples.data()),
            static_cast<std::streamsize>(samples.size() * sizeof(float)));
  }
  std::vector<float> ReadPlayed() const {
    std::ifstream f(out_, std::ios::binary | std::ios::ate);
    if (!f) return {};
    const auto bytes = static_cast<std::size_t>(f.tellg());
    std::vector<float> samples(bytes / sizeof(float));
    f.seekg(0);
    f.read(reinterpret_cast<char*>(samples.data()),
           static_cast<std::streamsize>(samples.size() * sizeof(float)));
    return samples;
  }

 private:
  TempDir dir_;
  std::string out_;
  std::string in_;
};

}  // namespace sas::test
