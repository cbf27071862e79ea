#pragma once
// The kiosk's Session state machine (app/kiosk, control thread). It owns what a
// visitor experiences over time — which surface is under the pen, the voice-recording flow,
// the idle reset with its attract screen, the staff panel — and nothing about devices: inputs are
// plain calls with a monotonic time in seconds, outputs are Actions the wiring carries out (play
// a cue, start the recorder, cross-fade, un-pop the bubbles...). Pure logic, so every rule below
// is tested without hardware.
//
// Rules (paper §5.2 for what visitors did):
// - Tokens choose one of the textures; switching cross-fades and speaks the texture's name.
// - Record button: a press starts a countdown — "speak after the tone", then the count spoken
//   (three, two, one, a second apart, or closer when the countdown is short) and the tone —
//   then up to `record_max_s` of recording. Pressing
//   again during the countdown, or holding the button for `long_hold_s`, cancels the recording and
//   speaks the texture's longer description instead (layered information for visitors who cannot
//   see the screen). A good recording becomes the surface at once; a silent or clipped one gives a
//   friendly message and the previous surface stays.
// - Layered spoken information without sight: the name when a token is placed; the description
//   when the pen rests still on the surface (OnPenRest: the engine watches the pen), found by a
//   visitor who simply stops moving, and told in the spoken invitation.
// - While idle (attract), the attract cycle: each attract language in turn has a slot of
//   `attract_slots_s[i]` seconds, starting with its texts on the screen and its spoken invitation
//   (kAttractLanguage, then the invitation), so every visitor language is shown and heard once a
//   cycle without anybody knowing a key. No slots: no spoken invitation, the configured language.
//   The cycle waits while the staff panel is open.
// - A visit's texture is named when the visit starts (its first touch or a token), not only when
//   the pen rests.
// - After `idle_timeout_s` without pen, token or button activity: bubbles un-popped, voice wiped,
//   attract screen, and the texture of the token still on a switch (the default texture when
//   none is): the picture must match the token a visitor sees. Any touch leaves attract at once;
//   a pen hovering over the attract screen does not (a mouse nudged by a passer-by is no visit).
// - A visit is counted at its first pen contact, not at a hover, a token or the kiosk's start:
//   the staff's visit count is people who scratched.
// - The staff panel closes itself `staff_panel_timeout_s` after the last staff action, so a panel
//   left open cannot hold off the idle reset for ever.

#include <cstdint>
#include <string>
#include <vector>

#include "files/counters_file.h"

namespace sas::kiosk {

enum class SessionMode : std::uint8_t { kAttract, kExploring, kCountdown, kRecording };

// What is under the pen.
struct SurfaceChoice {
  bool voice = false;  // the visitor's recording
  int texture = 0;     // index into the texture list when !voice

