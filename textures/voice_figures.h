#pragma once
// Figures that compare speech engines on the kiosk's own sentences (voice_survey writes them to
// docs/voices.md). Everything but the sample rate is measured on the cue as the kiosk plays it
// (cues::ShapeCue) brought to 16 kHz, the lowest rate among the candidates, so no engine gains
// from a wider analysis band:
//   band edge     the highest frequency where the long-term spectrum (Welch, Hann 1024) of the
//                 engine's own output is within kBandEdgeDb of its maximum: what the voice
//                 carries of the consonants' high band (limited by the engine's rate)
//   speaking rate words of the sentence per minute of the trimmed cue
//   loudness, true peak  after normalisation (BS.1770; 4x oversampled peak, libebur128): a
//                 voice whose loudness stays under the target was held back by the peak ceiling
//   voicing, F0   normalised autocorrelation per 40 ms frame (10 ms hop), 60-400 Hz; the F0
//                 range (5th to 95th percentile of the voiced frames, semitones) says how much
//                 melody the voice has (a flat range sounds robotic)
//   HF flatness   spectral flatness 2-5 kHz (Hann 1024) averaged over voiced frames: near 0 for a
//                 pure line spectrum (a buzzy, strictly periodic source), higher where the voice
//                 has breath noise between its harmonics; ~0.56 for white noise
//   word error    (English) a recogniser's words against the sentence: edit distance / words
// Offline only.

#include <span>
#include <string>
#include <vector>

#include "cue_voice.h"

namespace sas::cues {

inline constexpr double kAnalysisRateHz = 16000.0;
inline constexpr double kBandEdgeDb = 50.0;

double BandEdgeHz(std::span<const float> x, double rate_hz);
// F0 per 10 ms frame in Hz, 0 where unvoiced (or quieter than 35 dB under the loudest frame).
std::vector<double> PitchTrack(std::span<const float> x, double rate_hz);
// Spectral flatness in [lo_hz, hi_hz] averaged over the frames `f0` calls voiced.
double VoicedFlatness(std::span<const float> x, double rate_hz, const std::vector<double>& f0,
                      double lo_hz = 2000.0, double hi_hz = 5000.0);
double TruePeakDbtp(std::span<const float> x, double rate_hz);
// Lower-case words, punctuation dropped (bytes of UTF-8 letters kept).
std::vector<std::string> Words(const std::string& text);
// Word-level edit distance (substitutions, insertions, deletions) between two word lists.
std::size_t WordEdits(const std::vector<std::string>& reference,
                      const std::vector<std::string>& heard);

struct VoiceFigures {
  double source_rate_hz = 0.0;
  double band_edge_hz = 0.0;
  double duration_s = 0.0;  // of the shaped cue
  double words = 0.0;
  double loudness_lufs = 0.0;
  double true_peak_dbtp = 0.0;
  double voiced_frames = 0.0, frames = 0.0;
  std::vector<double> f0_hz;  // voiced frames' F0
  double flatness_sum = 0.0;  // HF flatness x voiced frames (to pool over cues)
};

// Figures of one cue; `shaped_16k` receives the shaped cue at kAnalysisRateHz (for a recogniser).
VoiceFigures MeasureCue(const Speech& raw, const std::string& text,
                        std::vector<float>* shaped_16k = nullptr);

// Pooled over many cues of one candidate.
struct VoiceSummary {
  double source_rate_hz = 0.0;
  double band_edge_hz = 0.0;  // median over cues
  double duration_s = 0.0;    // sum
  double words_per_minute = 0.0;
  double loudness_min_lufs = 0.0, loudness_max_lufs = 0.0;
  double true_peak_max_dbtp = -200.0;
  double voiced_share = 0.0;
  double f0_median_hz = 0.0;
  double f0_range_st = 0.0;
  double hf_flatness = 0.0;
};
VoiceSummary Summarise(const std::vector<VoiceFigures>& cues);

}  // namespace sas::cues
