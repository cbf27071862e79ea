// Speech engines' figures (see voice_figures.h).
#include "voice_figures.h"

#include <ebur128.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>
#include <numbers>
#include <opencv2/core.hpp>
#include <stdexcept>

#include "surface/audio_file.h"
#include "surface/loudness.h"

namespace sas::cues {
namespace {

constexpr int kFftSize = 1024;
constexpr double kFrameS = 0.040;
constexpr double kHopS = 0.010;
constexpr double kMinF0Hz = 60.0;
constexpr double kMaxF0Hz = 400.0;
constexpr double kVoicedCorrelation = 0.6;
constexpr double kQuietBelowLoudestDb = 35.0;
// A lag within this share of the best correlation counts as the period (see PitchTrack).
constexpr double kOctaveShare = 0.85;

// Power spectrum (bins 0..n/2) of x[from, from + n) under a Hann window, zero beyond the end.
std::vector<double> PowerSpectrum(std::span<const float> x, std::size_t from) {
  cv::Mat in(1, kFftSize, CV_64F, cv::Scalar(0.0));
  for (int i = 0; i < kFftSize; ++i) {
    const std::size_t at = from + static_cast<std::size_t>(i);
    if (at >= x.size()) break;
    const double w = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * i / kFftSize);
    in.at<double>(0, i) = w * static_cast<double>(x[at]);
  }
  cv::Mat spectrum;
  cv::dft(in, spectrum, cv::DFT_COMPLEX_OUTPUT);
  std::vector<double> power(kFftSize / 2 + 1);
  for (int k = 0; k <= kFftSize / 2; ++k) {
    const auto c = spectrum.at<cv::Vec2d>(0, k);
    power[static_cast<std::size_t>(k)] = c[0] * c[0] + c[1] * c[1];
  }
  return power;
}

double Percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double at = p * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(at));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (at - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

}  // namespace

double BandEdgeHz(std::span<const float> x, double rate_hz) {
  // Whole segments only (one zero-padded if the clip is shorter): a segment cut by the clip's end
  // would spread the cut's broadband click over the spectrum.
  std::vector<double> mean(kFftSize / 2 + 1, 0.0);
  for (std::size_t from = 0; from == 0 || from + kFftSize <= x.size(); from += kFftSize / 2) {
    const auto p = PowerSpectrum(x, from);
    for (std::size_t k = 0; k < mean.size(); ++k) mean[k] += p[k];
  }
  const double top = *std::max_element(mean.begin(), mean.end());
  if (top <= 0.0) return 0.0;
  const double floor = top * std::pow(10.0, -kBandEdgeDb / 10.0);
  std::size_t edge = 0;
  for (std::size_t k = 0; k < mean.size(); ++k) {
    if (mean[k] >= floor) edge = k;
  }
  return static_cast<double>(edge) * rate_hz / kFftSize;
}

