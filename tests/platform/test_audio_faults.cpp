// Audio output supervision through the fake device: lost mid-stroke, silent meanwhile, reopened
// with back-off when it returns; one log line per state change; the offline renderer runs the
// same callback core.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "platform/audio/audio_input.h"
#include "platform/audio/audio_output.h"
#include "platform/audio/fake_audio_backend.h"
#include "platform/common/clock.h"
#include "support/smaps.h"

using namespace sas::platform;

namespace {

constexpr std::int64_t kMs = 1'000'000;

// A "stroke": a running ramp on ch 1 and its negative on ch 2, so every rendered frame is
// distinguishable and the renderer's progress is visible.
class RampRenderer final : public AudioRenderer {
 public:
  void Render(float* out, int frames, int channels) noexcept override {
    for (int i = 0; i < frames; ++i) {
      const float v = static_cast<float>(n_++) * 1e-4f;
      out[i * channels] = v;
      out[i * channels + 1] = -v;
    }
  }
  long rendered() const { return n_; }

 private:
  long n_ = 1;
};

}  // namespace

TEST_CASE("audio device lost mid-stroke and back: lost once, silent, reopened with back-off",
          "[platform]") {
  FakeAudioStreamBackend::Shared device;
  RampRenderer renderer;
  Logger logger;
  logger.SetEchoToStderr(false);
  DeviceStatusBoard board(logger);
  AudioOutputConfig config;
  config.reopen_backoff_initial_s = 0.25;
  config.reopen_backoff_max_s = 2.0;
  SupervisedAudioOutput output(std::make_unique<FakeAudioStreamBackend>(device), renderer, config,
                               board);
  REQUIRE(output.Start());
  CHECK(board.Get("audio_out").state == DeviceState::kOk);
  CHECK(logger.Count() == 1);  // "ok: playing on ..."

  std::int64_t now = MonotonicNowNs();
  FakeAudioStreamBackend::Pump(device, 10);  // mid-stroke
  output.Poll(now);
  CHECK(output.Running());
  const long rendered_before = renderer.rendered();

  FakeAudioStreamBackend::Unplug(device);
  output.Poll(now += 10 * kMs);
  CHECK_FALSE(output.Running());
  auto status = board.Get("audio_out");
  CHECK(status.state == DeviceState::kLost);
  CHECK(status.message.find("running silent") != std::string::npos);
  REQUIRE(logger.Count() == 2);
  CHECK(logger.Recent().back().Text().rfind("warn audio_out: lost:", 0) == 0);
  CHECK(device.aborts == 1);  // a gone device is aborted, not drained

  // While away: the renderer is not called, reopen attempts back off 0.25, 0.5, 1, 2, 2 s and
  // log nothing.
  const int attempts_before = device.open_attempts;
  std::vector<std::int64_t> attempt_times;
  for (int step = 0; step < 800; ++step) {  // 8 s in 10 ms control ticks
    now += 10 * kMs;
    const int before = device.open_attempts;
    output.Poll(now);
    if (device.open_attempts != before) attempt_times.push_back(now);
    FakeAudioStreamBackend::Pump(device, 1);
  }
  CHECK(renderer.rendered() == rendered_before);
  CHECK(logger.Count() == 2);
  REQUIRE(attempt_times.size() >= 4);
  CHECK(device.open_attempts - attempts_before == static_cast<int>(attempt_times.size()));
  // Gaps between attempts double up to the cap (within one 10 ms tick).
  std::vector<double> gaps_s;
  for (std::size_t i = 1; i < attempt_times.size(); ++i)
    gaps_s.push_back(static_cast<double>(attempt_times[i] - attempt_times[i - 1]) * 1e-9);
  CHECK(gaps_s[0] == Approx(0.5).margin(0.011));
  CHECK(gaps_s[1] == Approx(1.0).margin(0.011));
  CHECK(gaps_s[2] == Approx(2.0).margin(0.011));
  CHECK(gaps_s.back() == Approx(2.0).margin(0.011));

  FakeAudioStreamBackend::Replug(device);
  for (int step = 0; step < 300 && !output.Running(); ++step) output.Poll(now += 10 * kMs);
  REQUIRE(output.Running());
  status = board.Get("audio_out");
  CHECK(status.state == DeviceState::kOk);
  CHECK(status.reconnects == 1);
  CHECK(logger.Count() == 3);
  CHECK(logger.Recent().back().Text().find("reopened") != std::string::npos);
  FakeAudioStreamBackend::Pump(device, 5);
  CHECK(renderer.rendered() == rendered_before + 5 * config.frames_per_buffer);
}

