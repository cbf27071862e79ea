#pragma once
// The audio device behind one small interface: two implementations run the same
// callback core — PortAudio (the product; ALSA host API on Debian 12) and an offline loop that
// renders into a buffer (tests, headless mode, benchmarks).
//
// Chain: device thread -> AudioCallbackCore::Run -> AudioRenderer::Render (the kiosk's
// synth::Scene) -> interleaved float frames, ch 1 speaker, ch 2 vibrotactile transducer.
// Run does nothing but time the call, call the renderer and bump atomic counters: no locks,
// allocation, logging or exceptions (checked by tests/platform/test_audio_callback_realtime.cpp).
// Everything else — opening, detecting a lost device, reopening with back-off, status and log
// lines — happens in Start()/Poll() on the control thread.

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "platform/device_status.h"

namespace sas::platform {

// Implemented by the kiosk (it calls synth::Scene::Process). Called on the audio thread; must fill
// all frames * channels samples and must not block, allocate, lock or throw.
class AudioRenderer {
 public:
  virtual ~AudioRenderer() = default;
  virtual void Render(float* interleaved, int frames, int channels) noexcept = 0;
};

struct AudioOutputConfig {
  std::string device = "default";  // PortAudio device name (ALSA PCM or "hw:CARD=...")
  int sample_rate_hz = 48000;
  int channels = 2;  // ch 1 speaker, ch 2 transducer
  int frames_per_buffer = 128;
  double suggested_latency_s = 0.0;  // 0: the device's default low latency
  double reopen_backoff_initial_s = 0.25;
  double reopen_backoff_max_s = 8.0;
  double reopen_stable_s = 5.0;       // a reopened stream must play this long to reset the back-off
  double stall_timeout_s = 1.0;       // no callback for this long while "running" counts as lost
  // xruns are one warning at the first, then at most one line per interval with the count since
  // the last line. An idle kiosk on a struggling card was seen at hundreds of xruns every 10 s:
  // a line a minute keeps the journal readable and still says how bad it is.
  double xrun_log_interval_s = 60.0;
};

// Snapshot of the callback counters (read from the control thread).
struct AudioCallbackStats {
  std::uint64_t callbacks = 0;
  std::uint64_t frames = 0;
  std::uint64_t xruns = 0;            // underflow/overflow flags reported by the device
  std::int64_t last_callback_ns = 0;  // duration of the latest callback
  std::int64_t max_callback_ns = 0;   // the longest since the start, warm-up included
  // The load as staff read it: the mean duration (exponential, about the last second of
  // callbacks) and the longest in the last 10 to 20 s, both without the warm-up callbacks after
  // each (re)open (kWarmUpCallbacks), whose first touches of the scenes' memory and the device's
  // start-up took tens of ms and said nothing about the running kiosk.
  std::int64_t mean_callback_ns = 0;
  std::int64_t recent_max_callback_ns = 0;
  std::int64_t heartbeat_ns = 0;  // CLOCK_MONOTONIC time of the latest callback (0: never)
};

// The callback core shared by every backend. Lock-free atomics only.
class AudioCallbackCore {
 public:
  explicit AudioCallbackCore(AudioRenderer& renderer) : renderer_(&renderer) {}
  // One device callback: `xrun` when the device flagged an underflow/overflow for this block.
  void Run(float* interleaved, int frames, int channels, bool xrun) noexcept;
  AudioCallbackStats Stats() const noexcept;
  void ResetMax() noexcept { max_ns_.store(0, std::memory_order_relaxed); }
  // A stream is about to be (re)opened (control thread, no callback running): its first
  // kWarmUpCallbacks are left out of the mean and the recent peak.
  void Opening() noexcept { warm_up_left_.store(kWarmUpCallbacks, std::memory_order_relaxed); }

  static constexpr int kWarmUpCallbacks = 32;
  // The recent peak's window, in callbacks (10.9 s at 128 frames and 48 kHz): the peak is the
  // larger of the current window's and the last one's.
  static constexpr std::uint32_t kPeakWindowCallbacks = 4096;

