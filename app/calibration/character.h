#pragma once
// Figures that give a texture's character numbers, so that "gritty", "tonal" or "clicky" can be
// checked: spectral flatness (noise-like or tonal), crest factor (smooth or impulsive) and onset
// rate (how many distinct events a second). Offline only (measurement tools and tests).

#include <span>

namespace sas::kiosk {

// Spectral flatness (Wiener entropy) of `x` between lo_hz and hi_hz: the geometric mean of the
// power spectral density over its arithmetic mean, 1 for white noise, near 0 for a few tones.
// The PSD is Welch's average of Hann-windowed segments of 4096 samples with half overlap
// (OpenCV's DFT); a signal shorter than one segment is taken as one zero-padded segment.
// 0 for silence.
double SpectralFlatness(std::span<const float> x, double fs_hz, double lo_hz = 100.0,
                        double hi_hz = 10000.0);

// Peak over RMS of `x` in dB (0 for silence).
double CrestFactorDb(std::span<const float> x);

// Onsets per second: 5 ms frames (RMS); a frame is an onset when it is at least
// kOnsetRiseDb over the quietest of the 30 ms before it and over kOnsetFloorDb below the
// signal's loudest frame, at least 20 ms after the last onset (so one click's ring is one onset).
inline constexpr double kOnsetRiseDb = 6.0;
inline constexpr double kOnsetFloorDb = 40.0;
double OnsetRatePerS(std::span<const float> x, double fs_hz);

}  // namespace sas::kiosk
