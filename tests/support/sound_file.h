#pragma once
// Writes test sounds in any format libsndfile writes (WAV, FLAC, Ogg ...), so that the readers
// under test meet real files.

#include <sndfile.h>

#include <catch2/catch.hpp>
#include <string>
#include <vector>

namespace sas::test {

// Writes interleaved float frames with the given format (SF_FORMAT_*; values beyond full scale
// are clipped for integer formats); returns the path.
inline std::string WriteSound(const std::string& path, int format, int rate, int channels,
                              const std::vector<float>& interleaved) {
  SF_INFO info{};
  info.samplerate = rate;
  info.channels = channels;
  info.format = format;
  SNDFILE* file = sf_open(path.c_str(), SFM_WRITE, &info);
  REQUIRE(file != nullptr);
  sf_command(file, SFC_SET_CLIPPING, nullptr, SF_TRUE);
  const auto frames =
      static_cast<sf_count_t>(interleaved.size() / static_cast<std::size_t>(channels));
  REQUIRE(sf_writef_float(file, interleaved.data(), frames) == frames);
  sf_close(file);
  return path;
}

}  // namespace sas::test
