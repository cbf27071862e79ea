#pragma once
// The audio-side player: what the kiosk sounds like once the control side has decided what should
// sound. Standard library and synth only, like synth itself: no I/O, lock, allocation or exception
// on the audio path (everything is allocated here at construction, on the control thread).
//
// Two faces, one per thread, so the thread of every call is in its type:
//   PlayerControl (control thread) sends small messages through one SPSC queue: pen commands,
//     scene switches, cue/test-signal starts. It owns the slot bookkeeping (which scene may be
//     prepared) and reads back the audio side's atomics (latency, switches taken, speaker level).
//   AudioPlayer (audio thread) is the queue's only consumer. Per block: pop the messages, place
//   each on the frame that keeps a constant pen-to-sound delay of one buffer, run Scene::Process
//   on the active scene (and the previous one while they cross-fade after a switch), mix the
//   playing clip, apply the staff gains, the transducer's compensation (ch 2) and the final
//   SafetyStage, publish the measured latency.
// Player owns both faces and what they share (the scene pool, the clips, the queue, the atomics).
//
// Scenes live in kSceneSlots slots. A switch prepares a free slot on the control thread
// (Scene::Prepare is not real-time) and sends its index; the audio side counts the switches it has
// taken, and a slot is prepared again only when no block can be rendering it (FreeSlot). The old
// scene gets a pen-up and fades out over cross_fade_s while the new one fades in (equal power).
//
// While the audio device is stopped nothing pops the queue: the control side then holds the pen's
// latest command instead of queueing strokes nobody hears, drops cues, and still sends a switch
// (at most one is in flight, so the queue cannot fill). When the device runs again the audio side
// takes what waited in order, then the held pen state: the queue never has a second consumer.

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "common/spsc_queue.h"
#include "synth/probe_command.h"
#include "synth/safety_stage.h"
#include "synth/scene.h"
#include "synth/transducer_eq.h"

namespace sas::player {

inline constexpr int kSceneSlots = 4;

struct PlayerSetup {
  double sample_rate_hz = 48000.0;
  int max_block_frames = 4096;  // largest block Render is called with (longer ones are split)
  double cross_fade_s = 0.45;   // a switch's equal-power cross-fade
  // Where the audio thread's block times come from (CLOCK_MONOTONIC, the pen's time base); null:
  // a virtual clock that starts at 0 and advances by the frames rendered (headless runs, tests).
  std::int64_t (*now_ns)() noexcept = nullptr;
  double speaker_ceiling = 1.0;       // linear, the safety stage's ceiling on ch 1
  double transducer_ceiling = 1.0;    // on ch 2
  double low_vibration_factor = 1.0;  // ch 2 ceiling factor in the low-vibration mode
  bool low_vibration = false;         // the mode at start
  float staff_sound_gain = 1.0f;      // the staff volume and vibration at start (linear)
  float staff_haptic_gain = 1.0f;
  // The transducer's profile (synth/transducer_eq.h): ch 2 is compensated so that the pen's
  // acceleration follows the mix. 0 Hz: a flat transducer, ch 2 passes unchanged.
  double transducer_resonance_hz = 0.0;
  double transducer_q = 1.0;
};

// A pre-loaded cue or test signal: mono at the output rate, played on one channel.
struct PlayerClip {
  std::vector<float> samples;
  int channel = 0;  // 0 speaker, 1 transducer
};

// Latency and load as measured by the audio side.
struct PlayerStats {
  std::int64_t pen_to_sample_last_ns = 0;  // pen event -> callback time its first sample is due
  std::int64_t pen_to_sample_max_ns = 0;
  std::uint64_t commands = 0;
  std::uint64_t dropped_commands = 0;  // queue full (control side)
  std::uint64_t switches = 0;
};

// The speaker's running totals after the safety stage: sum of squares and frames.
struct SpeakerTotals {
  double energy = 0.0;
  std::uint64_t frames = 0;
};

struct PlayerMessage {
  enum class Kind : std::uint8_t { kProbe, kSwitch, kPlay };
  Kind kind = Kind::kProbe;
  std::int64_t time_ns = 0;
  synth::ProbeCommand command{};
  int index = -1;  // kSwitch: the new scene's slot; kPlay: the clip (-1: stop the playing one)
};

// What both faces reach: written once at construction, then only through the queue and atomics.
struct PlayerShared {
  // Inits every scene; `prepare_first` prepares slot 0, which plays from the first block.
  PlayerShared(const PlayerSetup& setup, std::vector<PlayerClip> clips,
               const std::function<void(synth::Scene&)>& prepare_first);

