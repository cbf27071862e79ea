// The real PortAudio path (ALSA host API) with no sound card: ALSA's file plugin records what the
// stream played and plays a prepared file into the capture stream. Checks bit-exact transport of a
// rendered 2-channel signal, bit-exact recording of a known input, and device choice by name.
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <fstream>
#include <thread>

#include "alsa_file_config.h"
#include "platform/audio/audio_input.h"
#include "platform/audio/audio_output.h"
#include "platform/common/clock.h"

namespace {

using sas::platform::AudioOutputConfig;
using sas::platform::DeviceState;
using sas::platform::DeviceStatusBoard;
using sas::platform::Logger;

constexpr double kPi = 3.14159265358979323846;

// A deterministic stroke-like test signal: a linear chirp 200 Hz -> 4 kHz on ch 1 (speaker) and a
// 120 Hz tone with a different amplitude on ch 2 (transducer); cosine start so sample 0 is
// non-zero and the start can be located after the device's leading silence.
std::vector<float> RenderTestSignal(int frames, int rate_hz) {
  std::vector<float> out(static_cast<std::size_t>(frames) * 2);
  const double duration_s = static_cast<double>(frames) / rate_hz;
  for (int i = 0; i < frames; ++i) {
    const double t = static_cast<double>(i) / rate_hz;
    const double phase = 2 * kPi * (200.0 * t + 0.5 * (4000.0 - 200.0) / duration_s * t * t);
    out[2 * static_cast<std::size_t>(i)] = static_cast<float>(0.5 * std::cos(phase));
    out[2 * static_cast<std::size_t>(i) + 1] =
        static_cast<float>(0.25 * std::cos(2 * kPi * 120.0 * t));
  }
  return out;
}

// Plays a prepared buffer once, then silence; the renderer a kiosk test would replace by the
// synth Scene.
class BufferRenderer final : public sas::platform::AudioRenderer {
 public:
  explicit BufferRenderer(const std::vector<float>& signal) : signal_(signal) {}
  void Render(float* out, int frames, int channels) noexcept override {
    const std::size_t n = static_cast<std::size_t>(frames * channels);
    for (std::size_t i = 0; i < n; ++i) out[i] = pos_ < signal_.size() ? signal_[pos_++] : 0.0f;
  }
  std::size_t position() const { return pos_; }

 private:
  const std::vector<float>& signal_;
  std::size_t pos_ = 0;
};

template <typename Pred>
bool WaitFor(Pred pred, double timeout_s = 10.0) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!pred()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

}  // namespace

TEST_CASE("PortAudio output delivers the rendered 2-channel signal bit-exactly to the ALSA device",
          "[platform]") {
  sas::test::AlsaFileConfig alsa;
  constexpr int kRate = 48000;
  constexpr int kFrames = 24000;  // 0.5 s
  const auto signal = RenderTestSignal(kFrames, kRate);
  BufferRenderer renderer(signal);
  Logger logger;
  logger.SetEchoToStderr(false);
  DeviceStatusBoard board(logger);
  AudioOutputConfig config;
  config.device = "kiosk_out";
  auto output = sas::platform::MakePortAudioOutput(renderer, config, board);
  REQUIRE(output->Start());
  CHECK(board.Get("audio_out").state == DeviceState::kOk);
  // Render the whole signal plus a few blocks so it has been handed to ALSA before stopping.
  REQUIRE(WaitFor([&] { return output->Stats().frames >= kFrames + 8 * 128; }));
  output->Stop();
  const auto stats = output->Stats();
  CHECK(stats.callbacks > 0);
  CHECK(stats.max_callback_ns > 0);

  const auto played = alsa.ReadPlayed();
  REQUIRE(played.size() >= signal.size());
  std::size_t lead = 0;
  while (lead < played.size() && played[lead] == 0.0f) ++lead;
  INFO("leading silence samples: " << lead);
  CHECK(lead % 2 == 0);  // whole frames: channel order preserved
  REQUIRE(played.size() - lead >= signal.size());
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < signal.size(); ++i) mismatches += played[lead + i] != signal[i];
  CHECK(mismatches == 0);
  // After the signal the renderer wrote zeros, and the device got them.
  CHECK(played[lead + signal.size()] == 0.0f);
}

TEST_CASE("PortAudio capture records the known input file sample for sample", "[platform]") {
  sas::test::AlsaFileConfig alsa;
  constexpr int kRate = 48000;
  // 2 s of input (longer than the 0.5 s take: the file plugin repeats stale data at its end).
  std::vector<float> input(2 * kRate);
  for (std::size_t i = 0; i < input.size(); ++i) {
    const double t = static_cast<double>(i) / kRate;
    input[i] = static_cast<float>(0.3 * std::sin(2 * kPi * 330.0 * t) +
                                  0.1 * std::sin(2 * kPi * 1234.0 * t + 0.3));
  }
  alsa.WriteCaptureInput(input);
  Logger logger;
  logger.SetEchoToStderr(false);
  DeviceStatusBoard board(logger);
  sas::platform::AudioInputConfig config;
  config.device = "kiosk_in";
  sas::platform::VoiceRecorderConfig recorder_config;
  recorder_config.max_duration_s = 0.5;
  auto in = sas::platform::MakePortAudioInput(config, recorder_config, board);
  in->recorder().Arm();
  REQUIRE(in->Start());
  CHECK(board.Get("audio_in").state == DeviceState::kOk);
  REQUIRE(WaitFor([&] { return !in->recorder().Recording(); }));
  in->Stop();
  const auto take = in->recorder().Take();
  REQUIRE(take.samples.size() == static_cast<std::size_t>(kRate / 2));
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < take.samples.size(); ++i) mismatches += take.samples[i] != input[i];
  CHECK(mismatches == 0);
  CHECK_FALSE(take.clipped);
  CHECK_FALSE(take.silent);
  // RMS of the two sines: sqrt((0.3^2 + 0.1^2) / 2).
  CHECK(take.rms_dbfs == Approx(20 * std::log10(std::sqrt((0.09 + 0.01) / 2))).margin(0.05));
}

