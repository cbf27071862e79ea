// PortAudio discovery through a private ALSA configuration (no sound card needed): ALSA's `file`
// plugin stands in for the speaker (see alsa_file_config.h).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>

#include "platform/audio/audio_devices.h"
#include "support/temp_dir.h"

TEST_CASE("PortAudio lists the PCMs a private ALSA configuration defines", "[platform]") {
  sas::test::TempDir dir;
  const std::string out = dir.file("out.raw");
  const auto conf = dir.Write("asound.conf",
                              "pcm.null { type null }\n"
                              "pcm.kiosk_out { type file slave.pcm \"null\" file \"" +
                                  out +
                                  "\" format \"raw\" }\n"
                                  "pcm.!default { type plug slave.pcm \"kiosk_out\" }\n");
  setenv("ALSA_CONFIG_PATH", conf.c_str(), 1);
  std::string error;
  const auto devices = sas::platform::ListAudioDevices(&error);
  unsetenv("ALSA_CONFIG_PATH");
  INFO(error);
  const auto named = std::find_if(devices.begin(), devices.end(),
                                  [](const auto& d) { return d.name == "kiosk_out"; });
  REQUIRE(named != devices.end());
  CHECK(named->max_output_channels >= 2);
  CHECK(named->host_api == "ALSA");
}
