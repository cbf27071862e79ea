// Audio file reading with libsndfile (see audio_file.h). The resampler is a direct-form windowed
// sinc (J. O. Smith, "Digital Audio Resampling", bandlimited interpolation): for each output
// sample, sum the input under a sinc scaled to min(fs_in, fs_out)/2, Blackman-windowed over
// ±kZeroCrossings lobes. Cost is O(out * taps), fine for clips of seconds to minutes at load time.
#include "surface/audio_file.h"

#include <sndfile.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>

#include "surface/image_loader.h"  // LoadError

namespace sas::surface {
namespace {

[[noreturn]] void Fail(const std::string& path, const std::string& why) {
  throw LoadError("audio '" + path + "': " + why);
}

struct SndfileCloser {
  void operator()(SNDFILE* file) const { sf_close(file); }
};

constexpr int kZeroCrossings = 32;

// The windowed sinc, tabulated once at kTableSteps points per lobe and linearly interpolated:
// one table read per tap instead of three transcendental calls.
constexpr int kTableSteps = 512;

const std::vector<double>& KernelTable() {
  static const std::vector<double> table = [] {
    std::vector<double> t(static_cast<std::size_t>(kZeroCrossings * kTableSteps + 2), 0.0);
    for (std::size_t i = 0; i + 1 < t.size(); ++i) {
      const double x = static_cast<double>(i) / kTableSteps;  // lobes from the centre, >= 0
      if (x > kZeroCrossings) break;
      const double sinc = x == 0.0 ? 1.0 : std::sin(std::numbers::pi * x) / (std::numbers::pi * x);
      const double w_pos = (x / kZeroCrossings + 1.0) * 0.5;  // Blackman over [-Z, Z]
      const double window = 0.42 - 0.5 * std::cos(2.0 * std::numbers::pi * w_pos) +
                            0.08 * std::cos(4.0 * std::numbers::pi * w_pos);
      t[i] = sinc * window;
    }
    return t;
  }();
  return table;
}

}  // namespace

std::vector<float> Resample(const std::vector<float>& in, double from_hz, double to_hz) {
  if (in.empty() || from_hz == to_hz) return in;
  const std::vector<double>& table = KernelTable();
  const double ratio = to_hz / from_hz;
  const auto out_count =
      static_cast<std::size_t>(std::floor(static_cast<double>(in.size()) * ratio));
  std::vector<float> out(out_count);
  // Cut-off at the lower of the two Nyquist frequencies, expressed in input samples.
  const double bandwidth = std::min(1.0, ratio);
  const double half_width = kZeroCrossings / bandwidth;  // in input samples
  const auto n_in = static_cast<std::ptrdiff_t>(in.size());
  for (std::size_t i = 0; i < out_count; ++i) {
    const double centre = static_cast<double>(i) / ratio;
    const auto first =
        std::max<std::ptrdiff_t>(0, static_cast<std::ptrdiff_t>(std::ceil(centre - half_width)));
    const auto last = std::min<std::ptrdiff_t>(
        n_in - 1, static_cast<std::ptrdiff_t>(std::floor(centre + half_width)));
    double acc = 0.0;
    for (std::ptrdiff_t k = first; k <= last; ++k) {
      const double pos = std::fabs(static_cast<double>(k) - centre) * bandwidth * kTableSteps;
      const auto idx = static_cast<std::size_t>(pos);
      if (idx + 1 >= table.size()) continue;
      const double frac = pos - static_cast<double>(idx);
      const double kernel = table[idx] + frac * (table[idx + 1] - table[idx]);
      acc += static_cast<double>(in[static_cast<std::size_t>(k)]) * kernel;
    }
    out[i] = static_cast<float>(acc * bandwidth);
  }
  return out;
}

void AnalyseLevels(AudioClip& clip, const AudioReadLimits& limits) {
  float peak = 0.0f;
  std::size_t clipped = 0;
  for (const float s : clip.samples) {
    const float a = std::fabs(s);
    peak = std::max(peak, a);
    if (a >= limits.clip_level) ++clipped;
  }
  clip.peak = peak;
  clip.silent = peak < limits.silence_peak;
  clip.clipped_fraction = clip.samples.empty() ? 0.0
                                               : static_cast<double>(clipped) /
                                                     static_cast<double>(clip.samples.size());
}

AudioClip ReadAudioFile(const std::string& path, const AudioReadLimits& limits) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) Fail(path, "no such file");
  if (std::filesystem::file_size(path, ec) == 0) Fail(path, "empty file (zero bytes)");
  SF_INFO info{};
  std::unique_ptr<SNDFILE, SndfileCloser> file(sf_open(path.c_str(), SFM_READ, &info));
  if (!file) Fail(path, std::string("not a readable sound file: ") + sf_strerror(nullptr));

  // Everything below is decided from the header, before a sample is decoded.
  if (info.frames <= 0) Fail(path, "contains no audio frames");
  if (info.channels <= 0 || info.channels > limits.max_channels) {
    Fail(path, "has " + std::to_string(info.channels) + " channels; at most " +
                   std::to_string(limits.max_channels) + " are mixed down");
  }
  const auto rate = static_cast<double>(info.samplerate);
  if (!(rate >= limits.min_rate_hz && rate <= limits.max_rate_hz)) {
    Fail(path, "sample rate " + std::to_string(info.samplerate) + " Hz is outside " +
                   std::to_string(static_cast<int>(limits.min_rate_hz)) + "–" +
                   std::to_string(static_cast<int>(limits.max_rate_hz)) + " Hz");
  }
  const double duration_s = static_cast<double>(info.frames) / rate;
  if (duration_s > limits.max_duration_s) {
    Fail(path, "is " + std::to_string(static_cast<long long>(duration_s)) +
                   " s long; the limit is " +
                   std::to_string(static_cast<long long>(limits.max_duration_s)) + " s");
  }

  // Float files: do not let libsndfile rescale integers, and keep floats as they are.
  sf_command(file.get(), SFC_SET_NORM_FLOAT, nullptr, SF_TRUE);
  const auto channels = static_cast<std::size_t>(info.channels);
  AudioClip clip;
  clip.source_channels = info.channels;
  clip.source_rate_hz = rate;
  clip.samples.reserve(static_cast<std::size_t>(info.frames));
  std::vector<float> block(4096 * channels);
  std::size_t clipped = 0;
  for (;;) {
    const sf_count_t got = sf_readf_float(file.get(), block.data(), 4096);
    if (got <= 0) break;
    for (sf_count_t f = 0; f < got; ++f) {
      double sum = 0.0;
      for (std::size_t c = 0; c < channels; ++c) {
        const float s = block[static_cast<std::size_t>(f) * channels + c];
        if (!std::isfinite(s)) Fail(path, "contains non-finite samples (NaN or infinity)");
        if (std::fabs(s) >= limits.clip_level) ++clipped;
        // Float files may hold any finite value, e.g. 3e38: clip to full scale so the clip keeps
        // its [-1, 1] promise and the resampler's sums cannot overflow to infinity (a hazard
        // spotted while fixing the fuzz finding below; tested in test_audio_file.cpp).
        sum += std::clamp(static_cast<double>(s), -1.0, 1.0);
      }
      clip.samples.push_back(static_cast<float>(sum / static_cast<double>(channels)));
    }
    // A header may claim fewer frames than the data holds; never read past the checked length.
    if (clip.samples.size() >= static_cast<std::size_t>(info.frames)) break;
  }
  if (clip.samples.empty()) Fail(path, "no audio frames could be decoded (truncated or corrupt)");
  const double source_count = static_cast<double>(clip.samples.size() * channels);
  clip.samples = Resample(clip.samples, rate, limits.target_rate_hz);
  // A few frames at a high rate can resample to nothing (2 frames at 345 kHz = 0.28 samples at
  // 48 kHz; found by fuzzing): an empty clip would break every caller's "at least one sample".
  if (clip.samples.empty()) {
    Fail(path,
         "too short: " + std::to_string(static_cast<long long>(source_count) / info.channels) +
             " frames at " + std::to_string(info.samplerate) + " Hz give no sample at " +
             std::to_string(static_cast<int>(limits.target_rate_hz)) + " Hz");
  }
  clip.sample_rate_hz = limits.target_rate_hz;
  AnalyseLevels(clip, limits);
  clip.clipped_fraction = static_cast<double>(clipped) / source_count;
  return clip;
}

}  // namespace sas::surface
