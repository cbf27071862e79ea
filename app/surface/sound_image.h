#pragma once
// Sound -> image and sound/vibration -> profile (paper §3–§4).
//
// Sound -> image (paper figure 3): "the stacking of luminance-translated audio signals to produce
// rows of pixels". A recording of up to 5 s is cut into consecutive chunks of `samples_per_row`
// samples; each chunk becomes one row, its samples mapped to luminance 0.5 + 0.5 s / peak (silence
// is mid-grey; `level_quantile` can map a lower level than the peak to white, clipping above it).
// The paper's transformations:
//   row length (temporal expansion): `row_length_px` pixels show `samples_per_row` samples, so
//     expansion = row_length_px / samples_per_row (> 1 stretches time by interpolation, < 1
//     compresses it by averaging);
//   inversion: luminance -> 1 - luminance;
//   interlacing: as in interlaced video, even rows carry the first half of the recording in order
//     and odd rows the second half, so two moments of the sound lie side by side.
// The image then becomes a height field through image_surface.h with ReliefSource::kLuminance.
//
// Sound -> profile directly (paper §4): "the signals' buffer length is 1000 ms, ideally
// corresponding to a 1000-mm-long surface": time maps to distance at mm_per_s (default 1000), the
// profile sampled every pitch_mm. Shape kEnvelope follows the temporal envelope (paper §2:
// "translating the temporal envelope of a sound into spatially linear information"), silence
// flat; kWaveform keeps the waveform itself (offset so that its lowest point is 0).
//
// Vibration -> profile: a recorded vibration or scan as a sound file (kWaveform, as above) or as
// CSV, either one height per line (`height_mm`, spaced csv_pitch_mm) or `position_mm,height_mm`
// pairs with increasing positions. CSV heights are taken as true millimetres; lines starting with
// '#' and one non-numeric header line are skipped; errors name file:line.

#include <memory_resource>
#include <span>
#include <string>
#include <vector>

#include "surface/audio_file.h"
#include "surface/height_field.h"
#include "surface/image_loader.h"

namespace sas::surface {

struct SoundImageOptions {
  int samples_per_row = 4800;  // 100 ms per row at 48 kHz
  int row_length_px = 1920;    // image width
  int row_height_px = 1;       // each row repeated this many times (bands as in figure 3)
  bool invert = false;
  bool interlace = false;
  double max_duration_s = 5.0;  // longer recordings are cut (the kiosk records 5 s)
  double sample_rate_hz = 48000.0;
  // The |sample| level that maps to white and black: the level below which this share of the
  // active samples lie (the 10 ms blocks within 30 dB of the loudest: pauses and silence around
  // a take do not count). 1 is the peak (figure 3); below 1 the loudest samples clip and a peaky
  // sound (speech) fills the image instead of sitting near mid-grey.
  double level_quantile = 1.0;
};

// The speech of a take, for its picture: the silence before and after it cut (a visitor who
// starts late would otherwise leave most rows flat grey) and each pause inside it longer than
// `max_pause_s` shortened to that, its two ends kept. Speech is the 10 ms blocks within 30 dB of
// the loudest (as for `level_quantile`), with `margin_s` kept before the first and after the
// last. The result is the voice itself: it comes from `memory` (the kiosk: kept out of core
// dumps, zeroed when released). Empty when no block is active (silence). Throws
// std::invalid_argument for options out of range.
struct SpeechTrimOptions {
  double margin_s = 0.05;
  // 0.25 s is the usual shortest silent pause counted in speech research (Goldman-Eisler 1968):
  // the gaps inside words and between them keep their length, a longer wait is cut down to it.
  double max_pause_s = 0.25;
};
std::pmr::vector<float> TrimToSpeech(
    std::span<const float> samples, double sample_rate_hz, const SpeechTrimOptions& options = {},
    std::pmr::memory_resource* memory = std::pmr::get_default_resource());

// Throws std::invalid_argument for options out of range or an empty recording. The image's
// luminance comes from `memory`: a sound image is the recording itself, row by row, so the kiosk
// makes the visitor's in memory kept out of core dumps.
GrayImage SoundToImage(std::span<const float> samples, const SoundImageOptions& options = {},
                       std::pmr::memory_resource* memory = std::pmr::get_default_resource());

// The kiosk's voice path in one call: recording -> sound image -> height field, reading the
// image's luminance as height (ReliefSource::kLuminance, see image_surface.h) with `relief_mm` for
// white and the display's pixel pitch. Throws std::invalid_argument for an empty or silent clip
// (a silent recording would be a featureless plateau: the caller should ask the visitor again).
HeightField SoundToHeightField(const AudioClip& clip, const SoundImageOptions& options,
                               double relief_mm, double pixel_pitch_mm);
// The same from samples at options.sample_rate_hz, without a copy; every buffer on the way (the
// sound image, the heights, the summed-area table) comes from `memory`. Throws
// std::invalid_argument for an empty recording.
HeightField SoundToHeightField(std::span<const float> samples, const SoundImageOptions& options,
                               double relief_mm, double pixel_pitch_mm,
                               std::pmr::memory_resource* memory);

enum class ProfileShape { kEnvelope, kWaveform };

struct SoundProfileOptions {
  double mm_per_s = 1000.0;   // paper: 1000 ms buffer = 1000 mm surface
  double pitch_mm = 0.1;      // profile sample spacing
  double amplitude_mm = 0.5;  // height of the loudest point
  ProfileShape shape = ProfileShape::kEnvelope;
  double envelope_window_ms = 5.0;
  double max_length_mm = 20000.0;
};

// A field one row high. Throws std::invalid_argument for an empty clip or bad options.
HeightField SoundToProfile(const AudioClip& clip, const SoundProfileOptions& options = {});

struct VibrationOptions {
  SoundProfileOptions sound{.shape = ProfileShape::kWaveform};  // for WAV/FLAC/OGG scans
  double csv_pitch_mm = 0.1;  // spacing of single-column CSV data, and of the output profile
  std::size_t max_points = 10'000'000;
  AudioReadLimits audio_limits{};
};

// Reads a scan from .csv (any case) or from a sound file. Throws LoadError naming file[:line].
HeightField VibrationProfileFromFile(const std::string& path, const VibrationOptions& options = {});

// The CSV reader on text already in memory (`name` is used in messages).
HeightField VibrationProfileFromCsv(const std::string& text, const std::string& name,
                                    const VibrationOptions& options = {});

}  // namespace sas::surface
