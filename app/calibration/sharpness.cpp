// ISO 532-1 stationary loudness and DIN 45692 sharpness (see sharpness.h).
#include "calibration/sharpness.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>

namespace sas::kiosk {
namespace {

// ISO 532-1:2017 annex A tables (Zwicker et al. 1991 name them RAP, DLL, LTQ, A0, DCB, ZUP, RNS,
// USL).

// Level ranges (dB) of the low-frequency correction by the equal-loudness contours.
constexpr std::array<double, 8> kRangeTopDb = {45, 55, 65, 71, 80, 90, 100, 120};
// The correction (dB) of the 11 bands 25–250 Hz within each range.
constexpr std::array<std::array<double, 11>, 8> kLowBandCorrectionDb = {{
    {-32, -24, -16, -10, -5, 0, -7, -3, 0, -2, 0},
    {-29, -22, -15, -10, -4, 0, -7, -2, 0, -2, 0},
    {-27, -19, -14, -9, -4, 0, -6, -2, 0, -2, 0},
    {-25, -17, -12, -9, -3, 0, -5, -2, 0, -2, 0},
    {-23, -16, -11, -7, -3, 0, -4, -1, 0, -1, 0},
    {-20, -14, -10, -6, -3, 0, -4, -1, 0, -1, 0},
    {-18, -12, -9, -6, -2, 0, -3, -1, 0, -1, 0},
    {-15, -10, -8, -4, -2, 0, -3, -1, 0, -1, 0},
}};
// Critical-band level at the threshold in quiet, without the ear's transmission (dB).
constexpr std::array<double, 20> kThresholdDb = {30, 18, 12, 8, 7, 6, 5, 4, 3, 3,
                                                 3,  3,  3,  3, 3, 3, 3, 3, 3, 3};
// The ear's transmission (dB, subtracted from the band level).
constexpr std::array<double, 20> kTransmissionDb = {
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, -0.5, -1.6, -3.2, -5.4, -5.6, -4.0, -1.5, 2.0, 5.0, 12.0};
// Third-octave to critical-band level adaptation (dB, subtracted above the threshold).
constexpr std::array<double, 20> kBandwidthDb = {-0.25, -0.6, -0.8, -0.8, -0.5, 0.0, 0.5,
                                                 1.1,   1.5,  1.7,  1.8,  1.8,  1.7, 1.6,
                                                 1.4,   1.2,  0.8,  0.5,  0.0,  -0.5};
// Upper edges (Bark) of the 21 approximated critical bands.
constexpr std::array<double, 21> kBandTopBark = {0.9,  1.8,  2.8,  3.5,  4.4,  5.4,  6.6,
                                                 7.9,  9.2,  10.6, 12.3, 13.8, 15.2, 16.7,
                                                 18.1, 19.3, 20.6, 21.8, 22.7, 23.6, 24.0};
// Specific-loudness ranges (sone/Bark) that set the steepness of the upper slopes ...
constexpr std::array<double, 18> kSlopeRangeSone = {21.5, 18.0, 15.1, 11.5, 9.0,   6.1,
                                                    4.4,  3.1,  2.13, 1.36, 0.82,  0.42,
                                                    0.30, 0.22, 0.15, 0.10, 0.035, 0.0};
// ... and the steepness (sone/Bark per Bark) in each range, by critical band (the last column
// serves every band from the eighth on).
constexpr std::array<std::array<double, 8>, 18> kSlopeSteepness = {{
    {13.00, 8.20, 6.30, 5.50, 5.50, 5.50, 5.50, 5.50},
    {9.00, 7.50, 6.00, 5.10, 4.50, 4.50, 4.50, 4.50},
    {7.80, 6.70, 5.60, 4.90, 4.40, 3.90, 3.90, 3.90},
    {6.20, 5.40, 4.60, 4.00, 3.50, 3.20, 3.20, 3.20},
    {4.50, 3.80, 3.60, 3.20, 2.90, 2.70, 2.70, 2.70},
    {3.70, 3.00, 2.80, 2.35, 2.20, 2.20, 2.20, 2.20},
    {2.90, 2.30, 2.10, 1.90, 1.80, 1.70, 1.70, 1.70},
    {2.40, 1.70, 1.50, 1.35, 1.30, 1.30, 1.30, 1.30},
    {1.95, 1.45, 1.30, 1.15, 1.10, 1.10, 1.10, 1.10},
    {1.50, 1.20, 0.94, 0.86, 0.82, 0.82, 0.82, 0.82},
    {0.72, 0.67, 0.64, 0.63, 0.62, 0.62, 0.62, 0.62},
    {0.59, 0.53, 0.51, 0.50, 0.42, 0.42, 0.42, 0.42},
    {0.40, 0.33, 0.26, 0.24, 0.22, 0.22, 0.22, 0.22},
    {0.27, 0.21, 0.20, 0.18, 0.17, 0.17, 0.17, 0.17},
    {0.16, 0.15, 0.14, 0.12, 0.11, 0.11, 0.11, 0.11},
    {0.12, 0.11, 0.10, 0.08, 0.08, 0.08, 0.08, 0.08},
    {0.09, 0.08, 0.07, 0.06, 0.06, 0.06, 0.06, 0.05},
    {0.06, 0.05, 0.03, 0.02, 0.02, 0.02, 0.02, 0.02},
}};

// ISO 532-1:2017's third-octave filters (its coefficient table, for 48 kHz): band b is three
// second-order sections with numerators 1 + 2z⁻¹ + z⁻², 1 - z⁻², 1 - 2z⁻¹ + z⁻² and denominators
// 1 + a1 z⁻¹ + a2 z⁻², tabulated as their differences from 1 - 2z⁻¹ + z⁻²: a1 = -2 - d1,
// a2 = 1 - d2 (the pairs below, one per section), and one gain per band.
struct BandFilter {
  std::array<std::array<double, 2>, 3> d;
  double gain;
};
constexpr std::array<BandFilter, kLoudnessBands> kBandFilters = {{
    {{{{-6.70260e-4, 6.59453e-4}, {-3.75071e-4, 3.61926e-4}, {-3.06523e-4, 2.97634e-4}}},
     4.30764e-11},
    {{{{-8.47258e-4, 8.30131e-4}, {-4.76448e-4, 4.55616e-4}, {-3.88773e-4, 3.74685e-4}}},
     8.59340e-11},
    {{{{-1.07210e-3, 1.04496e-3}, {-6.06567e-4, 5.73553e-4}, {-4.94004e-4, 4.71677e-4}}},
     1.71424e-10},
    {{{{-1.35836e-3, 1.31535e-3}, {-7.74327e-4, 7.22007e-4}, {-6.29154e-4, 5.93771e-4}}},
     3.41944e-10},
    {{{{-1.72380e-3, 1.65564e-3}, {-9.91780e-4, 9.08866e-4}, {-8.03529e-4, 7.47455e-4}}},
     6.82035e-10},
    {{{{-2.19188e-3, 2.08388e-3}, {-1.27545e-3, 1.14406e-3}, {-1.02976e-3, 9.40900e-4}}},
     1.36026e-9},
    {{{{-2.79386e-3, 2.62274e-3}, {-1.64828e-3, 1.44006e-3}, {-1.32520e-3, 1.18438e-3}}},
     2.71261e-9},
    {{{{-3.57182e-3, 3.30071e-3}, {-2.14252e-3, 1.81258e-3}, {-1.71397e-3, 1.49082e-3}}},
     5.40870e-9},
    {{{{-4.58305e-3, 4.15355e-3}, {-2.80413e-3, 2.28135e-3}, {-2.23006e-3, 1.87646e-3}}},
     1.07826e-8},
    {{{{-5.90655e-3, 5.22622e-3}, {-3.69947e-3, 2.87118e-3}, {-2.92205e-3, 2.36178e-3}}},
     2.14910e-8},
    {{{{-7.65243e-3, 6.57493e-3}, {-4.92540e-3, 3.61318e-3}, {-3.86007e-3, 2.97240e-3}}},
     4.28228e-8},
    {{{{-1.00023e-2, 8.29610e-3}, {-6.63788e-3, 4.55999e-3}, {-5.15982e-3, 3.75306e-3}}},
     8.54316e-8},
    {{{{-1.31230e-2, 1.04220e-2}, {-9.02274e-3, 5.73132e-3}, {-6.94543e-3, 4.71734e-3}}},
     1.70009e-7},
    {{{{-1.73693e-2, 1.30947e-2}, {-1.24176e-2, 7.20526e-3}, {-9.46002e-3, 5.93145e-3}}},
     3.38215e-7},
    {{{{-2.31934e-2, 1.64308e-2}, {-1.73009e-2, 9.04761e-3}, {-1.30358e-2, 7.44926e-3}}},
     6.71990e-7},
    {{{{-3.13292e-2, 2.06370e-2}, {-2.44342e-2, 1.13731e-2}, {-1.82108e-2, 9.36778e-3}}},
     1.33531e-6},
    {{{{-4.28261e-2, 2.59325e-2}, {-3.49619e-2, 1.43046e-2}, {-2.57855e-2, 1.17912e-2}}},
     2.65172e-6},
    {{{{-5.91733e-2, 3.25054e-2}, {-5.06072e-2, 1.79513e-2}, {-3.69401e-2, 1.48094e-2}}},
     5.25477e-6},
    {{{{-8.26348e-2, 4.05894e-2}, {-7.40348e-2, 2.24476e-2}, {-5.34977e-2, 1.85371e-2}}},
     1.03780e-5},
    {{{{-1.17018e-1, 5.08116e-2}, {-1.09516e-1, 2.81387e-2}, {-7.85097e-2, 2.32872e-2}}},
     2.04870e-5},
    {{{{-1.67714e-1, 6.37872e-2}, {-1.63378e-1, 3.53729e-2}, {-1.16419e-1, 2.93723e-2}}},
     4.05198e-5},
    {{{{-2.42528e-1, 7.98576e-2}, {-2.45161e-1, 4.43370e-2}, {-1.73972e-1, 3.70015e-2}}},
     7.97914e-5},
    {{{{-3.53142e-1, 9.96330e-2}, {-3.69163e-1, 5.53535e-2}, {-2.61399e-1, 4.65428e-2}}},
     1.56511e-4},
    {{{{-5.16316e-1, 1.24177e-1}, {-5.55473e-1, 6.89403e-2}, {-3.93998e-1, 5.86715e-2}}},
     3.04954e-4},
    {{{{-7.56635e-1, 1.55023e-1}, {-8.34281e-1, 8.58123e-2}, {-5.94547e-1, 7.43960e-2}}},
     5.99157e-4},
    {{{{-1.10165e+0, 1.91713e-1}, {-1.23939e+0, 1.05243e-1}, {-8.91666e-1, 9.40354e-2}}},
     1.16544e-3},
    {{{{-1.58477e+0, 2.39049e-1}, {-1.80505e+0, 1.28794e-1}, {-1.32500e+0, 1.21333e-1}}},
     2.27488e-3},
    {{{{-2.50630e+0, 1.42308e-1}, {-2.19464e+0, 2.76470e-1}, {-1.90231e+0, 1.47304e-1}}},
     3.91006e-3},
}};
// The filters' design rate: their responses are read at a frequency's angle at this rate.
constexpr double kFilterRateHz = 48000.0;

constexpr double kEmptyBandDb = -100.0;
constexpr double kBarkStep = 0.1;

// The first slope range whose lower bound lies under n: where a slope starting at n falls.
std::size_t SlopeRange(double n) {
  std::size_t j = 0;
  while (j + 1 < kSlopeRangeSone.size() && kSlopeRangeSone[j] >= n) ++j;
  return j;
}

// Core loudness of the 20 critical bands (the 21st, above 12.5 kHz, is zero).
std::array<double, 21> CoreLoudness(const std::array<double, kLoudnessBands>& levels_db) {
  // The 11 bands up to 250 Hz, weighted by the equal-loudness contours of their level range and
  // grouped into the first three critical bands (25–80, 100–160, 200–250 Hz).
  std::array<double, 3> low_intensity{};
  for (std::size_t b = 0; b < 11; ++b) {
    const double level = std::min(levels_db[b], kRangeTopDb.back());
    std::size_t range = 0;
    while (range + 1 < kRangeTopDb.size() &&
           level > kRangeTopDb[range] - kLowBandCorrectionDb[range][b]) {
      ++range;
    }
    const double intensity = std::pow(10.0, (level + kLowBandCorrectionDb[range][b]) / 10.0);
    low_intensity[b < 6 ? 0 : (b < 9 ? 1 : 2)] += intensity;
  }
  std::array<double, 21> core{};
  for (std::size_t i = 0; i < 20; ++i) {
    double level = i < 3 ? 10.0 * std::log10(std::max(low_intensity[i], 1e-30))
                         : levels_db[i + 8];  // bands 315 Hz .. 12.5 kHz
    level -= kTransmissionDb[i];
    if (level <= kThresholdDb[i]) continue;
    level -= kBandwidthDb[i];
    // Zwicker's loudness function: N' = 0.0635 · 10^(0.025 LTQ) · ((1 - s + s ·
    // 10^((L-LTQ)/10))^0.25
    // - 1), s = 0.25 the threshold factor.
    constexpr double kS = 0.25;
    const double n =
        0.0635 * std::pow(10.0, 0.025 * kThresholdDb[i]) *
        (std::pow(1.0 - kS + kS * std::pow(10.0, 0.1 * (level - kThresholdDb[i])), 0.25) - 1.0);
    core[i] = std::max(n, 0.0);
  }
  // The threshold in quiet falls steeply across the lowest critical band: its loudness is reduced.
  const double correction = 0.4 + 0.32 * std::pow(core[0], 0.2);
  if (correction < 1.0) core[0] *= correction;
  return core;
}

}  // namespace

double LoudnessBandCentreHz(int band) {
  return 1000.0 * std::pow(10.0, (band - 16) / 10.0);
}

std::array<double, kLoudnessBands> ThirdOctaveLevelsDbSpl(std::span<const float> x, double fs_hz,
                                                          double full_scale_db_spl) {
  std::array<double, kLoudnessBands> levels;
  levels.fill(kEmptyBandDb);
  const auto count = x.size();
  if (count < 2 || !(fs_hz > 0.0)) return levels;
  const int n = cv::getOptimalDFTSize(static_cast<int>(count));
  cv::Mat in = cv::Mat::zeros(1, n, CV_64F);
  double window_power = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const double w = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * (static_cast<double>(i) + 0.5) /
                                          static_cast<double>(count));
    in.at<double>(0, static_cast<int>(i)) = w * x[i];
    window_power += w * w;
  }
  cv::Mat spectrum;
  cv::dft(in, spectrum, cv::DFT_COMPLEX_OUTPUT);
  // Parseval for a windowed stationary signal: its mean square is the one-sided power sum
  // 2 Σ|X_k|² / (n Σ w²). A band's mean square is that sum weighted by the band filter's power
  // response: what squaring and averaging its output would give on a stationary signal.
  const double scale = 2.0 / (static_cast<double>(n) * window_power);
  std::array<double, kLoudnessBands> mean_square{};
  const double bin_hz = fs_hz / n;
  for (int k = 1; k < (n + 1) / 2; ++k) {
    const double f = k * bin_hz;
    if (f >= 0.5 * kFilterRateHz) break;
    const cv::Vec2d c = spectrum.at<cv::Vec2d>(0, k);
    const double power = scale * (c[0] * c[0] + c[1] * c[1]);
    const double w = 2.0 * std::numbers::pi * f / kFilterRateHz;
    // |1 + z⁻¹|⁴ |1 - z⁻²|² |1 - z⁻¹|⁴ in the forms that keep their precision near 0 and π.
    const double s = std::sin(0.5 * w), c_half = std::cos(0.5 * w), s2 = std::sin(w);
    const double zeros =
        std::pow(4.0 * c_half * c_half, 2) * (4.0 * s2 * s2) * std::pow(4.0 * s * s, 2);
    const double cos1 = std::cos(w), cos2 = std::cos(2.0 * w);
    for (std::size_t b = 0; b < kBandFilters.size(); ++b) {
      const BandFilter& filter = kBandFilters[b];
      double poles = 1.0;
      for (const auto& [d1, d2] : filter.d) {
        const double a1 = -2.0 - d1, a2 = 1.0 - d2;
        poles *= 1.0 + a1 * a1 + a2 * a2 + 2.0 * a1 * (1.0 + a2) * cos1 + 2.0 * a2 * cos2;
      }
      mean_square[b] += power * filter.gain * filter.gain * zeros / poles;
    }
  }
  for (std::size_t b = 0; b < levels.size(); ++b) {
    if (mean_square[b] > 0.0) {
      levels[b] = std::max(kEmptyBandDb, full_scale_db_spl + 10.0 * std::log10(mean_square[b]));
    }
  }
  return levels;
}

