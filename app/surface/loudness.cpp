// K-weighted loudness and RMS (see loudness.h). Filter design after ITU-R BS.1770-4 Annex 1: the
// standard gives coefficients at 48 kHz only; the analogue prototypes below (shelf f0, gain, Q and
// the high-pass f0, Q, as fitted by Brecht De Man and used in libebur128) reproduce them there and
// give the same curve at other rates through the bilinear transform with tan() pre-warping.
#include "surface/loudness.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sas::surface {
namespace {

constexpr double kShelfHz = 1681.974450955533;
constexpr double kShelfGainDb = 3.999843853973347;
constexpr double kShelfQ = 0.7071752369554196;
constexpr double kShelfMidExponent = 0.4996667741545416;  // Vb = Vh^this
constexpr double kHighPassHz = 38.13547087602444;
constexpr double kHighPassQ = 0.5003270373238773;
constexpr double kLoudnessOffsetDb = -0.691;  // BS.1770: 1 kHz sine at 0 dBFS peak reads -3.01

double PowerDb(double mean_square) {
  return mean_square > 0.0 ? 10.0 * std::log10(mean_square) : kSilenceDb;
}

}  // namespace

std::array<synth::Biquad, 2> KWeightingFilters(double sample_rate_hz) {
  std::array<synth::Biquad, 2> f{};
  {
    const double k = std::tan(std::numbers::pi * kShelfHz / sample_rate_hz);
    const double vh = std::pow(10.0, kShelfGainDb / 20.0);
    const double vb = std::pow(vh, kShelfMidExponent);
    const double a0 = 1.0 + k / kShelfQ + k * k;
    f[0].b0 = (vh + vb * k / kShelfQ + k * k) / a0;
    f[0].b1 = 2.0 * (k * k - vh) / a0;
    f[0].b2 = (vh - vb * k / kShelfQ + k * k) / a0;
    f[0].a1 = 2.0 * (k * k - 1.0) / a0;
    f[0].a2 = (1.0 - k / kShelfQ + k * k) / a0;
  }
  {
    const double k = std::tan(std::numbers::pi * kHighPassHz / sample_rate_hz);
    const double a0 = 1.0 + k / kHighPassQ + k * k;
    f[1].b0 = 1.0;  // BS.1770 leaves the RLB numerator un-normalised: 1, -2, 1
    f[1].b1 = -2.0;
    f[1].b2 = 1.0;
    f[1].a1 = 2.0 * (k * k - 1.0) / a0;
    f[1].a2 = (1.0 - k / kHighPassQ + k * k) / a0;
  }
  return f;
}

double KWeightedLoudnessDb(std::span<const float> samples, double sample_rate_hz, std::size_t from,
                           std::size_t to, std::size_t stride) {
  const FrameWindow window{from, to};
  return KWeightedLoudnessDb(samples, sample_rate_hz, std::span(&window, 1), stride).front();
}

std::vector<double> KWeightedLoudnessDb(std::span<const float> samples, double sample_rate_hz,
                                        std::span<const FrameWindow> windows, std::size_t stride) {
  if (stride == 0 || !(sample_rate_hz > 0.0))
    return std::vector<double>(windows.size(), kSilenceDb);
  for (std::size_t w = 1; w < windows.size(); ++w) {
    if (windows[w].from < windows[w - 1].to) {  // out of order or overlapping: one at a time
      std::vector<double> loudness;
      for (const auto& one : windows) {
        loudness.push_back(KWeightedLoudnessDb(samples, sample_rate_hz, one.from, one.to, stride));
      }
      return loudness;
    }
  }
  const std::size_t frames = (samples.size() + stride - 1) / stride;
  auto filters = KWeightingFilters(sample_rate_hz);
  std::vector<double> loudness;
  std::size_t i = 0;  // next frame through the filters
  for (const auto& w : windows) {
    const std::size_t to = std::min(w.to, frames);
    double sum = 0.0;
    for (; i < to; ++i) {
      double y = samples[i * stride];
      for (auto& section : filters) y = section.Process(y);
      if (i >= w.from) sum += y * y;
    }
    const double mean_square = w.from < to ? sum / static_cast<double>(to - w.from) : 0.0;
    loudness.push_back(mean_square > 0.0 ? kLoudnessOffsetDb + PowerDb(mean_square) : kSilenceDb);
  }
  return loudness;
}

double RmsDb(std::span<const float> samples, std::size_t from, std::size_t to, std::size_t stride) {
  if (stride == 0) return kSilenceDb;
  const std::size_t frames = (samples.size() + stride - 1) / stride;
  to = std::min(to, frames);
  if (from >= to) return kSilenceDb;
  double sum = 0.0;
  for (std::size_t i = from; i < to; ++i) {
    const double x = samples[i * stride];
    sum += x * x;
  }
  return PowerDb(sum / static_cast<double>(to - from));
}

}  // namespace sas::surface
