#pragma once
// The kiosk's spoken cues (for visitors who cannot see the screen), loaded into RAM once
// at start so playing one never touches the disk. The files are made at build time by
// textures/cue_maker (espeak-ng speech, 48 kHz mono, loudness-normalised) into <build>/textures/
// cues/<language>/ and installed to share/sketch-a-scratch/cues/<language>/:
//   <texture folder>_name.wav, <texture folder>_description.wav   one pair per texture
//   one <message>.wav per MessageCueNames() (the count, the invitation, the recording messages)
// A missing or unreadable cue is not fatal: it is listed in problems() (for the journal and the
// staff panel) and Find() returns nullptr for it, so the kiosk simply stays silent there.
// Set-up only.

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "surface/audio_file.h"

namespace sas::surface {

// cue_maker writes every cue with its peak at or below -1 dBFS. A float WAV can hold any value
// (1e30 decodes fine and the reader clips it to full scale): a cue with more than a stray sample
// at full scale is a damaged file and would play as a full-scale square wave. Returns why `clip`
// is no cue, or "" when it may be one. A recording with more of its samples at full scale than
// kMaxCueClippedFraction is clipped audibly.
inline constexpr double kMaxCueClippedFraction = 0.001;
std::string CueLevelProblem(const AudioClip& clip);

// How every spoken cue is levelled, the synthetic ones (cue_maker) and those staff record
// (kiosk/staff_cues.h) alike, so all of them are heard at one level:
//   trim leading/trailing silence (below kCueTrimBelowPeakDb re the peak; a lone click, whose 10 ms
//   around it stay 12 dB under that, counts as silence), keep kCueMarginS
//   either side -> loudness-normalise to kCueLoudnessLufs (BS.1770 K-weighted, ungated,
//   surface/loudness.h), then lower further if needed so the peak stays at or below kCuePeakDbfs
//   (never clipped) -> kCueFadeS raised-cosine fades at both ends.
// EBU R 128's programme target: a cue sits at the level of broadcast speech; the exhibit's strokes
// at the kiosk's default gains are about -24 LUFS (calibration/texture_levels.h), so cues and
// textures are heard at a similar level.
inline constexpr double kCueLoudnessLufs = -23.0;
inline constexpr double kCuePeakDbfs = -1.0;
inline constexpr double kCueTrimBelowPeakDb = -40.0;
inline constexpr double kCueMarginS = 0.02;
inline constexpr double kCueFadeS = 0.005;

struct ShapedCue {
  std::vector<float> samples;
  double source_loudness_lufs = 0.0;  // of the trimmed input, before the gain
  double gain_db = 0.0;               // applied to it
};
// `x` at `rate_hz`, shaped as above. Throws std::runtime_error for silence (an all-zero input).
ShapedCue ShapeCue(std::vector<float> x, double rate_hz);

// The message cues' names (file name without .wav), in a fixed order.
const std::vector<std::string>& MessageCueNames();
// Every cue file name (with .wav) the kiosk expects for these texture folders.
std::vector<std::string> ExpectedCueFiles(const std::vector<std::string>& texture_folders);

class CueLibrary {
 public:
  // Loads every expected cue from `dir`, resampled to `sample_rate_hz`. Never throws.
  static CueLibrary Load(const std::string& dir, const std::vector<std::string>& texture_folders,
                         double sample_rate_hz = 48000.0);

  // Mono samples of cue `name` ("wooden_board_name", "too_quiet"), or nullptr when not loaded.
  const std::vector<float>* Find(const std::string& name) const;
  const std::vector<float>* TextureName(const std::string& folder) const;
  const std::vector<float>* TextureDescription(const std::string& folder) const;

  double sample_rate_hz() const { return sample_rate_hz_; }
  std::size_t size() const { return cues_.size(); }
  // One line per cue that could not be loaded: "<file>: <why>". Empty when all loaded.
  const std::vector<std::string>& problems() const { return problems_; }

 private:
  double sample_rate_hz_ = 48000.0;
  std::map<std::string, std::vector<float>> cues_;
  std::vector<std::string> problems_;
};

}  // namespace sas::surface
