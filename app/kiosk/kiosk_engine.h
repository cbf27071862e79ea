#pragma once
// The kiosk engine: everything a visit needs between the input devices and the output devices,
// shared by the live kiosk (app/live_kiosk.cpp: SDL window, PortAudio, pen, switches) and the
// headless default (app/headless_demo.cpp: a scripted visit through the offline audio loop), so
// the two never wire things twice.
//
// Control thread (OnPen, OnToken, OnRecordButton, OnStaffChord, Tick):
//   pen reading (platform/pen/pen_reading.h: screen px, pressure, tilt, CLOCK_MONOTONIC time) ->
//   surface metres (the picture covers the screen: ResizeToCover's scale and crop) ->
//   synth::ProbeCommand (pen_mapping.h: pressure -> normal force and penetration, tilt -> width
//   and style; velocity from successive readings) -> SPSC queue. Session (session.h) decides what
//   is shown; its actions are carried out here (scene switch, recorder, voice slot, bubble reset,
//   cues) and handed on to the UI.
// Audio thread (Render, the platform's AudioRenderer): pops the queue, places each command on the
//   frame that keeps a constant pen-to-sound delay of one buffer, runs Scene::Process on the
//   active scene (and on the previous one while they cross-fade after a switch), mixes the
//   pre-loaded cue / test-signal buffer, and publishes the measured latency. No lock, no
//   allocation, no I/O.
//
// Scenes live in a small pool of slots. A switch prepares a free slot on the control thread
// (Scene::Prepare is not real-time) and sends its index; the audio thread acknowledges each switch
// by a counter, and a slot is reused only when the audio thread can no longer be rendering it.
// The old scene gets a pen-up and fades out over cross_fade_s while the new one fades in, so a
// switch never clicks. Bubble pops flatten the field; the flattened field becomes the scene's
// surface through the same switch once the pen is lifted.
// Per-stroke loudness matching (stroke_gain.h): each pen sample updates the smoothed stroke
// (speed, pressure, style) and hands the texture's correction for it to the scene the pen plays
// (Scene::SetStrokeGains: ramped on the audio thread); a newly prepared scene starts at the
// correction for the last stroke.

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "kiosk/exposure_meter.h"
#include "kiosk/gesture.h"
#include "kiosk/kiosk_config.h"
#include "kiosk/material_file.h"
#include "kiosk/session.h"
#include "kiosk/staff_settings.h"
#include "kiosk/strings.h"
#include "kiosk/stroke_gain.h"
#include "platform/audio/audio_output.h"
#include "platform/audio/voice_recorder.h"
#include "platform/common/spsc_queue.h"
#include "platform/device_status.h"
#include "platform/pen/pen_reading.h"
#include "surface/image_loader.h"
#include "surface/profile_slots.h"
#include "surface/sound_image.h"
#include "surface/texture_set.h"
#include "synth/safety_stage.h"
#include "synth/scene.h"

namespace sas::kiosk {

struct EngineTexture {
  std::string key;  // folder name, e.g. "wooden_board" (config, counters, cue file names)
  surface::LoadedTexture loaded;
  Material material;
};

struct KioskEngineOptions {
  KioskConfig config;
  std::vector<std::string> texture_paths;  // texture.toml files, token order; empty: FindTextures
  std::string materials_dir;               // searched first (render_command.h search order)
  std::string counters_path;               // empty: counters are not persisted
  std::string staff_settings_path;         // staff panel volume/vibration; empty: not persisted
  std::string cues_dir;                    // empty: FindCuesDir()
  std::string strings_dir;                 // the language tables; empty: FindStringsDir()
  bool spoken_cues = true;                 // false: no cue files loaded (level calibration)
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

// Latency and load as measured by the audio thread.
struct EngineAudioStats {
  std::int64_t pen_to_sample_last_ns = 0;  // pen event -> callback time its first sample is due
  std::int64_t pen_to_sample_max_ns = 0;
  std::uint64_t commands = 0;
  std::uint64_t dropped_commands = 0;  // queue full (control side)
  std::uint64_t switches = 0;
};

// The four kiosk textures in token order (bubble wrap, broken glass, wooden board, cracked ground:
// the paper's §5.2 order), from the first of $SAS_DATA_DIR/textures, the source tree and the
// installed share/sketch-a-scratch/textures that holds them. Throws std::runtime_error when none.
std::vector<std::string> FindTextureFiles();
// The kiosk textures' names in token order ("bubble_wrap", "broken_glass", ...).
std::vector<std::string> KioskTextureNames();

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
// textures/<name>/texture.toml for kiosk texture `name`, from the first data folder holding it
// (the order above); "" when `name` is no kiosk texture or no folder holds it.
std::string FindTextureFile(const std::string& name);
// <data>/cues: $SAS_DATA_DIR/cues, the build's cue folder, the installed one; "" when none exists.
std::string FindCuesDir();
// <data>/strings (the language tables, strings.h), the same search order; "" when none has en.toml.
std::string FindStringsDir();

// A spoken cue as it was handed to the audio side (tests, the journal): the language, the cue's
// key ("wooden_board_name", "count_3") and the sentence its file holds (cue_maker's .txt next to
// it; "" when absent).
struct CueEvent {
  std::int64_t time_ns = 0;
  std::string language;
  std::string key;
  std::string text;
};

class KioskEngine final : public platform::AudioRenderer {
 public:
  // Loads the textures, materials, counters and cues and prepares the default texture's scene.
  // A texture whose files cannot be loaded is left out (logged, listed by texture_failures());
  // throws only when none loads.
  explicit KioskEngine(KioskEngineOptions options);
  ~KioskEngine() override;
  KioskEngine(const KioskEngine&) = delete;
  KioskEngine& operator=(const KioskEngine&) = delete;

