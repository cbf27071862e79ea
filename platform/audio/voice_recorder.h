#pragma once
// Voice recording for the "record your own texture" station: mono, up to 5 s, into a buffer
// allocated once at construction in memory kept out of core dumps (common/no_dump_buffer.h: the
// visitor's voice stays in RAM only, and a crash must not write it into a core file). The take is
// handed out as a view of that buffer, never copied to ordinary memory. The device callback
// pushes blocks (lock-free, allocation-free);
// the control thread arms, stops and takes the result. While recording, a peak level meter
// (linear 0..1, per block, with a short decay) is published through an atomic for the UI.
// At the end the take is classified: clipped (any sample at or above clip_level) and silent
// (RMS below silence_rms_dbfs) — both reported so the kiosk can ask for a retake.

#include <atomic>
#include <cstdint>
#include <span>

#include "platform/common/no_dump_buffer.h"

namespace sas::platform {

struct VoiceRecorderConfig {
  int sample_rate_hz = 48000;
  double max_duration_s = 5.0;
  float clip_level = 0.999f;        // |x| at or above this counts as clipped
  double silence_rms_dbfs = -50.0;  // RMS below this: "nothing recorded"
  float meter_decay_per_block = 0.8f;
};

struct VoiceTake {
  // Mono, sample_rate_hz: a view of the recorder's buffer, valid until its next Arm or Wipe (or
  // its end). Copy it only into memory kept out of core dumps (NoDumpMemory()).
  std::span<const float> samples;
  double duration_s = 0.0;
  float peak = 0.0f;
  double rms_dbfs = -300.0;
  std::uint64_t clipped_samples = 0;
  bool clipped = false;
  bool silent = true;
};

class VoiceRecorder {
 public:
  explicit VoiceRecorder(VoiceRecorderConfig config = {});

  // Control thread.
  void Arm();   // starts a new take (the previous samples are overwritten)
  void Stop();  // ends the take early (it also ends by itself when the buffer is full)
  bool Recording() const { return recording_.load(std::memory_order_acquire); }
  // The take recorded so far and its levels (call after Stop or when Recording() went false).
  VoiceTake Take() const;
  // Stops and overwrites the whole buffer with zeros: a visitor's voice leaves no trace in RAM
  // once the kiosk has turned it into a surface or the idle reset wiped it (no voice is kept).
  void Wipe();
  // The UI's level meter, linear 0..1.
  float Level() const { return level_.load(std::memory_order_relaxed); }
  std::size_t Capacity() const { return capacity_; }
  std::size_t Recorded() const { return count_.load(std::memory_order_acquire); }

  // Audio thread: appends `frames` mono samples while armed. No locks, no allocation.
  void Push(const float* mono, int frames) noexcept;
  // Audio thread, interleaved input: takes channel 0 of each frame.
  void PushInterleaved(const float* interleaved, int frames, int channels) noexcept;

 private:
  VoiceRecorderConfig config_;
  std::size_t capacity_;
  NoDumpBuffer<float> buffer_;
  std::atomic<std::size_t> count_{0};
  std::atomic<bool> recording_{false};
  std::atomic<float> level_{0.0f};
};

}  // namespace sas::platform
