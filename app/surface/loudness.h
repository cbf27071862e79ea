#pragma once
// Level measures for matching what visitors hear and feel, used offline (texture calibration, the
// spoken cues, tests), never on the audio thread:
//   KWeightedLoudnessDb  ITU-R BS.1770-4 loudness of one channel over one window, ungated, in LUFS:
//                        K-weighting (a +4 dB high shelf above ~1.7 kHz modelling the head, then
//                        a ~38 Hz high-pass, the "RLB" curve) -> mean square -> -0.691 + 10 log10.
//                        Broadcasters normalise programmes with it so that switching channels does
//                        not jump in level, which is exactly our problem with four textures; it
//                        tracks perceived loudness of broadband sounds better than plain RMS and
//                        is far simpler than a full ISO 532 loudness model. Measured with
//                        libebur128, which designs the filters for any sample rate (at 48 kHz
//                        they equal BS.1770's coefficient table).
//   RmsDb                plain RMS in dB re full scale (the transducer channel's levels are the
//                        RMS of its skin-weighted signal: calibration/felt.h).
// Both measure [from, to) of the signal but run the filter from sample 0, so the window starts
// with settled filter state. Silence gives kSilenceDb. The loudness window is whole milliseconds
// long (libebur128's unit): it ends at `to` and starts within half a millisecond of `from`, a
// difference far below 0.01 dB on the strokes and cues measured here (docs/engineering.md).

#include <cstddef>
#include <span>
#include <vector>

namespace sas::surface {

inline constexpr double kSilenceDb = -200.0;

// Loudness of `samples[from, to)` (frame indices into a signal with `stride` interleaved channels;
// pass a pointer offset to pick the channel). `to` is clamped to the signal length; the sample
// rate is taken in whole hertz.
double KWeightedLoudnessDb(std::span<const float> samples, double sample_rate_hz, std::size_t from,
                           std::size_t to, std::size_t stride = 1);
// The loudness of each window [from, to) of one signal, filtering it once (the single-window
// form above filters from the start, so measuring n strokes of a long run that way costs n^2).
// Windows in any order, overlapping or not.
struct FrameWindow {
  std::size_t from = 0, to = 0;
};
std::vector<double> KWeightedLoudnessDb(std::span<const float> samples, double sample_rate_hz,
                                        std::span<const FrameWindow> windows,
                                        std::size_t stride = 1);
double RmsDb(std::span<const float> samples, std::size_t from, std::size_t to,
             std::size_t stride = 1);

}  // namespace sas::surface
