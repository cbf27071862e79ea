#pragma once
// Loudness and sharpness of a stationary sound, for judging whether a stroke sounds brighter, not
// only whether its power moved: a resonator with a few strong low modes keeps the power centroid
// on them while the energy above 2 kHz rises, and listeners hear that rise.
//
// Chain: the signal's Hann-windowed power spectrum (OpenCV's DFT), weighted by the power response
// of each of ISO 532-1's 28 third-octave filters (25 Hz .. 12.5 kHz, the standard's sixth-order
// filters tabulated for 48 kHz and read at each frequency's angle at that rate) and summed: on a
// stationary signal that is what filtering, squaring and averaging give, at a fraction of the
// cost -> band levels in dB SPL at an assumed speaker calibration -> ISO 532-1:2017 section 5
// (Zwicker's method, stationary, free field): low-frequency weighting by the equal-loudness
// contours, the first three critical bands from groups of third octaves, the ear's transmission,
// core loudness per critical band, upper slopes that spread each band's loudness towards higher
// bands -> specific loudness N'(z) at 0.1 Bark steps and total loudness N (sone) -> DIN 45692:2009
// sharpness S = 0.11 · Σ N'(z) g(z) z Δz / Σ N'(z) Δz (acum), g(z) = 1 up to 15.8 Bark and
// 0.15 · e^{0.42 (z − 15.8)} + 0.85 above.
//
// The tables are the standard's (ISO 532-1:2017 annex A; the same values as Zwicker, Fastl,
// Widmann, Kurakata, Kuwano & Namba, "Program for calculating loudness according to DIN 45631
// (ISO 532B)", J. Acoust. Soc. Jpn. (E) 12, 1991). Offline only (measurement tools and tests).

#include <array>
#include <span>

namespace sas::kiosk {

// The kiosk's speaker calibration assumed for every loudness and sharpness figure: a signal of
// RMS 1.0 at the speaker's input (full scale) plays at 94 dB SPL (1 Pa) at the visitor's head.
// Why: the textures are calibrated to a mean stroke of -36 LUFS at their own gains and the kiosk
// adds +12 dB (KioskConfig::sound_gain_db), so a typical stroke reaches the speaker near -24 dB
// re full scale and plays at about 70 dB SPL, clearly over a gallery's 45-55 dB(A) background
// and well under 80 dB(A); the -1 dBTP ceiling then caps peaks at 93 dB SPL. Sharpness depends
// only weakly on level (Zwicker & Fastl, Psychoacoustics, 3rd ed., section 9.2), so a few dB
// either way hardly change it.
inline constexpr double kFullScaleDbSpl = 94.0;

inline constexpr int kLoudnessBands = 28;  // third octaves 25 Hz .. 12.5 kHz
inline constexpr int kBarkSteps = 240;     // N'(z) at z = 0.1, 0.2, ..., 24.0 Bark

// Centre of third-octave band `band` (0 = 25 Hz, 16 = 1 kHz, 27 = 12.5 kHz): 1000 · 10^((b-16)/10).
double LoudnessBandCentreHz(int band);

// Band levels (dB SPL) of `x` (full scale 1.0 = RMS at full_scale_db_spl). A band without energy
// reads -100 dB SPL (far below every threshold of the method).
std::array<double, kLoudnessBands> ThirdOctaveLevelsDbSpl(std::span<const float> x, double fs_hz,
                                                          double full_scale_db_spl);

struct SpecificLoudness {
  double total_sone = 0.0;  // N, the slopes' integral as ISO 532-1 computes it
  std::array<double, kBarkSteps> sone_per_bark{};  // N'(z), z = 0.1 · (i + 1) Bark
};

// ISO 532-1 stationary loudness (free field) from the 28 band levels (dB SPL). Levels of the
// lowest 11 bands above 120 dB are outside the method's tables; they are taken as 120 dB.
SpecificLoudness StationaryLoudness(const std::array<double, kLoudnessBands>& levels_db_spl);

// ISO 532-1 loudness level (phon) of a loudness in sone: 40 + 33.22 log10 N from 1 sone, and
// 40 (N + 0.0005)^0.35 below.
double LoudnessLevelPhon(double sone);

// DIN 45692 sharpness (acum) of a specific loudness; 0 where there is no loudness.
double SharpnessAcum(const SpecificLoudness& loudness);

// The whole chain on a signal: its sharpness (acum) and its loudness (sone).
double Sharpness(std::span<const float> x, double fs_hz, double full_scale_db_spl);
double LoudnessSone(std::span<const float> x, double fs_hz, double full_scale_db_spl);

}  // namespace sas::kiosk
