#pragma once
// Spoken cues recorded by the museum's staff, which replace the synthetic (espeak-ng) ones per
// language and cue: <staff_dir>/cues/<language>/<cue key>.<wav|flac|ogg|opus|...> (kiosk.toml
// [paths] staff_dir; /etc/sketch-a-scratch on the box, outside the package's files, so upgrades
// and reinstalls keep them). Any file libsndfile reads (WAV, FLAC, Ogg Vorbis or Opus, ...; the
// extension is not looked at), at any rate, mono or more channels: mixed down to mono at the
// kiosk's rate (surface/audio_file.h, libsoxr), then checked and levelled exactly like the
// synthetic cues (surface::ShapeCue). A <cue key>.txt beside a
// recording holds the sentence it says (reported with each play, as cue_maker's .txt is).
//
// A file is refused, with one warning naming it and why, and the synthetic cue kept, when it is
// unreadable or no sound file, silent or too quiet to be speech, clipped, peaky enough that it
// would play well below the other cues, outside its kind's duration bounds (DurationLimitsFor),
// a second recording of one cue, or named after no cue key or language (a typo would otherwise
// silently do nothing). Set-up only (reads files, allocates).

#include <map>
#include <string>
#include <vector>

#include "platform/log/log.h"

namespace sas::kiosk {

// The staff folder's subfolder holding the recorded cues.
inline constexpr const char* kStaffCuesFolder = "cues";

// How long a cue of a kind may be once the silence at either end is trimmed, and why.
struct CueDurationLimits {
  double min_s = 0.0;
  double max_s = 0.0;
  const char* why = "";
};
CueDurationLimits DurationLimitsFor(const std::string& key);

struct StaffCue {
  std::string path;
  std::vector<float> samples;  // mono at the kiosk's rate, levelled like the synthetic cues
  std::string text;            // the first line of <key>.txt beside it; "" when absent
};

// language code -> cue key -> recording.
using StaffCueMap = std::map<std::string, std::map<std::string, StaffCue>>;

// Reads `cues_dir` (<staff_dir>/cues; absent: no staff cues, one info line says so). `languages`: the
// kiosk's languages (a folder of another shipped language is reported and not read); `keys`:
// every cue key the kiosk speaks. Each refusal is a warning on `log` (component "cues"); each of
// `languages` gets one info line with its count of staff cues. Never throws.
StaffCueMap LoadStaffCues(const std::string& cues_dir, const std::vector<std::string>& languages,
                          const std::vector<std::string>& keys, double sample_rate_hz,
                          platform::Logger& log);

}  // namespace sas::kiosk
