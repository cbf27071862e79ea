#pragma once
// The kiosk engine: everything a visit needs between the input devices and the output devices,
// shared by the live kiosk (app/live_kiosk.cpp: SDL window, PortAudio, pen, switches) and the
// headless default (app/headless_demo.cpp: a scripted visit through the offline audio loop), so
// the two never wire things twice.
//
// KioskEngine is the control side (every public method runs on the control thread):
//   pen reading (platform/pen/pen_reading.h: screen px, pressure, tilt, CLOCK_MONOTONIC time) ->
//   surface metres (the picture covers the screen: ResizeToCover's scale and crop) ->
//   synth::ProbeCommand (pen_mapping.h: pressure -> normal force and penetration, tilt -> width
//   and style; velocity from successive readings) -> player::PlayerControl (a message to the
//   audio side). Session (session.h) decides what is shown; its actions are carried out here
//   (scene switch, recorder, voice slot, bubble reset, cues) and handed on to the UI. The pen side
//   is kiosk_pen.cpp; the languages and spoken cues are SpokenCues (spoken_cues.h).
// The audio side is the player (player/player.h): audio() is what the audio device calls, the
// player's AudioPlayer, which renders, cross-fades, mixes cues and measures latency.
//
// A switch prepares a free scene slot of the player's pool here and sends its index; the next
// waits until the audio side has taken it (pending_surface_), so slot reuse never races the
// audio thread. Bubble pops flatten the field; the flattened field becomes the scene's surface
// through the same switch once the pen is lifted.
// Per-stroke loudness matching (stroke_gain.h): each pen sample updates the smoothed stroke
// (speed, pressure, style) and hands the texture's correction for it to the scene the pen plays
// (Scene::SetStrokeGains: ramped on the audio thread); a newly prepared scene starts at the
// correction for the last stroke.

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "files/kiosk_config.h"
#include "files/material_file.h"
#include "files/staff_settings.h"
#include "files/strings.h"
#include "kiosk/data_dirs.h"
#include "kiosk/exposure_meter.h"
#include "kiosk/gesture.h"
#include "kiosk/session.h"
#include "kiosk/spoken_cues.h"
#include "levels/stroke_gain.h"
#include "platform/audio/audio_output.h"
#include "platform/audio/voice_recorder.h"
#include "platform/device_status.h"
#include "platform/pen/pen_reading.h"
#include "player/player.h"
#include "surface/image_loader.h"
#include "surface/profile_slots.h"
#include "surface/sound_image.h"
#include "surface/texture_set.h"
#include "synth/scene.h"

namespace sas::kiosk {

struct EngineTexture {
  std::string key;  // folder name, e.g. "wooden_board" (config, counters, cue file names)
  surface::LoadedTexture loaded;
  Material material;
};

struct KioskEngineOptions {
  KioskConfig config;
  // texture.toml files, token order; empty: the configuration's tokens ([textures], staff
  // textures first: data_dirs.h ResolveTokenTextures), each with its fallback.
  std::vector<std::string> texture_paths;
  // Per texture_paths entry, the texture its token shows when that one does not load ("" or
  // missing: none, the token then shows the default texture).
  std::vector<std::string> texture_fallbacks;
  std::string materials_dir;               // searched first (render_command.h search order)
  std::string counters_path;               // empty: counters are not persisted
  std::string staff_settings_path;         // staff panel volume/vibration; empty: not persisted
  std::string cues_dir;                    // empty: FindCuesDir()
  std::string strings_dir;                 // the language tables; empty: FindStringsDir()
  bool spoken_cues = true;                 // false: no cue files loaded (level calibration)
  // false: the staff's recorded cues (<staff_dir>/cues) are not read, while their textures are
  // (the scripted headless visit: the same voice on every machine).
  bool staff_cues = true;
  int screen_width_px = 1920;              // the screen the pen coordinates refer to
  int screen_height_px = 1080;
  double cross_fade_s = 0.45;  // sound cross-fade on a switch (the picture fades alongside)
  // Before recording starts: "speak after the tone" (~1.5 s in every language), the count a second
  // apart and the tone.
  double countdown_s = 5.5;
  // While idle the engine strokes the picture itself (the paper's passive exploration). The live
  // kiosk sets it from [attract] passive_stroke; off for everything that renders a scripted visit.
  bool attract_stroke = false;
  bool virtual_clock = false;   // headless: audio time advances by rendered frames from 0
  int max_block_frames = 4096;  // largest block Render is called with (longer ones are split)
};

// Latency and load as measured by the audio side.
using EngineAudioStats = player::PlayerStats;

// The voice surface: a recording becomes a sound image (100 ms per row, rows as bands filling the
// 1080-pixel screen, paper figure 3) read as heights kVoiceReliefMm high, scratched with the
// kVoiceMaterial material and, without pen tilt, a kVoiceWidthMm wide scrape.
inline constexpr const char* kVoiceMaterial = "plastic";
inline constexpr double kVoiceReliefMm = 0.5;
inline constexpr double kVoiceWidthMm = 0.5;
// The sound-image options for a recording of `sample_count` samples at `rate_hz`, of which at
// most `max_duration_s` is used.
surface::SoundImageOptions VoiceImageOptions(double rate_hz, double max_duration_s,
                                             std::size_t sample_count);

class KioskEngine final {
 public:
  // Loads the textures, materials, counters and cues and prepares the default texture's scene.
  // A texture whose files cannot be loaded is left out (logged, listed by texture_failures());
  // throws only when none loads.
  explicit KioskEngine(KioskEngineOptions options);
  ~KioskEngine();
  KioskEngine(const KioskEngine&) = delete;
  KioskEngine& operator=(const KioskEngine&) = delete;

