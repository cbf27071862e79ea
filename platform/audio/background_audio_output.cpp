// Audio output supervision off the UI thread (background_audio_output.h).
#include "platform/audio/background_audio_output.h"

#include <chrono>

#include "platform/common/clock.h"

namespace sas::platform {

BackgroundAudioOutput::BackgroundAudioOutput(std::unique_ptr<AudioOutput> inner,
                                             double poll_interval_s)
    : inner_(std::move(inner)), poll_interval_s_(poll_interval_s > 0.0 ? poll_interval_s : 0.05) {}

BackgroundAudioOutput::~BackgroundAudioOutput() {
  Stop();
}

bool BackgroundAudioOutput::Start() {
  if (thread_.joinable()) return Running();
  const bool ok = inner_->Start();
  running_.store(inner_->Running(), std::memory_order_release);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = false;
  }
  thread_ = std::thread([this] { Loop(); });
  return ok;
}

void BackgroundAudioOutput::Stop() {
  if (thread_.joinable()) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }
  inner_->Stop();
  running_.store(false, std::memory_order_release);
}

void BackgroundAudioOutput::Poll(std::int64_t /*now_ns*/) {}

AudioCallbackStats BackgroundAudioOutput::Stats() const {
  // The callback counters are atomics in the output's callback core: safe from any thread.
  return inner_->Stats();
}

void BackgroundAudioOutput::Loop() {
  const auto interval = std::chrono::duration<double>(poll_interval_s_);
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    lock.unlock();
    inner_->Poll(MonotonicNowNs());
    running_.store(inner_->Running(), std::memory_order_release);
    rounds_.fetch_add(1, std::memory_order_acq_rel);
    lock.lock();
    wake_.wait_for(lock, interval, [this] { return stop_; });
  }
}

}  // namespace sas::platform
