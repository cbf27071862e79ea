#pragma once
// Reading recorded sound and vibration scans (WAV, FLAC, OGG/Vorbis through libsndfile) for the
// surface pipeline: a voice recording becomes an image (paper §4, figure 3) and a scan becomes a
// profile. Everything is brought to one shape before anyone looks at it: mono (mean of the
// channels), float in [-1, 1], at `target_rate_hz` (band-limited resampling, below).
//
// Limits are checked from the file's header before any sample is read, so a 2-hour file or a
// 64-channel file is refused without reading it. Handling of the awkward cases:
//   empty (0 frames), or too short to give one sample at target_rate_hz -> LoadError
//   more than max_channels  -> LoadError; up to max_channels (default 8) are mixed down
//   longer than max_duration_s -> LoadError (from the header, nothing decoded)
//   sample rate below min_rate_hz or above max_rate_hz -> LoadError; otherwise resampled
//   non-finite samples (float files) -> LoadError
//   silent (peak below silence_peak)  -> loads; AudioClip::silent is set, so the caller can tell
//                                        the visitor instead of storing a flat surface
//   clipped                         -> loads unchanged; AudioClip::clipped_fraction says how much
//   float samples beyond full scale -> clipped to [-1, 1] (and counted in clipped_fraction)
// Set-up time only (exceptions), never on the audio thread.

#include <cstdint>
#include <string>
#include <vector>

namespace sas::surface {

struct AudioReadLimits {
  double target_rate_hz = 48000.0;
  double min_rate_hz = 4000.0;
  double max_rate_hz = 384000.0;
  int max_channels = 8;
  double max_duration_s = 600.0;
  float silence_peak = 1e-4f;  // ≈ -80 dBFS
  float clip_level = 0.999f;   // |x| at or above this counts as clipped
};

struct AudioClip {
  double sample_rate_hz = 0.0;
  std::vector<float> samples;  // mono, at sample_rate_hz
  int source_channels = 0;
  double source_rate_hz = 0.0;
  float peak = 0.0f;
  bool silent = false;
  double clipped_fraction = 0.0;  // share of source samples at or above clip_level

  double duration_s() const {
    return sample_rate_hz > 0.0 ? static_cast<double>(samples.size()) / sample_rate_hz : 0.0;
  }
};

// Reads a WAV/FLAC/OGG file (anything libsndfile opens). Throws LoadError naming the file.
AudioClip ReadAudioFile(const std::string& path, const AudioReadLimits& limits = {});

// Band-limited resampling (libsoxr, high quality: flat to 91% of the lower Nyquist, aliases and
// images below -130 dB), floor(n * to_hz / from_hz) samples out, no delay. Exposed for tests and
// for callers that already hold samples.
std::vector<float> Resample(const std::vector<float>& in, double from_hz, double to_hz);

// Fills in peak / silent / clipped_fraction from `samples` (used by ReadAudioFile).
void AnalyseLevels(AudioClip& clip, const AudioReadLimits& limits);

}  // namespace sas::surface
