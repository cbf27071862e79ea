#pragma once
// Writing rendered audio to WAV files with libsndfile: interleaved float samples in, 32-bit float
// or 24-bit PCM WAV out (the offline renderer's two channels: sound and haptic). Set-up/offline
// only: errors are exceptions naming the file and libsndfile's reason. libsndfile stays inside the
// .cpp (no header bloat).

#include <cstddef>
#include <stdexcept>
#include <string>

namespace sas::surface {

class WavError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class WavFormat {
  kFloat32,  // exact: what the synth computed
  kPcm24,    // for tools that do not read float WAV; samples are clipped to [-1, 1]
};

// Writes `frames` frames of `channels` interleaved samples to `path` (replacing it). Throws
// WavError on a bad argument (rate, channels, null data), when the file cannot be created or
// written, or on a sample that is NaN or infinite (a finite file is part of the contract).
void WriteWav(const std::string& path, const float* interleaved, std::size_t frames, int channels,
              int sample_rate_hz, WavFormat format = WavFormat::kFloat32);

}  // namespace sas::surface
