// Character figures (calibration/character.h).
#include "calibration/character.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>
#include <vector>

namespace sas::kiosk {

double SpectralFlatness(std::span<const float> x, double fs_hz, double lo_hz, double hi_hz) {
  constexpr int kSegment = 4096;
  const int n = kSegment;
  const auto length = static_cast<int>(x.size());
  if (length == 0 || !(fs_hz > 0.0)) return 0.0;
  std::vector<double> window(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    window[static_cast<std::size_t>(i)] =
        0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * (i + 0.5) / n);
  }
  std::vector<double> psd(static_cast<std::size_t>(n / 2 + 1), 0.0);
  const int hop = n / 2;
  int segments = 0;
  cv::Mat in(1, n, CV_64F), spectrum;
  for (int start = 0; start == 0 || start + n <= length; start += hop) {
    for (int i = 0; i < n; ++i) {
      const int at = start + i;
      in.at<double>(0, i) =
          at < length ? window[static_cast<std::size_t>(i)] * x[static_cast<std::size_t>(at)] : 0.0;
    }
    cv::dft(in, spectrum, cv::DFT_COMPLEX_OUTPUT);
    for (int k = 0; k <= n / 2; ++k) {
      const cv::Vec2d c = spectrum.at<cv::Vec2d>(0, k);
      psd[static_cast<std::size_t>(k)] += c[0] * c[0] + c[1] * c[1];
    }
    ++segments;
    if (start + n >= length) break;
  }
  double log_sum = 0.0, sum = 0.0;
  int bins = 0;
  for (int k = 1; k <= n / 2; ++k) {
    const double f = k * fs_hz / n;
    if (f < lo_hz || f > hi_hz) continue;
    const double p = psd[static_cast<std::size_t>(k)] / segments;
    if (!(p > 0.0)) return 0.0;  // a bin with no power: the geometric mean is 0
    log_sum += std::log(p);
    sum += p;
    ++bins;
  }
  if (bins == 0 || !(sum > 0.0)) return 0.0;
  return std::exp(log_sum / bins) / (sum / bins);
}

double CrestFactorDb(std::span<const float> x) {
  double peak = 0.0, square = 0.0;
  for (const float v : x) {
    peak = std::max(peak, static_cast<double>(std::fabs(v)));
    square += static_cast<double>(v) * v;
  }
  if (x.empty() || !(square > 0.0)) return 0.0;
  return 20.0 * std::log10(peak / std::sqrt(square / static_cast<double>(x.size())));
}

double OnsetRatePerS(std::span<const float> x, double fs_hz) {
  const auto frame = static_cast<std::size_t>(std::max(1.0, std::round(0.005 * fs_hz)));
  const std::size_t frames = x.size() / frame;
  if (frames == 0) return 0.0;
  std::vector<double> level(frames);
  double loudest = -400.0;
  for (std::size_t f = 0; f < frames; ++f) {
    double sum = 0.0;
    for (std::size_t i = 0; i < frame; ++i) {
      const double v = x[f * frame + i];
      sum += v * v;
    }
    level[f] = 10.0 * std::log10(sum / static_cast<double>(frame) + 1e-30);
    loudest = std::max(loudest, level[f]);
  }
  constexpr std::size_t kLookBack = 6;    // 30 ms
  constexpr std::size_t kRefractory = 4;  // 20 ms
  int onsets = 0;
  std::size_t last = 0;
  bool any = false;
  for (std::size_t f = 1; f < frames; ++f) {
    double quietest = level[f - 1];
    for (std::size_t back = 2; back <= kLookBack && back <= f; ++back) {
      quietest = std::min(quietest, level[f - back]);
    }
    if (level[f] - quietest >= kOnsetRiseDb && level[f] > loudest - kOnsetFloorDb &&
        (!any || f - last >= kRefractory)) {
      ++onsets;
      last = f;
      any = true;
    }
  }
  return onsets / (static_cast<double>(x.size()) / fs_hz);
}

}  // namespace sas::kiosk
