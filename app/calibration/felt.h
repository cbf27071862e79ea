#pragma once
// The vibration as the hand gets it: levels in the skin's units and the figures that say whether
// a texture's feel survives the transducer path (envelope kept under the ceiling, energy in the
// skin's band) and differs from the other textures'. Offline only (measurement tools and tests).
//
// Skin weighting: channel 2 drives the transducer, whose acceleration at the pen follows it (the
// transducer profile compensates the actuator). The glabrous hand's detection threshold, in
// displacement, is flat up to ~40 Hz, falls 12 dB per octave to its minimum near 250 Hz and rises
// again above (Verrillo, JASA 35, 1963, thenar eminence, contactors >= 2.9 cm²; the Pacinian
// channel of Bolanowski, Gescheider, Verrillo & Checkosky, JASA 84, 1988). In acceleration
// (displacement × ω²) that threshold is flat from 40 to 250 Hz, rises 12 dB per octave below
// 40 Hz and, taking the rise above 250 Hz as 12 dB per octave in displacement (those papers'
// points reach ~10 dB over the minimum near 500 Hz), 24 dB per octave above. The weighting is its
// inverse: a 2nd-order Butterworth high-pass at 40 Hz and a 4th-order Butterworth low-pass at
// 250 Hz, unity in between. A skin-weighted level is the RMS of the weighted signal in dB re full
// scale: as LUFS are to the ear, a level at which equal numbers feel about equally strong.

#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace sas::kiosk {

inline constexpr double kSkinLowHz = 40.0;
inline constexpr double kSkinHighHz = 250.0;

// The skin-weighted signal of every `stride`-th sample of `x` starting at x[0] (stride 2 on
// interleaved stereo from x.subspan(1): channel 2), run from silence over the whole span.
std::vector<float> SkinWeighted(std::span<const float> x, double fs_hz, std::size_t stride = 1);

// The skin weighting's gain at `hz` (linear), for the tests and the documents.
double SkinWeightingGain(double hz, double fs_hz);

// Classifier features of one stroke's vibration, level-free: the energy of five bands of the
// skin's range (40-63-100-160-250-400 Hz) in dB relative to their sum, the crest factor (dB), the
// spread of the 10 ms envelope (standard deviation in dB of the frames within 40 dB of the
// loudest), the onsets per second (character.h), the signal's kurtosis (log10: impulsive or
// noise-like), the spectral flatness over 40-400 Hz (tonal or noise-like), the envelope's range
// (90th minus 10th percentile of the 10 ms frames, dB) and its periodicity (the largest
// normalised autocorrelation of the 10 ms envelope at lags of 30-300 ms: bumps or grain lines
// passing at a steady pace), the share of 10 ms frames more than 20 dB under the 90th
// percentile frame (a smooth surface between its events), and the spectrum's peak and centroid
// over 40-400 Hz (log2 Hz).
inline constexpr int kFeltFeatures = 15;
using FeltFeatures = std::array<double, kFeltFeatures>;

struct FeltFigures {
  double skin_db = -300.0;        // skin-weighted RMS, dB re full scale
  double rms_db = -300.0;         // plain RMS
  double peak = 0.0;              // largest |sample|
  double crest_db = 0.0;          // peak over plain RMS, dB
  double near_ceiling = 0.0;      // fraction of samples within 1 dB of the ceiling
  double band_fraction = 0.0;     // fraction of the energy between 40 and 400 Hz
  double above_1k_db = -300.0;    // energy above 1 kHz relative to the total, dB
  FeltFeatures features{};
};

// The figures of a stroke's channel 2 `x` (mono, the samples the transducer gets) for a
// transducer ceiling `ceiling` (linear). Band energies from the stroke's whole periodogram
// (rectangular window: Parseval exact, the landing counted as the stroke's start).
FeltFigures MeasureFelt(std::span<const float> x, double fs_hz, double ceiling);

// A nearest-centroid classifier on standardised features (each feature's mean and standard
// deviation over the training set): one centroid per label. Deliberately simple, so that what
// tells the textures apart is the vibration, not the classifier.
class NearestCentroid {
 public:
  void Fit(const std::vector<FeltFeatures>& x, const std::vector<int>& label);
  int Predict(const FeltFeatures& x) const;

 private:
  FeltFeatures mean_{}, scale_{};
  std::vector<FeltFeatures> centroid_;
  std::vector<int> label_;
};

// k nearest neighbours on the same standardised features: the label most of the k training
// strokes nearest to x carry (a tie goes to the nearest of the tied labels). A texture's strokes
// form one cluster per style (a roll's vibration is not a rub's), which one centroid per texture
// averages away; the neighbours keep them.
class NearestNeighbours {
 public:
  explicit NearestNeighbours(int k = 5) : k_(k) {}
  void Fit(const std::vector<FeltFeatures>& x, const std::vector<int>& label);
  int Predict(const FeltFeatures& x) const;

 private:
  int k_;
  FeltFeatures mean_{}, scale_{};
  std::vector<FeltFeatures> z_;
  std::vector<int> label_;
};

}  // namespace sas::kiosk