  // The audio thread's face, for the audio output: the player's Render (nothing else of the
  // engine runs there).
  platform::AudioRenderer& audio() { return audio_face_; }

  // A pen reading in screen pixels (pen, mouse, touch or a script); `style` forces a probe style
  // (the headless visit's roll strokes).
  void OnPen(const platform::PenReading& pen, std::optional<synth::ProbeStyle> style = {});
  // `token`: the switch (0..3, the texture_paths order) holding the token that counts, -1: none.
  void OnToken(std::int64_t now_ns, int token);
  void OnRecordButton(std::int64_t now_ns, bool pressed);
  void OnStaffChord(std::int64_t now_ns);
  // A staff panel button was worked (restarts the panel's own timeout).
  void OnStaffActivity(std::int64_t now_ns);
  // Timers, recording, bubble surface updates; returns the session's actions (already applied to
  // the audio side) for the UI: pictures, overlays, attract, staff panel.
  std::vector<SessionAction> Tick(std::int64_t now_ns);
  // The microphone's recorder, or null (no microphone: the record button says so).
  void SetRecorder(platform::VoiceRecorder* recorder) { recorder_ = recorder; }
  // Whether the microphone delivers sound (platform::AudioInput::Delivering, once per loop pass).
  // While it does not, the record button says there is no microphone; a recording in progress
  // ends as if there were none (its take is wiped: half a take is not a voice).
  void SetMicrophoneLive(std::int64_t now_ns, bool live);
  // False while no audio callback can run (device missing): pen strokes and cues are then not
  // queued (player.h), a switch waits until the device runs again. Call after each
  // AudioOutput::Poll.
  void SetAudioRunning(bool running);
  // Staff panel: a 1 kHz tone on the speaker (ch 1), a 40..400 Hz sweep on the transducer (ch 2).
  void PlayTestTone();
  void PlayTransducerSweep();
  bool SaveCounters(std::string* error) const;
  // The usage counts as the counters file holds them (counter_keys() order for the strokes):
  // this run's for the loaded textures, the file's for any left out.
  UsageCounters PersistedCounters() const;
  const std::vector<std::string>& counter_keys() const { return counter_keys_; }
  // The visitor's language key: the next of the configured visitor languages, whose own name is
  // spoken in it; on the attract screen, the language it is showing. False (nothing changes) when
  // fewer than two are configured. The idle reset returns to the configured language.
  bool NextLanguage(std::int64_t now_ns);
  // How many times the language key has chosen a language (the view's banner follows it).
  int language_choices() const { return language_choices_; }
  // While idle with attract_stroke: the virtual probe's position (screen px) and whether its tip is
  // on the picture now, for the view's dent.
  std::optional<platform::PenReading> passive_pen() const {
    return passive_down_ ? std::optional<platform::PenReading>(passive_pen_) : std::nullopt;
  }
  // True when nothing the kiosk plays on its own (the passive stroke and its ring-out, a cue) is
  // sounding: the room's level can be measured by the microphone then.
  bool AmbientListening() const;
  // Called with every cue handed to the audio side (control thread).
  void SetCueObserver(std::function<void(const CueEvent&)> observer) {
    cue_observer_ = std::move(observer);
  }
  // Staff's low-vibration mode (configuration gains.low_vibration_db): switches at once, ramped,
  // and is kept in the staff settings file.
  void SetLowVibration(bool on);
  bool low_vibration() const { return low_vibration_; }
  // Staff panel volume (speaker) and vibration (transducer) by `steps` of kStaffStepDb on top of
  // the configured gains: applied at once (20 ms ramp) and kept in the staff settings file.
  void StepVolume(int steps);
  void StepVibration(int steps);
  const StaffSettings& staff_settings() const { return staff_; }
  // Ambient-adaptive sound gain (ambient_gain.h), dB on top of the configured gains.
  void SetAmbientGainDb(double gain_db);
  double ambient_gain_db() const { return ambient_gain_db_; }
  // Where a failing counters save is reported (status "storage": one line when it starts failing,
  // one when it works again). Without a board every failure is a log line.
  void SetStatusBoard(platform::DeviceStatusBoard* board) { board_ = board; }

