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

#include <map>
#include <string>
#include <vector>

#include "surface/audio_file.h"

namespace sas::surface {

// cue_maker writes every cue with its peak at or below -1 dBFS. A float WAV can hold any value
// (1e30 decodes fine and the reader clips it to full scale): a cue with more than a stray sample
// at full scale is a damaged file and would play as a full-scale square wave. Returns why `clip`
// is no cue, or "" when it may be one.
std::string CueLevelProblem(const AudioClip& clip);

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