 private:
  AudioRenderer* renderer_;
  std::atomic<std::uint64_t> callbacks_{0};
  std::atomic<std::uint64_t> frames_{0};
  std::atomic<std::uint64_t> xruns_{0};
  std::atomic<std::int64_t> last_ns_{0};
  std::atomic<std::int64_t> max_ns_{0};
  std::atomic<std::int64_t> heartbeat_ns_{0};
  std::atomic<int> warm_up_left_{kWarmUpCallbacks};
  std::atomic<std::int64_t> mean_ns_{0};
  std::atomic<std::int64_t> window_max_ns_{0};
  std::atomic<std::int64_t> last_window_max_ns_{0};
  double mean_state_ns_ = -1.0;  // audio thread only; < 0 until the first measured callback
  std::uint32_t in_window_ = 0;  // audio thread only
};

// One open stream on some device; the supervisor owns it. Open/Close run on the control thread.
class AudioStreamBackend {
 public:
  virtual ~AudioStreamBackend() = default;
  virtual const char* Name() const = 0;
  // Opens and starts the stream feeding `core`. False with a human `error` (never throws: it is
  // called again on every reopen attempt).
  virtual bool Open(const AudioOutputConfig& config, AudioCallbackCore& core,
                    std::string* error) = 0;
  virtual void Close() = 0;
  // Closes a stream whose device is gone or stuck: drops pending buffers instead of waiting.
  virtual void Abort() { Close(); }
  // False once the device has gone (stream stopped by an error, device vanished).
  virtual bool Healthy() = 0;
};

class AudioOutput {
 public:
  virtual ~AudioOutput() = default;
  // Tries to open the device. False when it is not there (status "missing", one log line naming
  // the available devices); Poll() keeps retrying, the kiosk runs silent meanwhile.
  virtual bool Start() = 0;
  virtual void Stop() = 0;
  // Control-thread supervision: detects a lost device and reopens with back-off. `now_ns` is
  // CLOCK_MONOTONIC (MonotonicNowNs()); tests advance it by hand from there.
  virtual void Poll(std::int64_t now_ns) = 0;
  virtual bool Running() const = 0;
  virtual AudioCallbackStats Stats() const = 0;
};

// Supervises any AudioStreamBackend: status board entry `device_key` (default "audio_out").
class SupervisedAudioOutput final : public AudioOutput {
 public:
  SupervisedAudioOutput(std::unique_ptr<AudioStreamBackend> backend, AudioRenderer& renderer,
                        AudioOutputConfig config, DeviceStatusBoard& board,
                        std::string device_key = "audio_out");
  ~SupervisedAudioOutput() override;
  SupervisedAudioOutput(const SupervisedAudioOutput&) = delete;
  SupervisedAudioOutput& operator=(const SupervisedAudioOutput&) = delete;

  bool Start() override;
  void Stop() override;
  void Poll(std::int64_t now_ns) override;
  bool Running() const override { return running_; }
  AudioCallbackStats Stats() const override { return core_.Stats(); }
  // Seconds until the next reopen attempt (0 while running): for the staff panel and tests.
  double NextRetryInS(std::int64_t now_ns) const;

 private:
  bool TryOpen(std::int64_t now_ns, std::string* error);
  // New xruns since the last line: the first one's warning at once, then one line per interval.
  void LogXruns(const AudioCallbackStats& stats, std::int64_t now_ns);

  std::unique_ptr<AudioStreamBackend> backend_;
  AudioCallbackCore core_;
  AudioOutputConfig config_;
  DeviceStatusBoard* board_;
  std::string key_;
  bool running_ = false;
  bool ever_opened_ = false;
  bool stopped_ = true;
  double backoff_s_ = 0.0;
  std::int64_t next_retry_ns_ = 0;
  std::uint64_t last_callbacks_ = 0;
  std::int64_t last_progress_ns_ = 0;
  std::int64_t opened_at_ns_ = 0;
  std::uint64_t xruns_reported_ = 0;
  bool xrun_logged_ = false;  // the first xrun's warning was written
  std::int64_t last_xrun_log_ns_ = 0;
};

// PortAudio backend (ALSA). Each Open re-initialises PortAudio so that a replugged USB device is
// seen again (PortAudio 19.6 scans devices only in Pa_Initialize).
std::unique_ptr<AudioStreamBackend> MakePortAudioOutputBackend();

// The product's audio output: SupervisedAudioOutput over PortAudio.
std::unique_ptr<AudioOutput> MakePortAudioOutput(AudioRenderer& renderer,
                                                 const AudioOutputConfig& config,
                                                 DeviceStatusBoard& board);

// Runs the same callback core in a loop into memory: no device, no thread, no clock.
class OfflineAudioOutput final : public AudioOutput {
 public:
  OfflineAudioOutput(AudioRenderer& renderer, AudioOutputConfig config);
  bool Start() override;
  void Stop() override { running_ = false; }
  void Poll(std::int64_t /*now_ns*/) override {}
  bool Running() const override { return running_; }
  AudioCallbackStats Stats() const override { return core_.Stats(); }

  // Renders `blocks` callbacks of frames_per_buffer frames and appends them to the buffer.
  void RenderBlocks(int blocks);
  const std::vector<float>& buffer() const { return buffer_; }
  void ClearBuffer() { buffer_.clear(); }

 private:
  AudioCallbackCore core_;
  AudioOutputConfig config_;
  std::vector<float> block_;
  std::vector<float> buffer_;
  bool running_ = false;
};

}  // namespace sas::platform
