// Callback core, supervisor with back-off, offline renderer (see audio_output.h).
#include "platform/audio/audio_output.h"

#include <algorithm>
#include <cmath>

#include "platform/common/clock.h"

namespace sas::platform {

void AudioCallbackCore::Run(float* interleaved, int frames, int channels, bool xrun) noexcept {
  const std::int64_t start_ns = MonotonicNowNs();
  renderer_->Render(interleaved, frames, channels);
  const std::int64_t end_ns = MonotonicNowNs();
  const std::int64_t took_ns = end_ns - start_ns;
  // Only this thread writes the counters: relaxed load + store, no read-modify-write contention.
  callbacks_.store(callbacks_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
  frames_.store(frames_.load(std::memory_order_relaxed) + static_cast<std::uint64_t>(frames),
                std::memory_order_relaxed);
  if (xrun) xruns_.store(xruns_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
  last_ns_.store(took_ns, std::memory_order_relaxed);
  if (took_ns > max_ns_.load(std::memory_order_relaxed))
    max_ns_.store(took_ns, std::memory_order_relaxed);
  if (const int warm = warm_up_left_.load(std::memory_order_relaxed); warm > 0) {
    warm_up_left_.store(warm - 1, std::memory_order_relaxed);
  } else {
    // Mean over about 375 callbacks (1 s at 128 frames, 48 kHz); the peak over two windows.
    constexpr double kMeanWeight = 1.0 / 375.0;
    const auto took = static_cast<double>(took_ns);
    mean_state_ns_ =
        mean_state_ns_ < 0.0 ? took : mean_state_ns_ + (took - mean_state_ns_) * kMeanWeight;
    mean_ns_.store(static_cast<std::int64_t>(mean_state_ns_), std::memory_order_relaxed);
    if (++in_window_ > kPeakWindowCallbacks) {
      last_window_max_ns_.store(window_max_ns_.load(std::memory_order_relaxed),
                                std::memory_order_relaxed);
      window_max_ns_.store(0, std::memory_order_relaxed);
      in_window_ = 1;
    }
    if (took_ns > window_max_ns_.load(std::memory_order_relaxed))
      window_max_ns_.store(took_ns, std::memory_order_relaxed);
  }
  heartbeat_ns_.store(end_ns, std::memory_order_release);
}

AudioCallbackStats AudioCallbackCore::Stats() const noexcept {
  AudioCallbackStats s;
  s.heartbeat_ns = heartbeat_ns_.load(std::memory_order_acquire);
  s.callbacks = callbacks_.load(std::memory_order_relaxed);
  s.frames = frames_.load(std::memory_order_relaxed);
  s.xruns = xruns_.load(std::memory_order_relaxed);
  s.last_callback_ns = last_ns_.load(std::memory_order_relaxed);
  s.max_callback_ns = max_ns_.load(std::memory_order_relaxed);
  s.mean_callback_ns = mean_ns_.load(std::memory_order_relaxed);
  s.recent_max_callback_ns = std::max(window_max_ns_.load(std::memory_order_relaxed),
                                      last_window_max_ns_.load(std::memory_order_relaxed));
  return s;
}

SupervisedAudioOutput::SupervisedAudioOutput(std::unique_ptr<AudioStreamBackend> backend,
                                             AudioRenderer& renderer, AudioOutputConfig config,
                                             DeviceStatusBoard& board, std::string device_key)
    : backend_(std::move(backend)),
      core_(renderer),
      config_(std::move(config)),
      board_(&board),
      key_(std::move(device_key)) {}

SupervisedAudioOutput::~SupervisedAudioOutput() {
  Stop();
}

bool SupervisedAudioOutput::TryOpen(std::int64_t now_ns, std::string* error) {
  core_.Opening();
  if (!backend_->Open(config_, core_, error)) return false;
  running_ = true;
  last_callbacks_ = core_.Stats().callbacks;
  last_progress_ns_ = now_ns;
  opened_at_ns_ = now_ns;
  return true;
}

namespace {

std::string Describe(const AudioOutputConfig& c, const char* backend) {
  return std::string(backend) + " '" + c.device + "' " + std::to_string(c.channels) + " ch " +
         std::to_string(c.sample_rate_hz) + " Hz, " + std::to_string(c.frames_per_buffer) +
         "-frame buffer";
}

}  // namespace

bool SupervisedAudioOutput::Start() {
  stopped_ = false;
  std::string error;
  const std::int64_t now_ns = MonotonicNowNs();
  if (TryOpen(now_ns, &error)) {
    ever_opened_ = true;
    board_->Set(key_, DeviceState::kOk, "playing on " + Describe(config_, backend_->Name()),
                backend_->Name());
    return true;
  }
  board_->AddFailure(key_);
  board_->Set(key_, DeviceState::kMissing, error + "; running silent, retrying", backend_->Name());
  backoff_s_ = config_.reopen_backoff_initial_s;
  next_retry_ns_ = now_ns + static_cast<std::int64_t>(backoff_s_ * 1e9);
  return false;
}

void SupervisedAudioOutput::Stop() {
  if (running_) backend_->Close();
  running_ = false;
  stopped_ = true;
}

double SupervisedAudioOutput::NextRetryInS(std::int64_t now_ns) const {
  if (running_ || stopped_) return 0.0;
  return std::max(0.0, static_cast<double>(next_retry_ns_ - now_ns) * 1e-9);
}

void SupervisedAudioOutput::LogXruns(const AudioCallbackStats& stats, std::int64_t now_ns) {
  // Rate-limited: a struggling machine must not flood the journal from the control loop. The
  // first xrun is said at once; later ones wait for the interval and are summed up in one line.
  const auto interval_ns = static_cast<std::int64_t>(config_.xrun_log_interval_s * 1e9);
  if (xrun_logged_ && now_ns - last_xrun_log_ns_ < interval_ns) return;
  const std::uint64_t count = stats.xruns - xruns_reported_;
  std::string line = std::to_string(count) + (count == 1 ? " xrun (buffer under/overflow)"
                                                         : " xruns (buffer under/overflows)");
  if (xrun_logged_) {
    line += " in the last " + std::to_string((now_ns - last_xrun_log_ns_) / 1'000'000'000) + " s";
  }
  line += "; total " + std::to_string(stats.xruns) + ", slowest callback " +
          std::to_string(stats.max_callback_ns / 1000) + " us";
  if (!xrun_logged_) {
    line += "; more are summed up at most every " +
            std::to_string(static_cast<long>(config_.xrun_log_interval_s)) + " s";
  }
  board_->logger().Warn(key_, line);
  xruns_reported_ = stats.xruns;
  xrun_logged_ = true;
  last_xrun_log_ns_ = now_ns;
}

void SupervisedAudioOutput::Poll(std::int64_t now_ns) {
  if (stopped_) return;
  if (running_) {
    const AudioCallbackStats stats = core_.Stats();
    board_->SetEvents(key_, stats.xruns);
    if (stats.callbacks != last_callbacks_) {
      last_callbacks_ = stats.callbacks;
      last_progress_ns_ = now_ns;
    }
    const bool stalled =
        now_ns - last_progress_ns_ > static_cast<std::int64_t>(config_.stall_timeout_s * 1e9);
    if (stats.xruns != xruns_reported_) LogXruns(stats, now_ns);
    if (backend_->Healthy() && !stalled) return;
    backend_->Abort();
    running_ = false;
    board_->AddFailure(key_);
    // A device that opens and dies again at once (flapping) keeps its growing back-off; one that
    // played for reopen_stable_s starts over from the initial delay.
    const bool flapping =
        now_ns - opened_at_ns_ < static_cast<std::int64_t>(config_.reopen_stable_s * 1e9);
    backoff_s_ = (flapping && backoff_s_ > 0.0)
                     ? std::min(config_.reopen_backoff_max_s, backoff_s_ * 2.0)
                     : config_.reopen_backoff_initial_s;
    next_retry_ns_ = now_ns + static_cast<std::int64_t>(backoff_s_ * 1e9);
    board_->Set(
        key_, DeviceState::kLost,
        std::string(stalled ? "no audio callbacks for " : "stream stopped: ") +
            (stalled ? std::to_string(static_cast<int>(config_.stall_timeout_s * 1000)) + " ms"
                     : "device gone") +
            "; running silent, reopening with back-off",
        backend_->Name());
    return;
  }
  if (now_ns < next_retry_ns_) return;
  std::string error;
  if (TryOpen(now_ns, &error)) {
    if (ever_opened_) board_->AddReconnect(key_);
    board_->Set(key_, DeviceState::kOk,
                std::string(ever_opened_ ? "reopened " : "playing on ") +
                    Describe(config_, backend_->Name()),
                backend_->Name());
    ever_opened_ = true;
    return;
  }
  // Failed retries do not log again (the state stays lost/missing); they only count and back off.
  board_->AddFailure(key_);
  backoff_s_ = std::min(config_.reopen_backoff_max_s,
                        std::max(config_.reopen_backoff_initial_s, backoff_s_ * 2.0));
  next_retry_ns_ = now_ns + static_cast<std::int64_t>(backoff_s_ * 1e9);
}

OfflineAudioOutput::OfflineAudioOutput(AudioRenderer& renderer, AudioOutputConfig config)
    : core_(renderer), config_(std::move(config)) {
  block_.resize(static_cast<std::size_t>(config_.frames_per_buffer * config_.channels));
}

bool OfflineAudioOutput::Start() {
  running_ = true;
  return true;
}

void OfflineAudioOutput::RenderBlocks(int blocks) {
  // Geometric growth: callers render one block at a time (the headless visit interleaves input),
  // and an exact reserve per call would copy the whole buffer every block.
  const std::size_t needed = buffer_.size() + block_.size() * static_cast<std::size_t>(blocks);
  if (needed > buffer_.capacity()) buffer_.reserve(std::max(needed, 2 * buffer_.capacity()));
  for (int b = 0; b < blocks; ++b) {
    core_.Run(block_.data(), config_.frames_per_buffer, config_.channels, false);
    buffer_.insert(buffer_.end(), block_.begin(), block_.end());
  }
}

}  // namespace sas::platform