TEST_CASE("an unknown output device name fails with a line listing the available devices",
          "[platform]") {
  sas::test::AlsaFileConfig alsa;
  std::vector<float> nothing;
  BufferRenderer renderer(nothing);
  Logger logger;
  logger.SetEchoToStderr(false);
  DeviceStatusBoard board(logger);
  AudioOutputConfig config;
  config.device = "no_such_card";
  auto output = sas::platform::MakePortAudioOutput(renderer, config, board);
  CHECK_FALSE(output->Start());
  const auto status = board.Get("audio_out");
  CHECK(status.state == DeviceState::kMissing);
  CHECK(status.message.find("'no_such_card' not found") != std::string::npos);
  CHECK(status.message.find("'kiosk_out'") != std::string::npos);
  const auto lines = logger.Recent();
  REQUIRE(lines.size() == 1);
  CHECK(lines[0].level == sas::platform::LogLevel::kWarn);
  CHECK(lines[0].Text().rfind("warn audio_out: missing: output device 'no_such_card' not found",
                              0) == 0);
}

namespace {

// A ramp renderer: every sample value tells which frame it was, so a device's recording shows
// whether playback resumed as one contiguous stream.
class CountingRenderer final : public sas::platform::AudioRenderer {
 public:
  void Render(float* out, int frames, int channels) noexcept override {
    for (int i = 0; i < frames; ++i) {
      n_ = n_ % 100000 + 1;
      for (int c = 0; c < channels; ++c) out[i * channels + c] = static_cast<float>(n_) * 1e-5f;
    }
  }

 private:
  int n_ = 0;
};

}  // namespace

TEST_CASE("real PortAudio output: device fails mid-stream, disappears, returns and is reopened",
          "[platform]") {
  sas::test::TempDir dir;
  const std::string out = dir.file("out.raw");
  int generation = 0;
  // ALSA re-reads its configuration when the file list changes: each phase gets a new file.
  auto use_config = [&](const std::string& text) {
    const auto path = dir.Write("asound" + std::to_string(++generation) + ".conf",
                                "pcm.null { type null }\n" + text);
    setenv("ALSA_CONFIG_PATH", path.c_str(), 1);
  };
  // Debian's PortAudio 19.6 aborts in Pa_Initialize when no `default` PCM exists: always define
  // one.
  const std::string default_pcm = "pcm.!default { type plug slave.pcm \"null\" }\n";
  // Phase 1: the device accepts the stream, then every write fails (as a yanked USB card does).
  use_config("pcm.kiosk_out { type file slave.pcm \"null\" file \"/dev/full\" format \"raw\" }\n" +
             default_pcm);
  CountingRenderer renderer;
  Logger logger;
  logger.SetEchoToStderr(false);
  DeviceStatusBoard board(logger);
  AudioOutputConfig config;
  config.device = "kiosk_out";
  config.reopen_backoff_initial_s = 0.01;
  config.reopen_backoff_max_s = 0.02;
  auto output = sas::platform::MakePortAudioOutput(renderer, config, board);
  REQUIRE(output->Start());
  REQUIRE(WaitFor([&] {
    output->Poll(sas::platform::MonotonicNowNs());
    return !output->Running();
  }));
  CHECK(board.Get("audio_out").state == DeviceState::kLost);
  CHECK(logger.Count() == 2);  // ok, lost

  // Phase 2: the device is gone; reopen attempts fail quietly (no new log lines).
  use_config(default_pcm);
  // Waits for the third failed attempt, not for a span of time: a busy host polls less often.
  CHECK(WaitFor([&] {
    output->Poll(sas::platform::MonotonicNowNs());
    return board.Get("audio_out").failures >= 3;
  }));
  CHECK_FALSE(output->Running());
  CHECK(logger.Count() == 2);

  // Phase 3: the device is back.
  use_config("pcm.kiosk_out { type file slave.pcm \"null\" file \"" + out +
             "\" format \"raw\" }\n" + default_pcm);
  REQUIRE(WaitFor([&] {
    output->Poll(sas::platform::MonotonicNowNs());
    return output->Running();
  }));
  const auto status = board.Get("audio_out");
  CHECK(status.state == DeviceState::kOk);
  CHECK(status.reconnects == 1);
  CHECK(logger.Count() == 3);
  const auto frames_at_reopen = output->Stats().frames;
  REQUIRE(WaitFor([&] { return output->Stats().frames > frames_at_reopen + 48000; }));
  output->Stop();
  unsetenv("ALSA_CONFIG_PATH");

  // The returned device received the renderer's stream, contiguous (steps of one frame).
  std::ifstream f(out, std::ios::binary | std::ios::ate);
  const auto bytes = static_cast<std::size_t>(f.tellg());
  std::vector<float> played(bytes / sizeof(float));
  f.seekg(0);
  f.read(reinterpret_cast<char*>(played.data()), static_cast<std::streamsize>(bytes));
  std::size_t lead = 0;
  while (lead < played.size() && played[lead] == 0.0f) ++lead;
  REQUIRE(played.size() - lead > 2 * 48000);
  std::size_t breaks = 0;
  for (std::size_t i = lead + 2; i + 1 < played.size(); i += 2) {
    const long a = std::lround(played[i - 2] * 1e5f);
    const long b = std::lround(played[i] * 1e5f);
    breaks += (b != a + 1 && !(a == 100000 && b == 1)) || played[i + 1] != played[i];
  }
  CHECK(breaks == 0);
}