SpecificLoudness StationaryLoudness(const std::array<double, kLoudnessBands>& levels_db_spl) {
  const std::array<double, 21> core = CoreLoudness(levels_db_spl);
  SpecificLoudness out;
  // Walk up the critical-band rate. Within each band the pattern is the band's core loudness,
  // unless the slope coming down from a louder band below is still above it: then it is that
  // slope, whose steepness depends on the loudness range it passes through and on the band.
  double n1 = 0.0, z1 = 0.0;
  std::size_t range = 0;
  std::size_t next = 0;  // next 0.1 Bark point to fill: z = 0.1 · (next + 1)
  const auto fill_to = [&](double z2, auto value_at) {
    // A point belongs to the segment that reaches it (the band tops carry +1e-4 Bark, as in the
    // standard, so a top lying on the grid is filled by its own band).
    while (next < out.sone_per_bark.size() &&
           kBarkStep * static_cast<double>(next + 1) <= z2 + 1e-9) {
      out.sone_per_bark[next] = value_at(kBarkStep * static_cast<double>(next + 1));
      ++next;
    }
  };
  for (std::size_t i = 0; i < core.size(); ++i) {
    const double top = kBandTopBark[i] + 1e-4;
    const std::size_t column = std::min<std::size_t>(i == 0 ? 0 : i - 1, 7);
    bool band_done = false;
    while (!band_done) {
      double n2 = 0.0, z2 = 0.0;
      if (n1 > core[i]) {
        // The slope from below, down to the end of its range or to the core loudness.
        const double steepness = kSlopeSteepness[range][column];
        n2 = std::max(kSlopeRangeSone[range], core[i]);
        z2 = z1 + (n1 - n2) / steepness;
        if (z2 > top) {
          band_done = true;
          z2 = top;
          n2 = n1 - (z2 - z1) * steepness;
        }
        out.total_sone += (z2 - z1) * (n1 + n2) / 2.0;
        const double from_n = n1, from_z = z1;
        fill_to(z2, [&](double z) { return from_n - (z - from_z) * steepness; });
      } else {
        // The band's own core loudness, flat to its top.
        if (n1 < core[i]) range = SlopeRange(core[i]);
        band_done = true;
        z2 = top;
        n2 = core[i];
        out.total_sone += n2 * (z2 - z1);
        fill_to(z2, [&](double) { return n2; });
      }
      while (range + 1 < kSlopeRangeSone.size() && n2 <= kSlopeRangeSone[range]) ++range;
      z1 = z2;
      n1 = n2;
    }
  }
  out.total_sone = std::max(out.total_sone, 0.0);
  for (double& n : out.sone_per_bark) n = std::max(n, 0.0);
  return out;
}