TEST_CASE("a flapping device (opens, dies at once) is retried with a growing back-off",
          "[platform]") {
  FakeAudioStreamBackend::Shared device;
  RampRenderer renderer;
  Logger logger;
  logger.SetEchoToStderr(false);
  DeviceStatusBoard board(logger);
  AudioOutputConfig config;
  config.reopen_backoff_initial_s = 0.25;
  config.reopen_backoff_max_s = 8.0;
  SupervisedAudioOutput output(std::make_unique<FakeAudioStreamBackend>(device), renderer, config,
                               board);
  REQUIRE(output.Start());
  std::int64_t now = MonotonicNowNs();
  std::vector<std::int64_t> opens;
  for (int step = 0; step < 6000; ++step) {  // 60 s of 10 ms control ticks
    device.healthy = false;                  // dies right after every open
    const int before = device.opens;
    output.Poll(now += 10 * kMs);
    if (device.opens != before) opens.push_back(now);
  }
  REQUIRE(opens.size() >= 5);
  // 0.25 + 0.5 + 1 + 2 + 4 + 8 + 8 ...: about ten reopen cycles a minute, not thousands.
  CHECK(opens.size() <= 12);
  CHECK(static_cast<double>(opens.back() - opens[opens.size() - 2]) * 1e-9 ==
        Approx(8.0).margin(0.03));
}

TEST_CASE("xruns are counted and logged at most once per interval", "[platform]") {
  FakeAudioStreamBackend::Shared device;
  RampRenderer renderer;
  Logger logger;
  logger.SetEchoToStderr(false);
  DeviceStatusBoard board(logger);
  AudioOutputConfig config;
  config.xrun_log_interval_s = 10.0;
  SupervisedAudioOutput output(std::make_unique<FakeAudioStreamBackend>(device), renderer, config,
                               board);
  REQUIRE(output.Start());
  const auto lines0 = logger.Count();
  std::int64_t now = MonotonicNowNs();
  for (int second = 0; second < 25; ++second) {
    FakeAudioStreamBackend::Pump(device, 2, true);  // two xruns every second
    FakeAudioStreamBackend::Pump(device, 10);
    output.Poll(now += 1000 * kMs);
  }
  CHECK(output.Stats().xruns == 50);
  CHECK(board.Get("audio_out").events == 50);
  // Lines at 1 s, 11 s, 21 s.
  REQUIRE(logger.Count() == lines0 + 3);
  CHECK(logger.Recent()[1].Text().rfind("warn audio_out: 2 xruns", 0) == 0);
  CHECK(logger.Recent()[2].Text().rfind("warn audio_out: 20 xruns", 0) == 0);
  CHECK(output.Running());
}

TEST_CASE(
    "xruns on an idle kiosk: one warning at the first, then at most one line a minute with the "
    "count since the last line, every xrun counted once",
    "[platform]") {
  FakeAudioStreamBackend::Shared device;
  RampRenderer renderer;
  Logger logger;
  logger.SetEchoToStderr(false);
  DeviceStatusBoard board(logger);
  SupervisedAudioOutput output(std::make_unique<FakeAudioStreamBackend>(device), renderer,
                               AudioOutputConfig{}, board);  // the kiosk's own settings
  REQUIRE(output.Start());
  const auto lines0 = logger.Count();
  // What the struggling card did: 30 xruns a second (300 per 10 s) for ten minutes, the loop
  // polling every 100 ms on a fake clock; then a quiet minute.
  std::int64_t now = 5'000 * kMs;
  const auto poll_for = [&](int seconds, int xruns_per_poll) {
    for (int i = 0; i < seconds * 10; ++i) {
      FakeAudioStreamBackend::Pump(device, xruns_per_poll, true);
      FakeAudioStreamBackend::Pump(device, 1);
      device.played.clear();
      output.Poll(now += 100 * kMs);
    }
  };
  poll_for(600, 3);
  poll_for(61, 0);
  const std::uint64_t total = 600 * 10 * 3;
  REQUIRE(output.Stats().xruns == total);
  CHECK(board.Get("audio_out").events == total);

  std::vector<LogLine> lines = logger.Recent();
  lines.erase(lines.begin(), lines.end() - static_cast<std::ptrdiff_t>(logger.Count() - lines0));
  INFO(::Catch::Detail::stringify(logger.Count() - lines0) << " lines");
  // The first at once, then one a minute: at 0.1 s, 60.1 s, ..., 600.1 s (the rest, after the
  // xruns stopped).
  REQUIRE(lines.size() == 11);
  CHECK(lines[0].Text().rfind("warn audio_out: 3 xruns (buffer under/overflows); total 3,", 0) ==
        0);
  CHECK_THAT(lines[0].message, Catch::EndsWith("more are summed up at most every 60 s"));
  std::uint64_t said = 0;
  for (const auto& line : lines) {
    INFO(line.Text());
    CHECK(line.level == LogLevel::kWarn);
    said += std::stoull(line.message);
  }
  CHECK(said == total);  // nothing counted twice, nothing left out
  for (std::size_t i = 1; i + 1 < lines.size(); ++i) {
    INFO(lines[i].Text());
    CHECK_THAT(lines[i].message, Catch::StartsWith("1800 xruns (buffer under/overflows) in the "
                                                   "last 60 s; total " +
                                                   std::to_string(3 + 1800 * i) + ","));
  }
  CHECK_THAT(lines.back().message,  // from 540.1 s to the end of the xruns at 600 s
             Catch::StartsWith("1797 xruns (buffer under/overflows) in the last 60 s; total " +
                               std::to_string(total) + ","));

  // A single xrun after a long quiet spell (the last line was at 600.1 s, this is at 901.2 s) is
  // said at once, in the singular.
  poll_for(240, 0);
  FakeAudioStreamBackend::Pump(device, 1, true);
  output.Poll(now += 100 * kMs);
  REQUIRE(logger.Count() == lines0 + 12);
  CHECK_THAT(logger.Recent().back().Text(),
             Catch::StartsWith("warn audio_out: 1 xrun (buffer under/overflow) in the last 301 s"));
}

