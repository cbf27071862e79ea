#pragma once
// The kiosk's languages and spoken cues, loaded once at start so playing one never touches the
// disk: the language tables (on-screen texts, strings.h) of the configured language and of the
// visitor's choices, each language's cue recordings (<cues>/<language>/, surface/cue_library.h;
// one the staff recorded replaces its synthetic cue: staff_cues.h), the recording's tone and the
// staff test signals. The control side asks which clip says a session action or a message in the
// current language; the clips' samples go to the audio side (the player) once, in clip order. A
// missing table or cue is logged and stays silent.

#include <map>
#include <string>
#include <vector>

#include "files/kiosk_config.h"
#include "files/strings.h"
#include "kiosk/session.h"
#include "player/player.h"

namespace sas::kiosk {

// A spoken cue as it was handed to the audio side (tests, the journal): the language, the cue's
// key ("wooden_board_name", "count_3") and the sentence its file holds (cue_maker's .txt next to
// it; "" when absent; a staff recording's own .txt, else the table's sentence).
struct CueEvent {
  std::int64_t time_ns = 0;
  std::string language;
  std::string key;
  std::string text;
};

// A clip to play (-1: none, its file is absent) and the cue key it says.
struct CuePick {
  int clip = -1;
  std::string key;
};

class SpokenCues {
 public:
  SpokenCues() = default;  // no languages: only to be assigned a loaded one
  // `cues_dir` "": no cue files (the test signals are still made). `spoken_cues` false: nobody
  // expects cues (no warning about missing ones). `texture_keys`: the loaded textures, in order.
  // `texture_dirs`: each texture's folder (or none): a curator's texture carries its own name
  // and description cues in <folder>/cues/<language>/<key>_name.wav (read as staff cues are, and
  // used unless <staff_dir>/cues has one for that key).
  SpokenCues(const KioskConfig& config, const std::string& strings_dir, std::string cues_dir,
             bool spoken_cues, std::vector<std::string> texture_keys,
             std::vector<std::string> texture_dirs = {});

  // The clips' samples for the player (moved out: call once).
  std::vector<player::PlayerClip> TakeClipSamples();

  // What a kSpeak session action says, a cue about `texture`, a message cue by key.
  CuePick ForAction(const SessionAction& action) const;
  CuePick ForCue(Cue cue, int texture) const;
  CuePick ForMessage(const std::string& key) const;
  int tone_clip() const { return tone_clip_; }
  int sweep_clip() const { return sweep_clip_; }
  // The sentence clip `clip` says ("" for the test signals or without cue_maker's .txt).
  const std::string& clip_text(int clip) const;

  // The next of the visitor languages; false (nothing changes) when fewer than two.
  bool NextLanguage();
  void ResetLanguage() { language_ = 0; }  // the configured language
  // The attract cycle (session.h): the configured language, then the other visitor languages when
  // the language key has at least two. One slot each: its invitation's length and `quiet_s`, and
  // kNoInvitationSlotS for a language without an invitation cue (its texts are still shown). A
  // cycle shorter than kMinAttractCycleS is stretched evenly to it, so a kiosk with one language
  // does not repeat itself every few seconds. `quiet_s` 0: no cycle (empty).
  static constexpr double kNoInvitationSlotS = 10.0;
  static constexpr double kMinAttractCycleS = 45.0;
  std::vector<double> AttractSlotsS(double quiet_s) const;
  // Slot `slot`'s language becomes the current one (screen texts and cues).
  void SetAttractLanguage(int slot);
  // Whether the attract cycle has more than the configured language.
  bool attract_cycles() const { return attract_languages_.size() > 1; }
  const LanguageTable& strings() const;

  const std::string& cues_dir() const { return cues_dir_; }
  int cues_loaded() const;
  // Of those, the ones staff recorded (staff_cues.h), which replaced synthetic ones.
  int staff_cues_loaded() const { return staff_cues_; }

 private:
  struct Clip {
    std::string name;
    std::string text;  // a cue's spoken sentence
  };
  struct LanguageAssets {  // one language's table and cue clips (-1: absent)
    LanguageTable table;
    std::vector<int> name_cues, description_cues;  // per texture
    std::map<std::string, int> message_cues;       // per CueKeys()
    double invitation_s = 0.0;                     // its invitation cue's length (0: none)
  };

  int AddClip(std::string name, std::vector<float> mono, int channel);
  void LoadLanguages(const KioskConfig& config, const std::string& strings_dir);
  void LoadCues(const KioskConfig& config, bool spoken_cues);

  std::string cues_dir_;
  std::vector<std::string> texture_keys_;
  std::vector<std::string> texture_dirs_;
  std::vector<Clip> clips_;
  std::vector<player::PlayerClip> clip_samples_;
  std::vector<LanguageAssets> languages_;  // [0]: the configured language
  std::vector<int> visitor_languages_;     // indices into languages_ the language key steps through
  std::vector<int> attract_languages_;     // indices into languages_ the attract cycle shows
  int language_ = 0;
  int tone_clip_ = -1, sweep_clip_ = -1, record_tone_clip_ = -1;
  int staff_cues_ = 0;
};

}  // namespace sas::kiosk
