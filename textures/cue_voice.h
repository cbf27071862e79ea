#pragma once
// The kiosk's spoken cues, from sentence to loudness-normalised 48 kHz mono clip, shared by
// cue_maker (the build and the regenerate step) and voice_survey (docs/voices.md):
//   CueSentences     which cues a language has and what each says (string table + texture.toml)
//   engines          espeak-ng (a program, optionally with an MBROLA voice), SVOX Pico (its
//                    library opened at run time from a folder unpacked by fetch_engines.sh: it is
//                    non-free, so the build never links or needs it) and any other program
//   ShapeCue         trim silence, normalise loudness (BS.1770) under a peak ceiling, fade
//   committed renders textures/voices/<lang>/<key>.opus + <key>.txt (the sentence it speaks):
//                    the build uses one only while its sentence equals the string table's
// Offline only (build and measurement tools); errors are exceptions.

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "files/strings.h"
#include "surface/cue_library.h"

namespace sas::cues {

inline constexpr double kCueRateHz = 48000.0;
// Every cue is levelled as staff recordings are (surface/cue_library.h: ShapeCue and its
// constants), so both are heard at one level.
using surface::kCueLoudnessLufs;
using surface::kCuePeakDbfs;

struct CueSentence {
  std::string key;  // file name without extension
  std::string text;
};

// The texture folders of `textures_dir` (those with a texture.toml), sorted.
std::vector<std::string> TextureFolders(const std::string& textures_dir);
// Every cue of `table`: <folder>_name and _description of each texture folder (the table's
// [textures], else the texture.toml's English name and description), then each CueKeys() message.
std::vector<CueSentence> CueSentences(const kiosk::LanguageTable& table,
                                      const std::string& textures_dir);

// Runs `args` (args[0] is the program's path) with `extra_env` ("NAME=value") added to this
// process's environment; its standard output goes to `stdout_path` when given. Throws when it
// cannot start or does not exit 0.
void RunProgram(const std::vector<std::string>& args, const std::vector<std::string>& extra_env = {},
                const std::string& stdout_path = {});

// A mono clip at its engine's own rate.
struct Speech {
  std::vector<float> samples;
  double rate_hz = 0.0;
};

// espeak-ng -v voice -s wpm. `data_path` (optional) is passed as --path: a folder holding an
// espeak-ng-data with mbrola/<voice> files for "mb-xx" voices; `bin_path` is put first in PATH so
// espeak-ng finds the mbrola program.
Speech SpeakEspeak(const std::string& espeak, const std::string& voice, int wpm,
                   const std::string& text, const std::string& scratch_wav,
                   const std::string& data_path = {}, const std::string& bin_path = {});

// SVOX Pico through libttspico from `root` (a folder with usr/lib/<arch>/libttspico.so.0 and
// usr/share/pico/lang/, as fetch_engines.sh unpacks the Debian packages). 16 kHz.
class PicoSpeaker {
 public:
  explicit PicoSpeaker(const std::string& root);
  ~PicoSpeaker();
  PicoSpeaker(const PicoSpeaker&) = delete;
  PicoSpeaker& operator=(const PicoSpeaker&) = delete;
  // `voice` is Pico's language: en-GB, en-US, de-DE, fr-FR, it-IT, es-ES.
  // `rate_percent`: Pico's own speed markup (100: the voice's natural rate).
  Speech Speak(const std::string& voice, const std::string& text, int rate_percent = 100);

 private:
  struct Api;
  void Load(const std::string& voice);
  void Unload();
  std::unique_ptr<Api> api_;
  std::string lang_dir_;
  std::string voice_;  // loaded, "" for none
};

// The engine's clip made into a cue: resampled to 48 kHz, leading and trailing silence (below
// -40 dB re the peak) trimmed to 20 ms, loudness-normalised to kCueLoudnessLufs and lowered
// further if needed so the sample peak stays at or below kCuePeakDbfs, 5 ms raised-cosine fades.
std::vector<float> ShapeCue(const Speech& speech);

// Where a cue's committed render would be, and whether the build may use it.
struct RenderChoice {
  bool use_render = false;
  std::string audio_path;  // <renders>/<lang>/<key>.opus
  std::string why;         // when not used: "no render" or "sentence changed"
};
RenderChoice ChooseRender(const std::string& renders_dir, const std::string& language,
                          const std::string& key, const std::string& text);

// A committed render: Ogg Opus (libsndfile) at the engine's rate, bit rate kRenderBitrate.
inline constexpr int kRenderBitrate = 24000;
void WriteRender(const std::string& audio_path, const Speech& speech);
Speech ReadRender(const std::string& audio_path);

// textures/voices/choice.toml: [pico] <language> = "<Pico voice>" for each language whose
// committed renders SVOX Pico speaks.
std::map<std::string, std::string> LoadPicoChoice(const std::string& path);
// choice.toml's [rate_percent]: cue key -> speaking rate in percent (a key not listed: 100).
std::map<std::string, int> LoadPicoRates(const std::string& path);

// The whole file as a string, its trailing newlines removed.
std::string ReadText(const std::string& path);
void WriteText(const std::string& path, const std::string& text);

}  // namespace sas::cues