  // ---- control thread
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
  // False while no audio callback can run (device missing): the control thread then applies
  // switches itself so the pool stays consistent. Call after each AudioOutput::Poll.
  void SetAudioRunning(bool running);
  // Staff panel: a 1 kHz tone on the speaker (ch 1), a 40..800 Hz sweep on the transducer (ch 2).
  void PlayTestTone();
  void PlayTransducerSweep();
  bool SaveCounters(std::string* error) const;
  // The visitor's language key: the next of the configured visitor languages, whose own name is
  // spoken in it. False (nothing changes) when fewer than two are configured. The idle reset
  // returns to the configured language.
  bool NextLanguage(std::int64_t now_ns);
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

  // ---- views (control thread)
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
  bool recorder_present() const { return recorder_ != nullptr; }
  EngineAudioStats audio_stats() const;
  // The speaker's Leq over the last visit and the last hour (exposure_meter.h), updated by Tick.
  const ExposureMeter& exposure() const { return exposure_; }
  const KioskConfig& config() const { return options_.config; }
  const std::string& cues_dir() const { return cues_dir_; }
  int cues_loaded() const;
  // The current language's table (on-screen texts) and its code.
  const LanguageTable& strings() const;
  const std::string& language() const { return strings().code; }
  // A texture's name in the current language.
  std::string TextureName(int texture) const;
  // The per-stroke correction last handed to the scene under the pen (dB).
  StrokeCorrection stroke_correction() const { return stroke_correction_; }
  const StrokeGainMap& stroke_gains() const { return stroke_gains_; }
  // Turns a voice take into the voice surface (headless run, tests: the same path as a
  // recording). The samples are read in place; the sound image and the height field made from
  // them live in memory kept out of core dumps (platform::NoDumpMemory()).
  RecordingOutcome AcceptRecording(std::int64_t now_ns, std::span<const float> samples);

  // ---- audio thread
  void Render(float* interleaved, int frames, int channels) noexcept override;

 private:
  static constexpr int kVoiceSlot = 0;
  static constexpr int kSceneSlots = 4;

  struct Message {
    enum class Kind : std::uint8_t { kProbe, kSwitch, kPlay };
    Kind kind = Kind::kProbe;
    std::int64_t time_ns = 0;
    synth::ProbeCommand command{};
    int slot = -1;  // kSwitch: the new scene; kPlay: the clip
  };
  struct Clip {  // a pre-loaded cue or test signal: mono at the output rate, on one channel
    std::vector<float> samples;
    int channel = 0;  // 0 speaker, 1 transducer
    std::string name;
    std::string text;  // a cue's spoken sentence
  };
  struct LanguageAssets {  // one language's table and cue clips (-1: absent)
    LanguageTable table;
    std::vector<int> name_cues, description_cues;  // per texture
    std::map<std::string, int> message_cues;       // per CueKeys()
  };
  struct Slot {  // control side: what the slot's scene was prepared with (kept alive by it)
    synth::Scene scene;
    std::shared_ptr<const surface::HeightField> field;
  };

  void ApplyActions(std::int64_t now_ns, const std::vector<SessionAction>& actions);
  void ShowSurface(const SurfaceChoice& choice);
  void SwitchTo(std::shared_ptr<const surface::HeightField> field, const Material& material,
                const surface::TextureGains& gains, int texture);
  StrokeCorrection CorrectionFor(int texture) const;
  void FinishRecording(std::int64_t now_ns);
  void WipeVoice();
  void PassiveStroke(std::int64_t now_ns);
  void WatchPenRest(const platform::PenReading& pen);
  void ApplyStaffGains();
  void SaveStaffSettings();
  void Speak(const SessionAction& action);
  void Speak(Cue cue, int texture);
  void Play(int clip);
  void Send(const Message& message);
  int FreeSlot() const;
  void LoadCues();
  int AddClip(std::string name, std::vector<float> mono, int channel);
  void LoadLanguages();
  static const char* CueKey(Cue cue);
  void SpeakMessage(const std::string& key);
  void PlayCue(int clip, const std::string& key);

