// The vibration as the hand gets it (see felt.h).
#include "calibration/felt.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <numbers>
#include <opencv2/core.hpp>

#include "calibration/character.h"

namespace sas::kiosk {
namespace {

// One biquad in transposed direct form II (a0 = 1), designed by the bilinear transform with the
// cutoff prewarped; q is the section's Butterworth Q.
struct Section {
  double b0 = 1.0, b1 = 0.0, b2 = 0.0, a1 = 0.0, a2 = 0.0, s1 = 0.0, s2 = 0.0;
  double Process(double x) {
    const double y = b0 * x + s1;
    s1 = b1 * x - a1 * y + s2;
    s2 = b2 * x - a2 * y;
    return y;
  }
  std::complex<double> Response(double hz, double fs) const {
    const std::complex<double> z1 = std::polar(1.0, -2.0 * std::numbers::pi * hz / fs);
    return (b0 + b1 * z1 + b2 * z1 * z1) / (1.0 + a1 * z1 + a2 * z1 * z1);
  }
};

Section Design(double hz, double q, double fs, bool high_pass) {
  const double k = std::tan(std::numbers::pi * hz / fs);
  const double norm = 1.0 / (1.0 + k / q + k * k);
  Section s;
  if (high_pass) {
    s.b0 = norm;
    s.b1 = -2.0 * norm;
  } else {
    s.b0 = k * k * norm;
    s.b1 = 2.0 * k * k * norm;
  }
  s.b2 = s.b0;
  s.a1 = 2.0 * (k * k - 1.0) * norm;
  s.a2 = (1.0 - k / q + k * k) * norm;
  return s;
}

std::array<Section, 3> Weighting(double fs) {
  return {Design(kSkinLowHz, std::numbers::sqrt2 / 2.0, fs, true),
          Design(kSkinHighHz, 1.0 / (2.0 * std::cos(std::numbers::pi / 8.0)), fs, false),
          Design(kSkinHighHz, 1.0 / (2.0 * std::cos(3.0 * std::numbers::pi / 8.0)), fs, false)};
}

double Db(double power) { return power > 0.0 ? 10.0 * std::log10(power) : -300.0; }

}  // namespace

std::vector<float> SkinWeighted(std::span<const float> x, double fs_hz, std::size_t stride) {
  auto w = Weighting(fs_hz);
  std::vector<float> out;
  out.reserve(x.size() / std::max<std::size_t>(stride, 1) + 1);
  for (std::size_t i = 0; i < x.size(); i += std::max<std::size_t>(stride, 1)) {
    double v = std::isfinite(x[i]) ? x[i] : 0.0;
    for (auto& s : w) v = s.Process(v);
    out.push_back(static_cast<float>(v));
  }
  return out;
}

double SkinWeightingGain(double hz, double fs_hz) {
  std::complex<double> h = 1.0;
  for (const auto& s : Weighting(fs_hz)) h *= s.Response(hz, fs_hz);
  return std::abs(h);
}

FeltFigures MeasureFelt(std::span<const float> x, double fs_hz, double ceiling) {
  FeltFigures f;
  if (x.empty()) return f;
  const auto n = x.size();
  double square = 0.0;
  std::size_t near = 0;
  const double threshold = ceiling * std::pow(10.0, -1.0 / 20.0);
  for (const float v : x) {
    const double a = std::fabs(static_cast<double>(v));
    f.peak = std::max(f.peak, a);
    square += a * a;
    if (a >= threshold) ++near;
  }
  f.rms_db = Db(square / static_cast<double>(n));
  f.crest_db = square > 0.0 ? 20.0 * std::log10(f.peak) - f.rms_db : 0.0;
  f.near_ceiling = static_cast<double>(near) / static_cast<double>(n);
  const auto weighted = SkinWeighted(x, fs_hz);
  double weighted_square = 0.0;
  for (const float v : weighted) weighted_square += static_cast<double>(v) * v;
  f.skin_db = Db(weighted_square / static_cast<double>(n));

  // The stroke's periodogram, zero-padded to an FFT-friendly length.
  const int padded = cv::getOptimalDFTSize(static_cast<int>(n));
  cv::Mat in(1, padded, CV_64F, cv::Scalar(0.0)), spectrum;
  for (std::size_t i = 0; i < n; ++i) in.at<double>(0, static_cast<int>(i)) = x[i];
  cv::dft(in, spectrum, cv::DFT_COMPLEX_OUTPUT);
  constexpr std::array<double, 6> kEdges = {40.0, 63.0, 100.0, 160.0, 250.0, 400.0};
  std::array<double, 5> band{};
  double total = 0.0, skin_band = 0.0, above_1k = 0.0;
  for (int k = 1; k <= padded / 2; ++k) {
    const auto c = spectrum.at<cv::Vec2d>(0, k);
    const double p = c[0] * c[0] + c[1] * c[1];
    const double hz = k * fs_hz / padded;
    total += p;
    if (hz >= 40.0 && hz <= 400.0) skin_band += p;
    if (hz > 1000.0) above_1k += p;
    for (std::size_t b = 0; b + 1 < kEdges.size(); ++b) {
      if (hz >= kEdges[b] && hz < kEdges[b + 1]) band[b] += p;
    }
  }
  if (total > 0.0) {
    f.band_fraction = skin_band / total;
    f.above_1k_db = Db(above_1k / total);
  }
  {  // flatness over 40-400 Hz of the periodogram smoothed over ~5 Hz (a raw periodogram's
     // bins scatter like chi-square with 2 degrees of freedom, which alone pulls flatness down)
    const int smooth = std::max(1, static_cast<int>(std::round(5.0 * padded / fs_hz)));
    double log_sum = 0.0, sum = 0.0;
    int bins = 0;
    const int first = static_cast<int>(std::ceil(40.0 * padded / fs_hz));
    const int last = static_cast<int>(std::floor(400.0 * padded / fs_hz));
    double best = -1.0, best_hz = 40.0, moment = 0.0;
    for (int k = first; k + smooth <= last + 1; k += smooth) {
      double p = 0.0;
      for (int j = k; j < k + smooth; ++j) {
        const auto c = spectrum.at<cv::Vec2d>(0, j);
        p += c[0] * c[0] + c[1] * c[1];
      }
      log_sum += std::log(p + 1e-300);
      sum += p;
      ++bins;
      const double hz = (k + 0.5 * smooth) * fs_hz / padded;
      moment += p * std::log2(hz);
      if (p > best) {
        best = p;
        best_hz = hz;
      }
    }
    f.features[9] = bins > 0 && sum > 0.0 ? std::exp(log_sum / bins) / (sum / bins) : 0.0;
    f.features[13] = std::log2(best_hz);
    f.features[14] = sum > 0.0 ? moment / sum : std::log2(40.0);
  }
  double band_sum = 0.0;
  for (const double b : band) band_sum += b;
  for (std::size_t b = 0; b < band.size(); ++b) {
    f.features[b] = band_sum > 0.0 ? Db(band[b] / band_sum + 1e-12) : -120.0;
  }
  f.features[5] = f.crest_db;
  // The 10 ms envelope's spread over the frames within 40 dB of the loudest.
  const auto frame = static_cast<std::size_t>(std::max(1.0, std::round(0.01 * fs_hz)));
  std::vector<double> level;
  for (std::size_t s = 0; s + frame <= n; s += frame) {
    double sum = 0.0;
    for (std::size_t i = s; i < s + frame; ++i) sum += static_cast<double>(x[i]) * x[i];
    level.push_back(Db(sum / static_cast<double>(frame) + 1e-30));
  }
  if (!level.empty()) {
    const double loudest = *std::max_element(level.begin(), level.end());
    double sum = 0.0, sum2 = 0.0;
    int count = 0;
    for (const double l : level) {
      if (l < loudest - 40.0) continue;
      sum += l;
      sum2 += l * l;
      ++count;
    }
    const double mean = sum / count;
    f.features[6] = std::sqrt(std::max(0.0, sum2 / count - mean * mean));
  }
  f.features[7] = OnsetRatePerS(x, fs_hz);
  {
    double m2 = 0.0, m4 = 0.0;
    for (const float v : x) {
      const double s2 = static_cast<double>(v) * v;
      m2 += s2;
      m4 += s2 * s2;
    }
    m2 /= static_cast<double>(n);
    m4 /= static_cast<double>(n);
    f.features[8] = m2 > 0.0 ? std::log10(m4 / (m2 * m2)) : 0.0;
  }
  if (level.size() >= 4) {
    std::vector<double> sorted = level;
    std::sort(sorted.begin(), sorted.end());
    const auto at = [&](double q) {
      return sorted[static_cast<std::size_t>(q * static_cast<double>(sorted.size() - 1))];
    };
    f.features[10] = at(0.9) - at(0.1);
    std::size_t quiet = 0;
    for (const double l : level) quiet += l < at(0.9) - 20.0 ? 1 : 0;
    f.features[12] = static_cast<double>(quiet) / static_cast<double>(level.size());
    // Periodicity of the linear envelope (mean removed).
    std::vector<double> e(level.size());
    double mean = 0.0;
    for (std::size_t i = 0; i < level.size(); ++i) {
      e[i] = std::pow(10.0, level[i] / 20.0);
      mean += e[i] / static_cast<double>(e.size());
    }
    double var = 0.0;
    for (auto& v : e) {
      v -= mean;
      var += v * v;
    }
    double best = 0.0;
    for (std::size_t lag = 3; lag <= 30 && lag + 2 < e.size(); ++lag) {
      double c = 0.0;
      for (std::size_t i = 0; i + lag < e.size(); ++i) c += e[i] * e[i + lag];
      if (var > 0.0) best = std::max(best, c / var);
    }
    f.features[11] = best;
  }
  return f;
}

namespace {

// Each feature's mean and 1 / standard deviation over `x` (0 for a constant feature).
void Standardise(const std::vector<FeltFeatures>& x, FeltFeatures& mean, FeltFeatures& scale) {
  const double n = static_cast<double>(x.size());
  mean.fill(0.0);
  scale.fill(0.0);
  for (const auto& v : x) {
    for (int k = 0; k < kFeltFeatures; ++k) mean[k] += v[k] / n;
  }
  for (const auto& v : x) {
    for (int k = 0; k < kFeltFeatures; ++k) scale[k] += (v[k] - mean[k]) * (v[k] - mean[k]) / n;
  }
  for (auto& s : scale) s = s > 0.0 ? 1.0 / std::sqrt(s) : 0.0;
}

}  // namespace

void NearestNeighbours::Fit(const std::vector<FeltFeatures>& x, const std::vector<int>& label) {
  Standardise(x, mean_, scale_);
  z_.clear();
  for (const auto& v : x) {
    FeltFeatures z;
    for (int k = 0; k < kFeltFeatures; ++k) z[k] = (v[k] - mean_[k]) * scale_[k];
    z_.push_back(z);
  }
  label_ = label;
}

int NearestNeighbours::Predict(const FeltFeatures& x) const {
  std::vector<std::pair<double, int>> d;
  for (std::size_t i = 0; i < z_.size(); ++i) {
    double sum = 0.0;
    for (int k = 0; k < kFeltFeatures; ++k) {
      const double e = (x[k] - mean_[k]) * scale_[k] - z_[i][k];
      sum += e * e;
    }
    d.emplace_back(sum, label_[i]);
  }
  const auto k = std::min<std::size_t>(static_cast<std::size_t>(std::max(k_, 1)), d.size());
  if (k == 0) return -1;
  std::partial_sort(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(k), d.end());
  std::map<int, int> votes;
  int most = 0;
  for (std::size_t i = 0; i < k; ++i) most = std::max(most, ++votes[d[i].second]);
  for (std::size_t i = 0; i < k; ++i) {  // nearest first: the first with the most votes wins
    if (votes[d[i].second] == most) return d[i].second;
  }
  return -1;
}

void NearestCentroid::Fit(const std::vector<FeltFeatures>& x, const std::vector<int>& label) {
  Standardise(x, mean_, scale_);
  std::map<int, std::pair<FeltFeatures, int>> sums;
  for (std::size_t i = 0; i < x.size(); ++i) {
    auto& [sum, count] = sums[label[i]];
    for (int k = 0; k < kFeltFeatures; ++k) sum[k] += (x[i][k] - mean_[k]) * scale_[k];
    ++count;
  }
  centroid_.clear();
  label_.clear();
  for (auto& [l, entry] : sums) {
    for (auto& v : entry.first) v /= entry.second;
    centroid_.push_back(entry.first);
    label_.push_back(l);
  }
}

int NearestCentroid::Predict(const FeltFeatures& x) const {
  std::size_t best = centroid_.size();
  double best_d = 0.0;
  for (std::size_t c = 0; c < centroid_.size(); ++c) {
    double d = 0.0;
    for (int k = 0; k < kFeltFeatures; ++k) {
      const double z = (x[k] - mean_[k]) * scale_[k] - centroid_[c][k];
      d += z * z;
    }
    if (best == centroid_.size() || d < best_d) {
      best = c;
      best_d = d;
    }
  }
  return best < label_.size() ? label_[best] : -1;
}

}  // namespace sas::kiosk