TEST_CASE("a stalled device (no callbacks) counts as lost", "[platform]") {
  FakeAudioStreamBackend::Shared device;
  RampRenderer renderer;
  Logger logger;
  logger.SetEchoToStderr(false);
  DeviceStatusBoard board(logger);
  AudioOutputConfig config;
  config.stall_timeout_s = 0.5;
  SupervisedAudioOutput output(std::make_unique<FakeAudioStreamBackend>(device), renderer, config,
                               board);
  REQUIRE(output.Start());
  const std::int64_t t0 = MonotonicNowNs();
  output.Poll(t0);
  FakeAudioStreamBackend::Pump(device, 1);
  output.Poll(t0 + 400 * kMs);
  CHECK(output.Running());
  output.Poll(t0 + 901 * kMs);  // 501 ms since the last progress
  CHECK_FALSE(output.Running());
  CHECK(board.Get("audio_out").message.find("no audio callbacks") != std::string::npos);
}

TEST_CASE("offline output runs the same callback in a loop and counts blocks", "[platform]") {
  RampRenderer renderer;
  AudioOutputConfig config;
  config.frames_per_buffer = 64;
  OfflineAudioOutput offline(renderer, config);
  REQUIRE(offline.Start());
  offline.RenderBlocks(10);
  const auto& buffer = offline.buffer();
  REQUIRE(buffer.size() == 10u * 64u * 2u);
  for (std::size_t i = 0; i < buffer.size() / 2; ++i) {
    CHECK(buffer[2 * i] == static_cast<float>(i + 1) * 1e-4f);
    CHECK(buffer[2 * i + 1] == -buffer[2 * i]);
  }
  const auto stats = offline.Stats();
  CHECK(stats.callbacks == 10);
  CHECK(stats.frames == 640);
  CHECK(stats.xruns == 0);
  CHECK(stats.heartbeat_ns > 0);
}

TEST_CASE("voice recorder fills its buffer, meters level and flags clipping and silence",
          "[platform]") {
  VoiceRecorderConfig config;
  config.sample_rate_hz = 8000;
  config.max_duration_s = 0.5;
  FakeAudioInput input(config, 100);
  REQUIRE(input.Start());
  auto& rec = input.recorder();
  std::vector<float> quiet(8000, 1e-4f);  // -80 dBFS
  rec.Arm();
  input.Feed(quiet.data(), quiet.size());
  CHECK_FALSE(rec.Recording());  // stopped by itself at 0.5 s
  auto take = rec.Take();
  CHECK(take.samples.size() == 4000);
  CHECK(take.duration_s == Approx(0.5));
  CHECK(take.silent);
  CHECK_FALSE(take.clipped);

  std::vector<float> loud(1000);
  for (std::size_t i = 0; i < loud.size(); ++i)
    loud[i] = (i == 500 || i == 501) ? -1.0f : 0.5f * std::sin(0.05f * static_cast<float>(i));
  rec.Arm();
  input.Feed(loud.data(), loud.size());
  CHECK(rec.Recording());
  CHECK(rec.Level() > 0.3f);
  rec.Stop();
  take = rec.Take();
  CHECK(take.samples.size() == 1000);
  CHECK(take.clipped);
  CHECK(take.clipped_samples == 2);
  CHECK_FALSE(take.silent);
  CHECK(take.peak == 1.0f);
}

TEST_CASE(
    "voice recorder keeps the take in memory a core dump leaves out, hands it out without a copy "
    "and Wipe zeroes it",
    "[platform]") {
  VoiceRecorderConfig config;
  config.sample_rate_hz = 8000;
  config.max_duration_s = 1.0;
  FakeAudioInput input(config, 100);
  REQUIRE(input.Start());
  auto& rec = input.recorder();
  std::vector<float> voice(4000);
  for (std::size_t i = 0; i < voice.size(); ++i)
    voice[i] = 0.4f * std::sin(0.07f * static_cast<float>(i));
  rec.Arm();
  input.Feed(voice.data(), voice.size());
  rec.Stop();
  const auto take = rec.Take();
  REQUIRE(take.samples.size() == voice.size());
  CHECK(std::equal(take.samples.begin(), take.samples.end(), voice.begin()));
  // The whole capture buffer, not only the take, is in "dd" pages.
  CHECK(sas::test::AllDontDump(
      sas::test::VmFlagsOf(take.samples.data(), rec.Capacity() * sizeof(float))));
  const float* buffer = take.samples.data();
  rec.Wipe();
  CHECK(rec.Take().samples.empty());
  CHECK(std::all_of(buffer, buffer + rec.Capacity(), [](float x) { return x == 0.0f; }));
}
