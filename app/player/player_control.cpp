// The player's shared state and its control-thread face (see player.h).
#include "player/player.h"

namespace sas::player {

PlayerShared::PlayerShared(const PlayerSetup& player_setup, std::vector<PlayerClip> player_clips,
                           const std::function<void(synth::Scene&)>& prepare_first)
    : setup(player_setup), clips(std::move(player_clips)) {
  for (auto& scene : scenes) scene.Init(setup.sample_rate_hz);
  low_vibration.store(setup.low_vibration, std::memory_order_relaxed);
  staff_sound.store(setup.staff_sound_gain, std::memory_order_relaxed);
  staff_haptic.store(setup.staff_haptic_gain, std::memory_order_relaxed);
  // No audio thread exists yet: the first scene is in place before the first block, so the
  // kiosk is never silent for lack of one and its first switch is counted like the others.
  prepare_first(scenes[0]);
  active.store(0, std::memory_order_relaxed);
  switches_done.store(1, std::memory_order_relaxed);
}

Player::Player(const PlayerSetup& setup, std::vector<PlayerClip> clips,
               const std::function<void(synth::Scene&)>& prepare_first)
    : shared_(setup, std::move(clips), prepare_first), control_(shared_), audio_(shared_) {}

PlayerControl::PlayerControl(PlayerShared& shared)
    : shared_(&shared),
      requested_(shared.active.load(std::memory_order_acquire)),
      switches_sent_(shared.switches_done.load(std::memory_order_acquire)) {}

void PlayerControl::Send(const PlayerMessage& message) {
  if (!shared_->queue.TryPush(message)) ++dropped_;
}

void PlayerControl::Probe(std::int64_t time_ns, const synth::ProbeCommand& command) {
  const PlayerMessage message{PlayerMessage::Kind::kProbe, time_ns, command, -1};
  if (running_) {
    Send(message);
  } else {
    held_probe_ = message;
  }
}

void PlayerControl::Play(std::int64_t time_ns, int clip) {
  if (running_) Send({PlayerMessage::Kind::kPlay, time_ns, {}, clip});
}

bool PlayerControl::Switch(std::int64_t time_ns, int slot) {
  if (!shared_->queue.TryPush({PlayerMessage::Kind::kSwitch, time_ns, {}, slot})) {
    ++dropped_;
    return false;
  }
  requested_ = slot;
  ++switches_sent_;
  return true;
}

void PlayerControl::SetDeviceRunning(bool running, std::int64_t now_ns) {
  if (running == running_) return;
  running_ = running;
  if (!running) {
    // A cue cut off by the outage is not resumed when the device comes back.
    Send({PlayerMessage::Kind::kPlay, now_ns, {}, -1});
    return;
  }
  if (held_probe_) {
    // The pen as it is now, not the strokes made while nothing could sound (dated now, so the
    // latency figures are not those of the outage).
    held_probe_->time_ns = now_ns;
    Send(*held_probe_);
    held_probe_.reset();
  }
}

bool PlayerControl::SwitchTaken() const {
  return shared_->switches_done.load(std::memory_order_acquire) == switches_sent_;
}

bool PlayerControl::Settled() const {
  return SwitchTaken() && shared_->fade_from.load(std::memory_order_acquire) < 0;
}

bool PlayerControl::SlotInUse(int slot) const {
  return slot == shared_->active.load(std::memory_order_acquire) ||
         slot == shared_->fade_from.load(std::memory_order_acquire) || slot == requested_;
}

int PlayerControl::FreeSlot() const {
  for (int slot = 0; slot < kSceneSlots; ++slot) {
    if (!SlotInUse(slot)) return slot;
  }
  return -1;
}

void PlayerControl::SetLowVibration(bool on) {
  for (auto& scene : shared_->scenes) scene.SetLowVibration(on);
  // The transducer's ceiling comes down too, so nothing mixed after the scenes (the staff sweep,
  // a cue) can drive it harder than the mode allows.
  shared_->low_vibration.store(on, std::memory_order_release);
}

void PlayerControl::SetStaffGains(float sound, float haptic) {
  shared_->staff_sound.store(sound, std::memory_order_relaxed);
  shared_->staff_haptic.store(haptic, std::memory_order_relaxed);
}

PlayerStats PlayerControl::stats() const {
  PlayerStats stats;
  stats.pen_to_sample_last_ns = shared_->latency_last_ns.load(std::memory_order_relaxed);
  stats.pen_to_sample_max_ns = shared_->latency_max_ns.load(std::memory_order_relaxed);
  stats.commands = shared_->commands_done.load(std::memory_order_relaxed);
  stats.dropped_commands = dropped_;
  stats.switches = shared_->switches_done.load(std::memory_order_relaxed);
  return stats;
}

SpeakerTotals PlayerControl::speaker() const {
  // The frames are published last, with release: whoever sees them sees at least their energy.
  const std::uint64_t frames = shared_->speaker_frames.load(std::memory_order_acquire);
  return {shared_->speaker_energy.load(std::memory_order_relaxed), frames};
}

}  // namespace sas::player