  // Audio side.
  void ApplySwitchOnAudio(int slot) noexcept;
  void RenderChunk(float* out, int frames, int channels, std::int64_t chunk_start_ns) noexcept;
  void RenderSegment(float* out, int channels, int begin, int end, int command_count) noexcept;

  KioskEngineOptions options_;
  std::vector<EngineTexture> textures_;
  Material voice_material_;
  int default_texture_ = 0;
  Session session_;
  std::vector<std::string> texture_keys_;  // loaded textures, textures_ order
  std::vector<std::string> counter_keys_;  // every texture path's key, token order
  std::vector<int> token_texture_;         // token -> index in textures_, -1 when left out
  std::vector<std::string> texture_failures_;
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
  bool recording_ = false;
  std::string cues_dir_;
  bool low_vibration_ = false;
  StaffSettings staff_;
  bool staff_may_save_ = true;  // false: a damaged staff file could not be moved aside
  double speaker_ceiling_ = 1.0, transducer_ceiling_ = 1.0;  // linear, from the configuration
  double low_vibration_factor_ = 1.0;                        // transducer ceiling factor
  ExposureMeter exposure_;
  double ambient_gain_db_ = 0.0;
  double ambient_gain_applied_db_ = 0.0;  // what the prepared scenes were given
  std::vector<Clip> clips_;
  std::vector<LanguageAssets> languages_;  // [0]: the configured language
  std::vector<int> visitor_languages_;     // indices into languages_ the language key steps through
  int language_ = 0;
  std::function<void(const CueEvent&)> cue_observer_;
  int tone_clip_ = -1, sweep_clip_ = -1, record_tone_clip_ = -1;
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

  // Control side of the pool.
  std::array<Slot, kSceneSlots> slots_;
  std::shared_ptr<const surface::HeightField> current_field_;
  std::uint64_t switches_sent_ = 0;
  int requested_slot_ = -1;
  std::optional<SurfaceChoice> pending_surface_;  // waiting for the audio side to take a switch
  bool audio_running_ = false;
  std::int64_t last_now_ns_ = 0;
  double current_relief_m_ = 0.0;
  mutable UsageCounters saved_counters_;
  double last_counters_save_s_ = -1e9;
  // Pen mapping state.
  bool have_last_pen_ = false;
  platform::PenReading last_pen_{};
  double last_fx_ = 0.0, last_fy_ = 0.0;
  double dir_x_ = 1.0, dir_y_ = 0.0;
  StrokeGainMap stroke_gains_;
  StrokeTracker stroke_;
  synth::ProbeStyle stroke_style_ = synth::ProbeStyle::kScrape;
  double stroke_width_mm_ = 0.5;     // the probe's width (tilt) for the stroke's correction
  std::int64_t stroke_down_ns_ = 0;  // when the pen last touched down
  int stroke_texture_ = -1;          // texture of the scene the pen plays (-1: the voice)
  StrokeCorrection stroke_correction_;
  std::atomic<std::uint64_t> dropped_{0};

  // Audio side (the audio thread only, except the atomics).
  platform::SpscQueue<Message, 2048> queue_;
  int active_ = -1;     // slot being rendered
  int fade_from_ = -1;  // slot fading out, -1 none
  int fade_pos_ = 0;
  int fade_len_ = 1;
  bool lift_fading_ = false;
  int playing_clip_ = -1;
  std::atomic<bool> audio_clip_playing_{false};
  std::size_t clip_pos_ = 0;
  std::int64_t virtual_now_ns_ = 0;
  std::vector<synth::ProbeCommand> block_commands_;
  std::vector<float> scratch_a_, scratch_b_;
  // The last stage before the device: every source is mixed before it (synth/safety_stage.h).
  synth::SafetyStage safety_;
  bool safety_low_vibration_ = false;             // the ceilings the stage has now
  std::atomic<bool> audio_low_vibration_{false};  // set by SetLowVibration (control thread)
  // Staff volume and vibration as linear gains (control thread writes, audio thread follows them
  // with a 20 ms one-pole, so a button press never clicks).
  std::atomic<float> audio_staff_sound_{1.0f};
  std::atomic<float> audio_staff_haptic_{1.0f};
  float staff_sound_now_ = 1.0f, staff_haptic_now_ = 1.0f;
  float staff_smooth_ = 1.0f;  // the one-pole's per-sample coefficient
  // The speaker's running totals after the safety stage (audio thread writes, Tick reads).
  double speaker_energy_ = 0.0;
  std::uint64_t speaker_frames_ = 0;
  std::atomic<double> audio_speaker_energy_{0.0};
  std::atomic<std::uint64_t> audio_speaker_frames_{0};
  std::atomic<int> audio_active_{-1};
  std::atomic<int> audio_fade_from_{-1};
  std::atomic<std::uint64_t> switches_done_{0};
  std::atomic<std::uint64_t> commands_done_{0};
  std::atomic<std::int64_t> latency_last_ns_{0};
  std::atomic<std::int64_t> latency_max_ns_{0};
};

}  // namespace sas::kiosk