  bool operator==(const SurfaceChoice&) const = default;
};

enum class Cue : std::uint8_t {
  kTextureName,         // the texture's spoken name (texture index in `texture`)
  kTextureDescription,  // its longer one-sentence description
  kRecordCountdown,     // "speak after the tone" + countdown ticks
  kRecordingTooQuiet,   // friendly messages; the previous surface stays
  kRecordingTooLoud,
  kRecordingUnavailable,
  kVoiceReady,  // "now scratch your voice"
  kCount,       // the countdown's spoken number (`count`: 3, 2, 1)
  kRecordTone,  // the tone after which the visitor speaks (a beep, not speech)
  kInvitation,  // the attract screen's spoken invitation (what to do, and how to hear more)
};

enum class RecordingOutcome : std::uint8_t { kOk, kSilent, kClipped, kNoMicrophone };

struct SessionAction {
  enum class Kind : std::uint8_t {
    kShowSurface,      // cross-fade picture and sound to `surface`
    kSpeak,            // play `cue` (for `surface.texture` where it names a texture)
    kStartRecording,   // open the microphone into the preallocated buffer
    kStopRecording,    // stop and hand the take to the surface pipeline
    kCancelRecording,  // stop and drop the take (nothing is kept)
    kWipeVoice,        // erase the voice slot from memory
    kResetTextures,    // un-pop the bubbles, relax every deformation
    kEnterAttract,
    kLeaveAttract,
    kStaffPanel,       // open (`open` = true) or close the staff panel
    kAttractLanguage,  // the attract cycle's slot `count` begins: show and speak its language
  };
  Kind kind;
  SurfaceChoice surface{};
  Cue cue = Cue::kTextureName;
  bool open = false;
  int count = 0;  // kCount's number
};

struct SessionConfig {
  int texture_count = 4;
  int default_texture = 0;
  double idle_timeout_s = 60.0;
  double countdown_s = 3.0;   // the press to the start of the recording (intro, count, tone)
  double count_step_s = 1.0;  // between the spoken numbers (less when the countdown is short)
  double tone_s = 0.4;        // the tone before the recording starts
  double record_max_s = 5.0;
  double long_hold_s = 1.2;
  double staff_panel_timeout_s = 300.0;
  // The attract cycle: one slot per attract language, in order (empty: no spoken invitation).
  std::vector<double> attract_slots_s;
};

// The attract cycle's length (the sum of its slots).
double AttractCycleS(const SessionConfig& config);

class Session {
 public:
  explicit Session(const SessionConfig& config);

  // Inputs. `now_s` is monotonic and never decreases between calls.
  void OnPen(double now_s, bool tip_down);
  void OnTokenSelection(double now_s, int texture);  // -1: no token (default texture)
  void OnRecordButton(double now_s, bool pressed);
  void OnRecordingFinished(double now_s, RecordingOutcome outcome);
  void OnStaffChord(double now_s);
  // The pen has rested still on the surface long enough: the description is spoken.
  void OnPenRest(double now_s);
  // Any other visitor input (the language key): leaves attract and restarts the idle timer.
  void OnVisitorActivity(double now_s) { Activity(now_s); }
  // A button worked on the open staff panel: restarts the panel's own timeout.
  void OnStaffActivity(double now_s);
  void Tick(double now_s);

  // Outputs: actions since the last call, in order.
  std::vector<SessionAction> TakeActions();

  SessionMode mode() const { return mode_; }
  SurfaceChoice surface() const { return surface_; }
  bool staff_panel_open() const { return staff_panel_open_; }
  bool has_voice() const { return has_voice_; }
  // Seconds left in the countdown (kCountdown) or the recording (kRecording); 0 otherwise.
  double SecondsLeft(double now_s) const;
  const UsageCounters& counters() const { return counters_; }
  const SessionConfig& config() const { return config_; }
  // Restores persisted counters (sized to the texture count).
  void RestoreCounters(const UsageCounters& counters);

 private:
  void Activity(double now_s);
  void Show(SurfaceChoice surface, bool speak_name);
  void Emit(SessionAction::Kind kind);
  void Speak(Cue cue, int texture);
  void CancelRecordingFlow(bool speak_description);
  void CountDown(double now_s);
  void AttractCycle(double now_s);
  void NameTexture();
  int ClampTexture(int texture) const;

  SessionConfig config_;
  SessionMode mode_ = SessionMode::kAttract;
  SurfaceChoice surface_{};
  int token_texture_ = -1;
  bool has_voice_ = false;
  bool staff_panel_open_ = false;
  double staff_last_s_ = 0.0;
  bool visit_counted_ = false;  // this visit's first pen contact has been counted
  bool tip_down_ = false;
  bool button_down_ = false;
  bool hold_handled_ = false;
  double button_down_since_s_ = 0.0;
  double last_activity_s_ = 0.0;
  double phase_started_s_ = 0.0;
  int next_count_ = 0;        // countdown: the number to speak next (3..1), 0: the tone, -1: done
  double next_slot_s_ = 0.0;  // when the attract cycle's next slot begins
  int next_slot_ = 0;
  bool named_ = false;  // this visit has heard its texture's name
  UsageCounters counters_;
  std::vector<SessionAction> actions_;
};

}  // namespace sas::kiosk
