#pragma once
// Supervision of the audio output on a thread of its own. Reopening a lost device can sit in ALSA
// for seconds (PortAudio's Pa_OpenStream on a vanished card); done from the UI loop, that froze
// the screen and the idle reset. This wrapper runs the wrapped output's Start() once (boot, before
// the UI exists) and then its Poll() every `poll_interval_s` on its own thread; what the UI thread
// calls — Poll (nothing to do), Running, Stats — only reads atomics and never waits on the device.
// The wrapped output keeps its own rules (back-off, one log line per state change, status board,
// which is mutex-guarded and so safe from this thread).

#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>

#include "platform/audio/audio_output.h"

namespace sas::platform {

class BackgroundAudioOutput final : public AudioOutput {
 public:
  explicit BackgroundAudioOutput(std::unique_ptr<AudioOutput> inner, double poll_interval_s = 0.05);
  ~BackgroundAudioOutput() override;
  BackgroundAudioOutput(const BackgroundAudioOutput&) = delete;
  BackgroundAudioOutput& operator=(const BackgroundAudioOutput&) = delete;

  // The first open, on the caller's thread (at boot), then the supervision thread starts.
  bool Start() override;
  // Stops the supervision thread (waits for a reopen attempt in progress), then the output.
  void Stop() override;
  // The UI loop's call: the supervision runs on its own thread, so there is nothing to wait for.
  void Poll(std::int64_t now_ns) override;
  bool Running() const override { return running_.load(std::memory_order_acquire); }
  AudioCallbackStats Stats() const override;
  // Supervision rounds done so far (tests wait on it).
  std::uint64_t rounds() const { return rounds_.load(std::memory_order_acquire); }

 private:
  void Loop();

  std::unique_ptr<AudioOutput> inner_;
  double poll_interval_s_;
  std::atomic<bool> running_{false};
  std::atomic<std::uint64_t> rounds_{0};
  std::mutex mutex_;  // guards stop_ for the condition variable only
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace sas::platform
