// The audio output's supervision off the UI thread (platform/audio/background_audio_output.h):
// while a reopen is stuck inside the device (as PortAudio's open sat in ALSA for > 3 s after a
// card vanished), what the UI loop calls still returns; and a device that stays away through many
// supervision rounds and reopen attempts is still one journal line, one more when it returns.
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "platform/audio/background_audio_output.h"
#include "platform/audio/fake_audio_backend.h"
#include "platform/device_status.h"
#include "platform/log/log.h"

using namespace sas::platform;

namespace {

// A device whose open can be made to hang until the test lets it go.
struct Gate {
  std::mutex mutex;
  std::condition_variable changed;
  bool hang = false;
  std::atomic<bool> present{true};
  std::atomic<int> attempts{0};
  std::atomic<int> hanging{0};  // opens waiting at the gate now
};

class HangingBackend final : public AudioStreamBackend {
 public:
  explicit HangingBackend(Gate& gate) : gate_(&gate) {}
  const char* Name() const override { return "hanging"; }
  bool Open(const AudioOutputConfig&, AudioCallbackCore&, std::string* error) override {
    gate_->attempts.fetch_add(1);
    std::unique_lock<std::mutex> lock(gate_->mutex);
    gate_->hanging.fetch_add(1);
    gate_->changed.notify_all();
    gate_->changed.wait(lock, [this] { return !gate_->hang; });
    gate_->hanging.fetch_sub(1);
    if (!gate_->present.load()) {
      if (error) *error = "device gone";
      return false;
    }
    return true;
  }
  void Close() override {}
  bool Healthy() override { return gate_->present.load(); }

 private:
  Gate* gate_;
};

class SilentRenderer final : public AudioRenderer {
 public:
  void Render(float* out, int frames, int channels) noexcept override {
    for (int i = 0; i < frames * channels; ++i) out[i] = 0.0f;
  }
};

}  // namespace

TEST_CASE(
    "background audio output: while a reopen hangs in the device, the UI's calls return at "
    "once, and the output comes back when the device does",
    "[platform][audio][faults]") {
  Gate gate;
  SilentRenderer renderer;
  Logger log;
  log.SetEchoToStderr(false);
  DeviceStatusBoard board(log);
  AudioOutputConfig config;
  config.reopen_backoff_initial_s = 0.01;
  config.reopen_backoff_max_s = 0.02;
  config.stall_timeout_s = 1e6;  // this device never calls back: only Healthy() tells
  BackgroundAudioOutput output(std::make_unique<SupervisedAudioOutput>(
                                   std::make_unique<HangingBackend>(gate), renderer, config, board),
                               0.005);
  REQUIRE(output.Start());
  CHECK(output.Running());

  // The device vanishes and its next open hangs.
  {
    std::lock_guard<std::mutex> lock(gate.mutex);
    gate.hang = true;
  }
  gate.present = false;
  {
    std::unique_lock<std::mutex> lock(gate.mutex);
    REQUIRE(gate.changed.wait_for(lock, std::chrono::seconds(30),
                                  [&] { return gate.hanging.load() > 0; }));
  }
  // The supervision thread is stuck in the device: the UI loop's calls must not wait for it.
  for (int i = 0; i < 1000; ++i) {
    output.Poll(0);
    CHECK_FALSE(output.Running());
    (void)output.Stats();
  }
  CHECK(gate.hanging.load() == 1);  // still stuck: the calls above did not wait it out

  // The device returns.
  gate.present = true;
  {
    std::lock_guard<std::mutex> lock(gate.mutex);
    gate.hang = false;
  }
  gate.changed.notify_all();
  for (int i = 0; i < 3000 && !output.Running(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  CHECK(output.Running());
  output.Stop();
  CHECK_FALSE(output.Running());
}

namespace {

int AudioOutLines(const Logger& log) {
  int n = 0;
  for (const auto& line : log.Recent()) n += line.component == "audio_out" ? 1 : 0;
  return n;
}

// Waits (for the supervision thread) until `done`, at most 30 s.
template <typename Done>
bool WaitUntil(Done done) {
  for (int i = 0; i < 3000 && !done(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return done();
}

}  // namespace

TEST_CASE(
    "background audio output: a device gone through dozens of reopen attempts is one warning "
    "line, and its return one info line, not one per attempt, round or callback",
    "[platform][audio][faults]") {
  ThreadedFakeAudioStreamBackend::Shared device;
  SilentRenderer renderer;
  Logger log;
  log.SetEchoToStderr(false);
  DeviceStatusBoard board(log);
  AudioOutputConfig config;
  config.reopen_backoff_initial_s = 0.005;
  config.reopen_backoff_max_s = 0.01;
  config.stall_timeout_s = 1e6;  // loss is seen through Healthy(), not a stall
  BackgroundAudioOutput output(
      std::make_unique<SupervisedAudioOutput>(
          std::make_unique<ThreadedFakeAudioStreamBackend>(device), renderer, config, board),
      0.002);
  REQUIRE(output.Start());
  REQUIRE(WaitUntil([&] { return device.blocks.load() > 10; }));  // callbacks run
  const int at_start = AudioOutLines(log);
  CHECK(at_start == 1);  // "ok" at the first open

  device.present = false;
  const int attempts_before = device.open_attempts.load();
  const std::uint64_t rounds_before = output.rounds();
  REQUIRE(WaitUntil([&] {
    return device.open_attempts.load() >= attempts_before + 30 &&
           output.rounds() >= rounds_before + 60;
  }));
  CHECK_FALSE(output.Running());
  CHECK(board.Get("audio_out").state == DeviceState::kLost);
  CHECK(AudioOutLines(log) == at_start + 1);
  CHECK(log.Recent().back().level == LogLevel::kWarn);

  device.present = true;
  REQUIRE(WaitUntil([&] { return output.Running(); }));
  const std::uint64_t blocks = device.blocks.load();
  REQUIRE(WaitUntil([&] { return device.blocks.load() > blocks + 10; }));
  CHECK(board.Get("audio_out").state == DeviceState::kOk);
  CHECK(AudioOutLines(log) == at_start + 2);
  CHECK(log.Recent().back().Text().find("info audio_out: ok: reopened") == 0);
  output.Stop();
}