  // ---- views
  const Session& session() const { return session_; }
  const std::vector<EngineTexture>& textures() const { return textures_; }
  // "<key>: <why>" for each texture left out at start (empty when all four loaded).
  const std::vector<std::string>& texture_failures() const { return texture_failures_; }
  int default_texture() const { return default_texture_; }
  // The token (switch) that selects textures()[texture_index], -1 when none does.
  int TokenForTexture(std::size_t texture_index) const;
  SurfaceChoice surface() const { return session_.surface(); }
  bool has_voice() const { return voice_.occupied(kVoiceSlot); }
  // The voice recording as a grey sound image (null when the slot is empty).
  const surface::GrayImage* voice_image() const { return voice_image_ ? &*voice_image_ : nullptr; }
  // The field under the pen now, and where screen pixel (x, y) lands on it (field samples).
  std::shared_ptr<const surface::HeightField> current_field() const { return current_field_; }
  void ScreenToField(double x_px, double y_px, double* fx, double* fy) const;
  void FieldToScreen(double fx, double fy, double* x_px, double* y_px) const;
  const surface::BubbleWrapState* bubbles() const;
  int popped_bubbles() const;
  float mic_level() const { return recorder_ ? recorder_->Level() : 0.0f; }
  bool recorder_present() const { return recorder_ != nullptr && microphone_live_; }
  EngineAudioStats audio_stats() const;
  // The speaker's Leq over the last visit and the last hour (exposure_meter.h), updated by Tick.
  const ExposureMeter& exposure() const { return exposure_; }
  const KioskConfig& config() const { return options_.config; }
  const std::string& cues_dir() const { return cues_.cues_dir(); }
  int cues_loaded() const { return cues_.cues_loaded(); }
  int staff_cues_loaded() const { return cues_.staff_cues_loaded(); }
  // The current language's table (on-screen texts) and its code.
  const LanguageTable& strings() const { return cues_.strings(); }
  const std::string& language() const { return strings().code; }
  // A texture's name in the current language.
  std::string TextureName(int texture) const;
  // The probe style of the stroke the pen plays (or last played): a held barrel button rolls.
  synth::ProbeStyle stroke_style() const { return stroke_style_; }
  // The per-stroke correction last handed to the scene under the pen (dB).
  StrokeCorrection stroke_correction() const { return stroke_correction_; }
  const StrokeGainMap& stroke_gains() const { return stroke_gains_; }
  // Turns a voice take into the voice surface (headless run, tests: the same path as a
  // recording): its speech (surface::TrimToSpeech: the silence around it cut, long pauses
  // shortened) becomes the sound image and the height field. The samples are read in place; the
  // speech, the image and the field live in memory kept out of core dumps
  // (platform::NoDumpMemory()).
  RecordingOutcome AcceptRecording(std::int64_t now_ns, std::span<const float> samples);

 private:
  static constexpr int kVoiceSlot = 0;
  // The passive stroke's level below a visitor's stroke of the same speed and pressure.
  static constexpr double kPassiveGainDb = -10.0;

  // Hands the audio device's calls to the player's audio face.
  struct AudioFace final : platform::AudioRenderer {
    player::AudioPlayer* player = nullptr;
    void Render(float* interleaved, int frames, int channels) noexcept override {
      player->Render(interleaved, frames, channels);
    }
  };