std::vector<double> PitchTrack(std::span<const float> x, double rate_hz) {
  const auto frame = static_cast<std::size_t>(kFrameS * rate_hz);
  const auto hop = static_cast<std::size_t>(kHopS * rate_hz);
  const auto min_lag = static_cast<std::size_t>(rate_hz / kMaxF0Hz);
  const auto max_lag = static_cast<std::size_t>(rate_hz / kMinF0Hz);
  std::vector<double> energy;
  for (std::size_t from = 0; from + frame <= x.size(); from += hop) {
    double e = 0.0;
    for (std::size_t i = 0; i < frame; ++i) e += double(x[from + i]) * double(x[from + i]);
    energy.push_back(e);
  }
  const double loudest = energy.empty() ? 0.0 : *std::max_element(energy.begin(), energy.end());
  const double quiet = loudest * std::pow(10.0, -kQuietBelowLoudestDb / 10.0);
  std::vector<double> f0(energy.size(), 0.0);
  for (std::size_t f = 0; f < energy.size(); ++f) {
    if (energy[f] <= quiet || energy[f] <= 0.0) continue;
    const std::size_t from = f * hop;
    // Normalised cross-correlation of the frame's first part with itself one lag later.
    const std::size_t n = frame - max_lag;
    std::vector<double> r(max_lag + 2, 0.0);
    for (std::size_t lag = min_lag; lag <= max_lag + 1 && from + lag + n <= x.size(); ++lag) {
      double xy = 0.0, xx = 0.0, yy = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        const double a = x[from + i], b = x[from + i + lag];
        xy += a * b;
        xx += a * a;
        yy += b * b;
      }
      r[lag] = xx > 0.0 && yy > 0.0 ? xy / std::sqrt(xx * yy) : 0.0;
    }
    const auto best = std::max_element(r.begin() + static_cast<std::ptrdiff_t>(min_lag),
                                       r.begin() + static_cast<std::ptrdiff_t>(max_lag + 1));
    if (*best < kVoicedCorrelation) continue;
    // The shortest lag nearly as good as the best: a period's multiples correlate as well, and
    // taking them would halve F0.
    std::size_t lag = min_lag;
    while (lag < max_lag && !(r[lag] >= kOctaveShare * *best && r[lag] >= r[lag - 1] && r[lag] >= r[lag + 1])) {
      ++lag;
    }
    // Parabolic interpolation between the neighbouring lags.
    const double a = r[lag - 1], b = r[lag], c = r[lag + 1];
    const double denom = a - 2.0 * b + c;
    const double shift = denom != 0.0 ? 0.5 * (a - c) / denom : 0.0;
    f0[f] = rate_hz / (static_cast<double>(lag) + std::clamp(shift, -0.5, 0.5));
  }
  return f0;
}

double VoicedFlatness(std::span<const float> x, double rate_hz, const std::vector<double>& f0,
                      double lo_hz, double hi_hz) {
  const auto hop = static_cast<std::size_t>(kHopS * rate_hz);
  const auto lo = static_cast<std::size_t>(std::ceil(lo_hz * kFftSize / rate_hz));
  const auto hi = static_cast<std::size_t>(std::floor(hi_hz * kFftSize / rate_hz));
  double sum = 0.0;
  int count = 0;
  for (std::size_t f = 0; f < f0.size(); ++f) {
    if (f0[f] <= 0.0) continue;
    // Centre the longer spectral window on the pitch frame.
    const std::size_t centre = f * hop + static_cast<std::size_t>(kFrameS * rate_hz / 2);
    // Whole windows only (see BandEdgeHz): shifted inwards at the clip's ends.
    std::size_t from = centre > kFftSize / 2 ? centre - kFftSize / 2 : 0;
    if (x.size() >= kFftSize) from = std::min(from, x.size() - kFftSize);
    const auto p = PowerSpectrum(x, from);
    double log_sum = 0.0, lin_sum = 0.0;
    for (std::size_t k = lo; k <= hi; ++k) {
      const double v = std::max(p[k], 1e-30);
      log_sum += std::log(v);
      lin_sum += v;
    }
    const double n = static_cast<double>(hi - lo + 1);
    if (lin_sum <= 0.0) continue;
    sum += std::exp(log_sum / n) / (lin_sum / n);
    ++count;
  }
  return count > 0 ? sum / count : 0.0;
}

double TruePeakDbtp(std::span<const float> x, double rate_hz) {
  struct Deleter {
    void operator()(ebur128_state* s) const { ebur128_destroy(&s); }
  };
  std::unique_ptr<ebur128_state, Deleter> meter(
      ebur128_init(1, static_cast<unsigned long>(rate_hz), EBUR128_MODE_TRUE_PEAK));
  if (!meter) throw std::runtime_error("libebur128: cannot start a meter");
  ebur128_add_frames_float(meter.get(), x.data(), x.size());
  double peak = 0.0;
  ebur128_true_peak(meter.get(), 0, &peak);
  return peak > 0.0 ? 20.0 * std::log10(peak) : surface::kSilenceDb;
}

