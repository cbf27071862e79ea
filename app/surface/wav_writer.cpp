// WAV writing through libsndfile (see wav_writer.h).
#include "surface/wav_writer.h"

#include <sndfile.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace sas::surface {
namespace {

struct SndfileCloser {
  void operator()(SNDFILE* file) const { sf_close(file); }
};
using SndfileHandle = std::unique_ptr<SNDFILE, SndfileCloser>;

}  // namespace

void WriteWav(const std::string& path, const float* interleaved, std::size_t frames, int channels,
              int sample_rate_hz, WavFormat format) {
  if (channels < 1 || channels > 64) {
    throw WavError(path + ": cannot write " + std::to_string(channels) + " channels");
  }
  if (sample_rate_hz < 1000 || sample_rate_hz > 768000) {
    throw WavError(path + ": unsupported sample rate " + std::to_string(sample_rate_hz) + " Hz");
  }
  if (interleaved == nullptr && frames > 0) throw WavError(path + ": no samples to write");
  const std::size_t count = frames * static_cast<std::size_t>(channels);
  // Checked before the file is created, so a bad render leaves no half-written file behind.
  for (std::size_t i = 0; i < count; ++i) {
    if (!std::isfinite(interleaved[i])) {
      throw WavError(path + ": sample " + std::to_string(i / static_cast<std::size_t>(channels)) +
                     " of channel " + std::to_string(i % static_cast<std::size_t>(channels) + 1) +
                     " is not finite");
    }
  }

  SF_INFO info{};
  info.samplerate = sample_rate_hz;
  info.channels = channels;
  info.format =
      SF_FORMAT_WAV | (format == WavFormat::kFloat32 ? SF_FORMAT_FLOAT : SF_FORMAT_PCM_24);
  if (sf_format_check(&info) == 0) throw WavError(path + ": libsndfile rejects this WAV format");
  SndfileHandle file(sf_open(path.c_str(), SFM_WRITE, &info));
  if (!file) throw WavError(path + ": cannot create: " + sf_strerror(nullptr));

  std::vector<float> clipped;
  const float* data = interleaved;
  if (format == WavFormat::kPcm24) {
    // libsndfile would wrap out-of-range floats in integer formats unless told to clip; clipping
    // here makes the behaviour explicit and independent of that setting.
    clipped.assign(interleaved, interleaved + count);
    for (float& sample : clipped) sample = std::clamp(sample, -1.0f, 1.0f);
    data = clipped.data();
  }
  const auto written = sf_writef_float(file.get(), data, static_cast<sf_count_t>(frames));
  if (written != static_cast<sf_count_t>(frames)) {
    const std::string reason = sf_strerror(file.get());
    file.reset();
    throw WavError(path + ": write failed after " + std::to_string(written) + " of " +
                   std::to_string(frames) + " frames: " + reason);
  }
  sf_write_sync(file.get());
  SNDFILE* raw = file.release();
  if (sf_close(raw) != 0) throw WavError(path + ": closing failed (disk full?)");
}

}  // namespace sas::surface