  // The textures and their materials, the voice's material and the default texture; throws when
  // no texture loads.
  void LoadTextures();
  void ApplyActions(std::int64_t now_ns, const std::vector<SessionAction>& actions);
  void ShowSurface(const SurfaceChoice& choice);
  // Prepares `scene` (slot `slot`) with `choice`'s surface; false when there is none (no voice).
  bool PrepareScene(const SurfaceChoice& choice, int slot, synth::Scene& scene);
  StrokeCorrection CorrectionFor(int texture) const;
  void FinishRecording(std::int64_t now_ns);
  void WipeVoice();
  void PassiveStroke(std::int64_t now_ns);
  void LiftPassiveProbe(std::int64_t now_ns);
  // The probe `choice`'s surface is scratched with when the pen gives no tilt: the voice's scrape
  // or the texture's own (width and style).
  ProbeShape UntiltedProbe(const SurfaceChoice& choice) const;
  void WatchPenRest(const platform::PenReading& pen);
  void ApplyStaffGains();
  void SaveStaffSettings();
  void Play(int clip);
  // Plays a cue (none when its file is absent) and tells the cue observer.
  void PlayCue(const CuePick& pick);

  KioskEngineOptions options_;
  std::vector<EngineTexture> textures_;
  Material voice_material_;
  int default_texture_ = 0;
  Session session_;
  std::vector<std::string> texture_keys_;  // loaded textures, textures_ order
  std::vector<std::string> counter_keys_;  // every texture path's key, token order
  std::vector<int> token_texture_;         // token -> index in textures_, -1 when left out
  std::vector<std::string> texture_failures_;
  std::vector<bool> staff_texture_;        // per texture path: a staff texture
  std::vector<std::string> texture_dirs_;  // per loaded texture: its folder (its own cues)
  UsageCounters file_counters_;    // as read at start (counter_keys_ order)
  bool counters_may_save_ = true;  // false: a damaged counters file stays untouched
  platform::DeviceStatusBoard* board_ = nullptr;
  GestureMapping mapping_;
  int bubble_texture_ = -1;
  bool bubbles_dirty_ = false;       // pops not yet in the bubble scene's surface
  bool release_idle_slots_ = false;  // after an idle reset, once the fade has ended
  surface::ProfileSlots voice_;
  std::optional<surface::GrayImage> voice_image_;
  platform::VoiceRecorder* recorder_ = nullptr;
  bool microphone_live_ = true;
  bool recording_ = false;
  bool low_vibration_ = false;
  StaffSettings staff_;
  bool staff_may_save_ = true;  // false: a damaged staff file could not be moved aside
  ExposureMeter exposure_;
  double ambient_gain_db_ = 0.0;
  double ambient_gain_applied_db_ = 0.0;  // what the prepared scenes were given
  SpokenCues cues_;
  bool keep_language_ = false;  // the language key ended the attract screen
  int language_choices_ = 0;
  std::function<void(const CueEvent&)> cue_observer_;
  // Passive stroke (attract): where the virtual probe is and when its bursts started/ended.
  bool passive_down_ = false;
  platform::PenReading passive_pen_{};
  synth::ProbeCommand last_passive_command_{};
  std::int64_t passive_started_ns_ = -1;  // this attract's start, -1 while a visitor is there
  std::int64_t passive_quiet_since_ns_ = 0;
  // The pen resting still (layered information): where it settled and since when (-1: moving or
  // up), and whether this rest has been described already.
  double rest_x_px_ = 0.0, rest_y_px_ = 0.0;
  std::int64_t rest_since_ns_ = -1;
  bool rest_spoken_ = false;

  // The fields the player's scene slots were prepared with (each scene reads its own).
  std::array<std::shared_ptr<const surface::HeightField>, player::kSceneSlots> slot_fields_;
  std::shared_ptr<const surface::HeightField> current_field_;
  std::optional<SurfaceChoice> pending_surface_;  // waiting for the audio side to take a switch
  std::int64_t last_now_ns_ = 0;
  double current_relief_m_ = 0.0;
  mutable UsageCounters saved_counters_;
  double last_counters_save_s_ = -1e9;
  // Pen mapping state.
  bool have_last_pen_ = false;
  platform::PenReading last_pen_{};
  double last_fx_ = 0.0, last_fy_ = 0.0;
  double dir_x_ = 1.0, dir_y_ = 0.0;
  double last_velocity_mps_ = 0.0;  // of the last position report (a button reading keeps it)
  StrokeGainMap stroke_gains_;
  StrokeTracker stroke_;
  synth::ProbeStyle stroke_style_ = synth::ProbeStyle::kScrape;
  double stroke_width_mm_ = 0.5;     // the probe's width (tilt) for the stroke's correction
  std::int64_t stroke_down_ns_ = 0;  // when the pen last touched down
  int stroke_texture_ = -1;          // texture of the scene the pen plays (-1: the voice)
  StrokeCorrection stroke_correction_;

  // The audio side (made last in the constructor: it starts with the default texture's scene).
  std::unique_ptr<player::Player> player_;
  AudioFace audio_face_;
};

}  // namespace sas::kiosk
