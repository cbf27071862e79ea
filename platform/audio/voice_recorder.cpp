// Voice recorder (see voice_recorder.h).
#include "platform/audio/voice_recorder.h"

#include <algorithm>
#include <cmath>

namespace sas::platform {

VoiceRecorder::VoiceRecorder(VoiceRecorderConfig config)
    : config_(config),
      capacity_(
          static_cast<std::size_t>(std::lround(config.max_duration_s * config.sample_rate_hz))),
      buffer_(capacity_) {}

void VoiceRecorder::Arm() {
  recording_.store(false, std::memory_order_release);
  count_.store(0, std::memory_order_release);
  level_.store(0.0f, std::memory_order_relaxed);
  recording_.store(true, std::memory_order_release);
}

void VoiceRecorder::Stop() {
  recording_.store(false, std::memory_order_release);
}

void VoiceRecorder::Wipe() {
  recording_.store(false, std::memory_order_release);
  buffer_.Wipe();
  count_.store(0, std::memory_order_release);
  level_.store(0.0f, std::memory_order_relaxed);
}

void VoiceRecorder::Push(const float* mono, int frames) noexcept {
  PushInterleaved(mono, frames, 1);
}

void VoiceRecorder::PushInterleaved(const float* interleaved, int frames, int channels) noexcept {
  float peak = 0.0f;
  for (int i = 0; i < frames; ++i) peak = std::max(peak, std::fabs(interleaved[i * channels]));
  const float decayed = level_.load(std::memory_order_relaxed) * config_.meter_decay_per_block;
  level_.store(std::max(peak, decayed), std::memory_order_relaxed);
  if (!recording_.load(std::memory_order_acquire)) return;
  std::size_t count = count_.load(std::memory_order_relaxed);
  const std::size_t n = std::min(capacity_ - count, static_cast<std::size_t>(frames));
  for (std::size_t i = 0; i < n; ++i)
    buffer_[count + i] = interleaved[i * static_cast<std::size_t>(channels)];
  count += n;
  count_.store(count, std::memory_order_release);
  if (count == capacity_) recording_.store(false, std::memory_order_release);
}

VoiceTake VoiceRecorder::Take() const {
  VoiceTake take;
  const std::size_t count = count_.load(std::memory_order_acquire);
  take.samples = std::span<const float>(buffer_.data(), count);
  take.duration_s = static_cast<double>(count) / config_.sample_rate_hz;
  double sum_sq = 0.0;
  for (float x : take.samples) {
    const float a = std::fabs(x);
    take.peak = std::max(take.peak, a);
    if (a >= config_.clip_level) ++take.clipped_samples;
    sum_sq += static_cast<double>(x) * x;
  }
  const double rms = count ? std::sqrt(sum_sq / static_cast<double>(count)) : 0.0;
  take.rms_dbfs = rms > 0.0 ? 20.0 * std::log10(rms) : -300.0;
  take.clipped = take.clipped_samples > 0;
  take.silent = take.rms_dbfs < config_.silence_rms_dbfs;
  return take;
}

}  // namespace sas::platform