std::vector<std::string> Words(const std::string& text) {
  std::vector<std::string> words;
  std::string word;
  for (char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (std::isalnum(c) || c >= 0x80 || c == '\'') {
      word += static_cast<char>(std::tolower(c));
    } else if (!word.empty()) {
      words.push_back(word);
      word.clear();
    }
  }
  if (!word.empty()) words.push_back(word);
  return words;
}

std::size_t WordEdits(const std::vector<std::string>& reference,
                      const std::vector<std::string>& heard) {
  std::vector<std::size_t> row(heard.size() + 1);
  for (std::size_t j = 0; j <= heard.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= reference.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= heard.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1,
                         diagonal + (reference[i - 1] == heard[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[heard.size()];
}

VoiceFigures MeasureCue(const Speech& raw, const std::string& text,
                        std::vector<float>* shaped_16k) {
  VoiceFigures out;
  out.source_rate_hz = raw.rate_hz;
  out.band_edge_hz = BandEdgeHz(raw.samples, raw.rate_hz);
  const std::vector<float> shaped = ShapeCue(raw);
  out.duration_s = static_cast<double>(shaped.size()) / kCueRateHz;
  out.words = static_cast<double>(Words(text).size());
  out.loudness_lufs = surface::KWeightedLoudnessDb(shaped, kCueRateHz, 0, shaped.size());
  out.true_peak_dbtp = TruePeakDbtp(shaped, kCueRateHz);
  const std::vector<float> low = surface::Resample(shaped, kCueRateHz, kAnalysisRateHz);
  const auto f0 = PitchTrack(low, kAnalysisRateHz);
  out.frames = static_cast<double>(f0.size());
  for (double f : f0) {
    if (f > 0.0) out.f0_hz.push_back(f);
  }
  out.voiced_frames = static_cast<double>(out.f0_hz.size());
  out.flatness_sum = VoicedFlatness(low, kAnalysisRateHz, f0) * out.voiced_frames;
  if (shaped_16k != nullptr) *shaped_16k = low;
  return out;
}

VoiceSummary Summarise(const std::vector<VoiceFigures>& cues) {
  VoiceSummary s;
  if (cues.empty()) return s;
  std::vector<double> edges, f0;
  double words = 0.0, voiced = 0.0, frames = 0.0, flatness = 0.0;
  s.source_rate_hz = cues.front().source_rate_hz;
  s.loudness_min_lufs = cues.front().loudness_lufs;
  s.loudness_max_lufs = cues.front().loudness_lufs;
  for (const auto& c : cues) {
    edges.push_back(c.band_edge_hz);
    s.duration_s += c.duration_s;
    words += c.words;
    s.loudness_min_lufs = std::min(s.loudness_min_lufs, c.loudness_lufs);
    s.loudness_max_lufs = std::max(s.loudness_max_lufs, c.loudness_lufs);
    s.true_peak_max_dbtp = std::max(s.true_peak_max_dbtp, c.true_peak_dbtp);
    voiced += c.voiced_frames;
    frames += c.frames;
    flatness += c.flatness_sum;
    f0.insert(f0.end(), c.f0_hz.begin(), c.f0_hz.end());
  }
  s.band_edge_hz = Percentile(edges, 0.5);
  s.words_per_minute = s.duration_s > 0.0 ? 60.0 * words / s.duration_s : 0.0;
  s.voiced_share = frames > 0.0 ? voiced / frames : 0.0;
  s.f0_median_hz = Percentile(f0, 0.5);
  const double p5 = Percentile(f0, 0.05), p95 = Percentile(f0, 0.95);
  s.f0_range_st = p5 > 0.0 ? 12.0 * std::log2(p95 / p5) : 0.0;
  s.hf_flatness = voiced > 0.0 ? flatness / voiced : 0.0;
  return s;
}

}  // namespace sas::cues
