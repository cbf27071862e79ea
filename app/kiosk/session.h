#pragma once
// The kiosk's Session state machine (DESIGN.md §1: app/kiosk, control thread). It owns what a
// visitor experiences over time — which surface is under the pen, the voice-recording flow,
// the idle reset with its attract screen, the staff panel — and nothing about devices: inputs are
// plain calls with a monotonic time in seconds, outputs are Actions the wiring carries out (play
// a cue, start the recorder, cross-fade, un-pop the bubbles...). Pure logic, so every rule below
// is tested without hardware.
//
// Rules (issue 7; paper §5.2 for what visitors did):
// - Tokens choose one of the textures; switching cross-fades and speaks the texture's name.
// - Record button: a press starts a countdown, then up to `record_max_s` of recording. Pressing
//   again during the countdown, or holding the button for `long_hold_s`, cancels the recording and
//   speaks the texture's longer description instead (layered information for visitors who cannot
//   see the screen). A good recording becomes the surface at once; a silent or clipped one gives a
//   friendly message and the previous surface stays.
// - After `idle_timeout_s` without pen, token or button activity: back to the default texture,
//   bubbles un-popped, voice wiped, attract screen. Any touch leaves attract at once.

#include <cstdint>
#include <string>
#include <vector>

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
    kStaffPanel,  // open (`open` = true) or close the staff panel
  };
  Kind kind;
  SurfaceChoice surface{};
  Cue cue = Cue::kTextureName;
  bool open = false;
};

struct SessionConfig {
  int texture_count = 4;
  int default_texture = 0;
  double idle_timeout_s = 60.0;
  double countdown_s = 3.0;
  double record_max_s = 5.0;
  double long_hold_s = 1.2;
};

// Anonymous usage counters shown on the staff panel (and persisted by the wiring).
// Counts stop at the largest TOML integer (2^63 - 1) instead of wrapping to zero, so the file
// stays valid TOML and a count never goes down.
inline constexpr std::uint64_t kMaxUsageCount = 0x7fffffffffffffffULL;
inline void CountOne(std::uint64_t& count) {
  if (count < kMaxUsageCount) ++count;
}

struct UsageCounters {
  std::vector<std::uint64_t> strokes_per_texture;  // pen-down strokes on each texture
  std::uint64_t voice_strokes = 0;
  std::uint64_t recordings = 0;  // good recordings that became a surface
  std::uint64_t failed_recordings = 0;
  std::uint64_t sessions = 0;  // visits: first activity after the attract screen

  bool operator==(const UsageCounters&) const = default;
};

class Session {
 public:
  explicit Session(const SessionConfig& config);

  // Inputs. `now_s` is monotonic and never decreases between calls.
  void OnPen(double now_s, bool tip_down);
  void OnTokenSelection(double now_s, int texture);  // -1: no token (default texture)
  void OnRecordButton(double now_s, bool pressed);
  void OnRecordingFinished(double now_s, RecordingOutcome outcome);
  void OnStaffChord(double now_s);
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
  // Restores persisted counters (sized to the texture count).
  void RestoreCounters(const UsageCounters& counters);

 private:
  void Activity(double now_s);
  void Show(SurfaceChoice surface, bool speak_name);
  void Emit(SessionAction::Kind kind);
  void Speak(Cue cue, int texture);
  void CancelRecordingFlow(bool speak_description);
  int ClampTexture(int texture) const;

  SessionConfig config_;
  SessionMode mode_ = SessionMode::kAttract;
  SurfaceChoice surface_{};
  int token_texture_ = -1;
  bool has_voice_ = false;
  bool staff_panel_open_ = false;
  bool tip_down_ = false;
  bool button_down_ = false;
  bool hold_handled_ = false;
  double button_down_since_s_ = 0.0;
  double last_activity_s_ = 0.0;
  double phase_started_s_ = 0.0;
  UsageCounters counters_;
  std::vector<SessionAction> actions_;
};

}  // namespace sas::kiosk