double LoudnessLevelPhon(double sone) {
  if (sone >= 1.0) return 40.0 + 33.22 * std::log10(sone);
  return 40.0 * std::pow(std::max(sone, 0.0) + 0.0005, 0.35);
}

double SharpnessAcum(const SpecificLoudness& loudness) {
  double weighted = 0.0, total = 0.0;
  for (std::size_t i = 0; i < loudness.sone_per_bark.size(); ++i) {
    const double z = kBarkStep * static_cast<double>(i + 1);
    const double g = z <= 15.8 ? 1.0 : 0.15 * std::exp(0.42 * (z - 15.8)) + 0.85;
    weighted += loudness.sone_per_bark[i] * g * z * kBarkStep;
    total += loudness.sone_per_bark[i] * kBarkStep;
  }
  return total > 0.0 ? 0.11 * weighted / total : 0.0;
}

double Sharpness(std::span<const float> x, double fs_hz, double full_scale_db_spl) {
  return SharpnessAcum(StationaryLoudness(ThirdOctaveLevelsDbSpl(x, fs_hz, full_scale_db_spl)));
}

double LoudnessSone(std::span<const float> x, double fs_hz, double full_scale_db_spl) {
  return StationaryLoudness(ThirdOctaveLevelsDbSpl(x, fs_hz, full_scale_db_spl)).total_sone;
}

}  // namespace sas::kiosk