  const PlayerSetup setup;
  const std::vector<PlayerClip> clips;
  std::array<synth::Scene, kSceneSlots> scenes;
  SpscQueue<PlayerMessage, 2048> queue;  // control -> audio; AudioPlayer pops
  std::atomic<bool> low_vibration{false};
  // Staff volume and vibration as linear gains (the audio side follows them with a 20 ms one-pole,
  // so a button press never clicks).
  std::atomic<float> staff_sound{1.0f};
  std::atomic<float> staff_haptic{1.0f};
  std::atomic<bool> clip_playing{false};
  std::atomic<double> speaker_energy{0.0};
  std::atomic<std::uint64_t> speaker_frames{0};
  std::atomic<int> active{-1};     // slot being rendered
  std::atomic<int> fade_from{-1};  // slot fading out, -1 none
  std::atomic<std::uint64_t> switches_done{0};
  std::atomic<std::uint64_t> commands_done{0};
  std::atomic<std::int64_t> latency_last_ns{0};
  std::atomic<std::int64_t> latency_max_ns{0};
};

// The control thread's face.
class PlayerControl {
 public:
  explicit PlayerControl(PlayerShared& shared);

  // A pen command for the current scene at `time_ns` (the pen's clock).
  void Probe(std::int64_t time_ns, const synth::ProbeCommand& command);
  // Starts clip `clip` (replacing a playing one).
  void Play(std::int64_t time_ns, int clip);
  // Hands the prepared FreeSlot() `slot` to the audio side. False when the queue is full: nothing
  // was sent, try again later.
  bool Switch(std::int64_t time_ns, int slot);
  // Whether an audio callback can run (the device is open). While not, nothing is queued but
  // switches (see the top of this file).
  void SetDeviceRunning(bool running, std::int64_t now_ns);

  // True when the audio side has taken every switch sent.
  bool SwitchTaken() const;
  // ...and no cross-fade is running: only the current slot is in use.
  bool Settled() const;
  // True while the audio side may render `slot` (playing, fading out or about to play).
  bool SlotInUse(int slot) const;
  // A slot not in use (-1 cannot happen: at most three are).
  int FreeSlot() const;
  // The slot last switched to: the scene the pen plays.
  int current_slot() const { return requested_; }
  // Prepare only a FreeSlot(); SetStrokeGains and SetLowVibration are safe on any (atomics).
  synth::Scene& scene(int slot) { return shared_->scenes[static_cast<std::size_t>(slot)]; }

  // Every scene and the transducer's ceiling follow at once (ramped).
  void SetLowVibration(bool on);
  void SetStaffGains(float sound, float haptic);

  PlayerStats stats() const;
  bool clip_playing() const { return shared_->clip_playing.load(std::memory_order_relaxed); }
  SpeakerTotals speaker() const;

 private:
  void Send(const PlayerMessage& message);

  PlayerShared* shared_;
  int requested_ = -1;
  std::uint64_t switches_sent_ = 0;
  std::uint64_t dropped_ = 0;
  bool running_ = false;
  std::optional<PlayerMessage> held_probe_;  // the pen's latest command while the device is off
};

// The audio thread's face: the only consumer of the queue.
class AudioPlayer {
 public:
  explicit AudioPlayer(PlayerShared& shared);
  // Fills frames * channels interleaved samples (ch 1 speaker, ch 2 transducer, others silent).
  void Render(float* interleaved, int frames, int channels) noexcept;

 private:
  void TakeSwitch(int slot) noexcept;
  void RenderChunk(float* out, int frames, int channels, std::int64_t chunk_start_ns) noexcept;
  void RenderSegment(float* out, int channels, int begin, int end, int command_count) noexcept;
  void MixClip(float* mix, int frames) noexcept;

  PlayerShared* shared_;
  const double fs_hz_;
  const int fade_len_;
  const float staff_smooth_;  // the staff gains' one-pole per-sample coefficient
  int active_ = -1;
  int fade_from_ = -1;
  int fade_pos_ = 0;
  bool lift_fading_ = false;
  int playing_clip_ = -1;
  std::size_t clip_pos_ = 0;
  std::int64_t virtual_now_ns_ = 0;
  std::vector<synth::ProbeCommand> block_commands_;
  std::vector<float> scratch_a_, scratch_b_;
  // Ch 2 of the whole mix, after the staff gains: every source is compensated for the actuator,
  // and the safety stage after it still bounds the (boosted) drive.
  synth::TransducerEq transducer_eq_;
  // The last stage before the device: every source is mixed before it.
  synth::SafetyStage safety_;
  bool safety_low_vibration_ = false;  // the ceilings the stage has now
  float staff_sound_now_, staff_haptic_now_;
  double speaker_energy_ = 0.0;
  std::uint64_t speaker_frames_ = 0;
};

// Owns the shared state and both faces; made and destroyed on the control thread (destroy it only
// after the audio device stopped calling audio().Render).
class Player {
 public:
  Player(const PlayerSetup& setup, std::vector<PlayerClip> clips,
         const std::function<void(synth::Scene&)>& prepare_first);
  Player(const Player&) = delete;
  Player& operator=(const Player&) = delete;

  PlayerControl& control() { return control_; }
  const PlayerControl& control() const { return control_; }
  AudioPlayer& audio() { return audio_; }

 private:
  PlayerShared shared_;
  PlayerControl control_;
  AudioPlayer audio_;
};

}  // namespace sas::player
