// The player's audio-thread face (see player.h): message timing, scene rendering, the switch's
// cross-fade, clip mixing, staff gains, the transducer's compensation and the safety stage. No
// lock, allocation or I/O here.
#include <algorithm>
#include <cmath>

#include "player/player.h"

namespace sas::player {

AudioPlayer::AudioPlayer(PlayerShared& shared)
    : shared_(&shared),
      fs_hz_(shared.setup.sample_rate_hz),
      fade_len_(std::max(1, static_cast<int>(std::lround(shared.setup.cross_fade_s * fs_hz_)))),
      staff_smooth_(static_cast<float>(1.0 - std::exp(-1.0 / (0.02 * fs_hz_)))),
      active_(shared.active.load(std::memory_order_acquire)),
      block_commands_(512),
      scratch_a_(static_cast<std::size_t>(std::max(1, shared.setup.max_block_frames)) * 2),
      scratch_b_(scratch_a_.size()),
      // Where the ramps start: a restart comes up at the kept level, not fading into it.
      staff_sound_now_(shared.setup.staff_sound_gain),
      staff_haptic_now_(shared.setup.staff_haptic_gain) {
  transducer_eq_.Prepare(fs_hz_, shared.setup.transducer_resonance_hz, shared.setup.transducer_q);
  safety_.Prepare(fs_hz_);
  safety_.SetCeilings(shared.setup.speaker_ceiling, shared.setup.transducer_ceiling);
}

void AudioPlayer::TakeSwitch(int slot) noexcept {
  if (slot == active_) return;
  if (active_ >= 0) {
    fade_from_ = active_;
    fade_pos_ = 0;
    lift_fading_ = true;
  }
  active_ = slot;
  shared_->active.store(active_, std::memory_order_release);
  shared_->fade_from.store(fade_from_, std::memory_order_release);
  shared_->switches_done.fetch_add(1, std::memory_order_acq_rel);
}

void AudioPlayer::Render(float* interleaved, int frames, int channels) noexcept {
  const PlayerSetup& setup = shared_->setup;
  if (const bool low = shared_->low_vibration.load(std::memory_order_acquire);
      low != safety_low_vibration_) {
    safety_low_vibration_ = low;
    safety_.SetCeilings(setup.speaker_ceiling,
                        setup.transducer_ceiling * (low ? setup.low_vibration_factor : 1.0));
  }
  const std::int64_t start_ns = setup.now_ns ? setup.now_ns() : virtual_now_ns_;
  const int max_chunk = static_cast<int>(scratch_a_.size() / 2);
  for (int done = 0; done < frames; done += max_chunk) {
    const int n = std::min(max_chunk, frames - done);
    RenderChunk(interleaved + static_cast<std::ptrdiff_t>(done) * channels, n, channels,
                start_ns + static_cast<std::int64_t>(done * 1e9 / fs_hz_));
  }
  if (!setup.now_ns) {
    virtual_now_ns_ += static_cast<std::int64_t>(std::llround(frames * 1e9 / fs_hz_));
  }
}

void AudioPlayer::MixClip(float* mix, int frames) noexcept {
  if (playing_clip_ < 0) return;
  const auto& playing = shared_->clips[static_cast<std::size_t>(playing_clip_)];
  const auto& clip = playing.samples;
  const std::size_t n = std::min(clip.size() - clip_pos_, static_cast<std::size_t>(frames));
  float* to = mix + playing.channel;
  for (std::size_t i = 0; i < n; ++i) to[2 * i] += clip[clip_pos_ + i];
  clip_pos_ += n;
  if (clip_pos_ >= clip.size()) {
    playing_clip_ = -1;
    shared_->clip_playing.store(false, std::memory_order_relaxed);
  }
}

void AudioPlayer::RenderSegment(float* out, int channels, int begin, int end,
                                int command_count) noexcept {
  const int frames = end - begin;
  if (frames <= 0) return;
  float* a = scratch_a_.data();
  float* b = scratch_b_.data();
  if (active_ >= 0) {
    shared_->scenes[static_cast<std::size_t>(active_)].Process(block_commands_.data(),
                                                               command_count, a, frames);
  } else {
    std::fill(a, a + 2 * frames, 0.0f);
  }
  if (fade_from_ >= 0) {
    synth::ProbeCommand lift;
    lift.tip_down = false;
    auto& old = shared_->scenes[static_cast<std::size_t>(fade_from_)];
    const auto state = old.probe_state();
    lift.x_m = state.x_m;
    lift.y_m = state.y_m;
    old.Process(&lift, lift_fading_ ? 1 : 0, b, frames);
    lift_fading_ = false;
    // Equal-power cross-fade: uncorrelated sounds keep their loudness through the switch.
    constexpr double kHalfPi = 1.5707963267948966;
    for (int i = 0; i < frames; ++i) {
      const double p = std::min(1.0, static_cast<double>(fade_pos_ + i) / fade_len_);
      const auto w_in = static_cast<float>(std::sin(kHalfPi * p));
      const auto w_out = static_cast<float>(std::cos(kHalfPi * p));
      a[2 * i] = a[2 * i] * w_in + b[2 * i] * w_out;
      a[2 * i + 1] = a[2 * i + 1] * w_in + b[2 * i + 1] * w_out;
    }
    fade_pos_ += frames;
    if (fade_pos_ >= fade_len_) {
      fade_from_ = -1;
      shared_->fade_from.store(-1, std::memory_order_release);
    }
  }
  MixClip(a, frames);
  // Everything is mixed: the staff's volume and vibration, the transducer's compensation on ch 2
  // (scenes and clips alike reach the pen as designed), then the safety stage as the last step
  // (its ceilings hold for every source, every staff setting and whatever the compensation adds).
  const float sound_target = shared_->staff_sound.load(std::memory_order_relaxed);
  const float haptic_target = shared_->staff_haptic.load(std::memory_order_relaxed);
  float sound_gain = staff_sound_now_, haptic_gain = staff_haptic_now_;
  for (int i = 0; i < frames; ++i) {
    sound_gain += (sound_target - sound_gain) * staff_smooth_;
    haptic_gain += (haptic_target - haptic_gain) * staff_smooth_;
    a[2 * i] *= sound_gain;
    a[2 * i + 1] = static_cast<float>(transducer_eq_.Process(a[2 * i + 1] * haptic_gain));
    safety_.Process(a + 2 * static_cast<std::ptrdiff_t>(i));
    speaker_energy_ += static_cast<double>(a[2 * i]) * a[2 * i];
    float* frame = out + static_cast<std::ptrdiff_t>(begin + i) * channels;
    for (int c = 0; c < channels; ++c) frame[c] = c < 2 ? a[2 * i + c] : 0.0f;
  }
  staff_sound_now_ = sound_gain;
  staff_haptic_now_ = haptic_gain;
  // The frames go out last, with release: a reader that sees them sees at least their energy.
  speaker_frames_ += static_cast<std::uint64_t>(frames);
  shared_->speaker_energy.store(speaker_energy_, std::memory_order_relaxed);
  shared_->speaker_frames.store(speaker_frames_, std::memory_order_release);
}

void AudioPlayer::RenderChunk(float* out, int frames, int channels,
                              std::int64_t chunk_start_ns) noexcept {
  // A pen event from the last buffer period lands at the same place in this buffer: a constant
  // delay of one buffer (no jitter from when the callback happens to run). Older ones at 0.
  const double window_start_ns = static_cast<double>(chunk_start_ns) - frames * 1e9 / fs_hz_;
  int segment_start = 0;
  int last_offset = 0;
  int count = 0;
  const int capacity = static_cast<int>(block_commands_.size());
  PlayerMessage message;
  while (count < capacity && shared_->queue.TryPop(message)) {
    const auto raw = static_cast<long long>(
        std::llround((static_cast<double>(message.time_ns) - window_start_ns) * fs_hz_ * 1e-9));
    const int offset = static_cast<int>(std::clamp<long long>(raw, last_offset, frames - 1));
    last_offset = offset;
    if (message.kind == PlayerMessage::Kind::kProbe) {
      synth::ProbeCommand command = message.command;
      command.frame_offset = static_cast<std::uint32_t>(offset - segment_start);
      block_commands_[static_cast<std::size_t>(count++)] = command;
      shared_->commands_done.fetch_add(1, std::memory_order_relaxed);
      // Due when it leaves the safety stage, kDelayFrames after the scene renders it.
      const std::int64_t due_ns =
          chunk_start_ns + static_cast<std::int64_t>(std::llround(
                               (offset + synth::SafetyStage::kDelayFrames) * 1e9 / fs_hz_));
      const std::int64_t latency = due_ns - message.time_ns;
      shared_->latency_last_ns.store(latency, std::memory_order_relaxed);
      if (latency > shared_->latency_max_ns.load(std::memory_order_relaxed)) {
        shared_->latency_max_ns.store(latency, std::memory_order_relaxed);
      }
      continue;
    }
    if (offset > segment_start) {  // else the commands so far go to the scene after the switch
      RenderSegment(out, channels, segment_start, offset, count);
      count = 0;
      segment_start = offset;
    }
    if (message.kind == PlayerMessage::Kind::kSwitch) {
      TakeSwitch(message.index);
    } else if (message.index >= 0 && message.index < static_cast<int>(shared_->clips.size())) {
      playing_clip_ = message.index;
      clip_pos_ = 0;
      shared_->clip_playing.store(true, std::memory_order_relaxed);
    } else {
      playing_clip_ = -1;
      shared_->clip_playing.store(false, std::memory_order_relaxed);
    }
  }
  RenderSegment(out, channels, segment_start, frames, count);
}

}  // namespace sas::player
