// Token switches: the debouncer's state machine, the GPIO event thread driven through a fake fd
// source (the real processing code, only the fds faked), MCP2221A report decoding from
// datasheet-format bytes, adapter unplug/replug, keyboard, selection rule, and the fallback when
// the GPIO chip is absent.
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <thread>
#include <vector>

#include "platform/common/clock.h"
#include "platform/gpio/gpio_chips.h"
#include "platform/gpio/gpio_switches.h"
#include "platform/hid/mcp2221.h"
#include "platform/input/debouncer.h"
#include "platform/input/switch_factory.h"
#include "platform/input/token_selector.h"

using namespace sas::platform;

namespace {

constexpr std::int64_t kMs = 1'000'000;

struct Collect {
  std::vector<SwitchEvent>* out;
  void operator()(const SwitchEvent& e) const { out->push_back(e); }
};

// A GPIO "chip" whose event fd is a pipe: the test writes RawEdge records, the real
// GpioSwitchInput thread polls the read end exactly as it polls libgpiod's line fds.
class PipeEventSource final : public GpioEventSource {
 public:
  explicit PipeEventSource(std::array<bool, kSwitchInputCount> initial_high)
      : initial_(initial_high) {
    REQUIRE(pipe2(fds_, O_CLOEXEC | O_NONBLOCK) == 0);
  }
  ~PipeEventSource() override {
    close(fds_[0]);
    close(fds_[1]);
  }
  int write_fd() const { return fds_[1]; }
  std::vector<pollfd> Fds() const override { return {{fds_[0], POLLIN, 0}}; }
  bool Read(const std::vector<pollfd>& ready, std::vector<RawEdge>& out) override {
    if ((ready[0].revents & POLLIN) == 0) return true;
    RawEdge edge;
    while (read(fds_[0], &edge, sizeof edge) == static_cast<ssize_t>(sizeof edge))
      out.push_back(edge);
    return true;
  }
  std::array<bool, kSwitchInputCount> InitialLevels() override { return initial_; }
  std::string Describe() const override { return "pipe"; }

 private:
  int fds_[2] = {-1, -1};
  std::array<bool, kSwitchInputCount> initial_;
};

void WriteEdges(int fd, const std::vector<RawEdge>& edges) {
  // One write (well under PIPE_BUF): the thread may see them in one batch or several.
  const auto bytes = static_cast<ssize_t>(edges.size() * sizeof(RawEdge));
  REQUIRE(write(fd, edges.data(), static_cast<std::size_t>(bytes)) == bytes);
}

std::vector<SwitchEvent> PopUntil(SwitchInput& input, std::size_t count, double timeout_s = 5.0) {
  std::vector<SwitchEvent> events;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  SwitchEvent e;
  while (events.size() < count && std::chrono::steady_clock::now() < deadline) {
    if (input.Pop(e))
      events.push_back(e);
    else
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return events;
}

}  // namespace

TEST_CASE("debouncer turns a chattering press into one event at the first edge", "[platform]") {
  Debouncer d(30 * kMs);
  std::vector<SwitchEvent> out;
  Collect sink{&out};
  // Contact bounces for 6 ms, then stays closed.
  const std::int64_t t0 = 1000 * kMs;
  for (int i = 0; i < 7; ++i) d.Feed(1, i % 2 == 0, t0 + i * kMs, sink);
  d.Advance(t0 + 6 * kMs + 29 * kMs, sink);
  CHECK(out.empty());  // 29 ms of quiet is not enough
  d.Advance(t0 + 6 * kMs + 30 * kMs, sink);
  REQUIRE(out.size() == 1);
  CHECK(out[0].input == 1);
  CHECK(out[0].pressed);
  CHECK(out[0].time_ns == t0);
}

TEST_CASE("debouncer ignores a glitch shorter than the debounce time", "[platform]") {
  Debouncer d(30 * kMs);
  std::vector<SwitchEvent> out;
  Collect sink{&out};
  d.Feed(2, true, 0, sink);
  d.Feed(2, false, 20 * kMs, sink);
  d.Advance(500 * kMs, sink);
  CHECK(out.empty());
  CHECK_FALSE(d.Stable(2));
  CHECK(d.NextDeadlineNs() == -1);
}

TEST_CASE("debouncer keeps inputs independent and reports the deadline for poll", "[platform]") {
  Debouncer d(30 * kMs);
  std::vector<SwitchEvent> out;
  Collect sink{&out};
  d.Feed(0, true, 0, sink);
  d.Feed(3, true, 10 * kMs, sink);
  CHECK(d.NextDeadlineNs() == 30 * kMs);
  // An edge at 35 ms first commits input 0 (quiet since 0), leaving input 3 pending.
  d.Feed(4, true, 35 * kMs, sink);
  REQUIRE(out.size() == 1);
  CHECK(out[0].input == 0);
  CHECK(d.NextDeadlineNs() == 40 * kMs);
  d.Advance(65 * kMs, sink);
  REQUIRE(out.size() == 3);
  CHECK(out[1].input == 3);
  CHECK(out[2].input == 4);
  CHECK(out[2].time_ns == 35 * kMs);
}

TEST_CASE("GPIO event thread debounces edges read from the line fds (active low, both edges)",
          "[platform]") {
  auto initial = std::array<bool, kSwitchInputCount>{true, true, true, false, true};  // 3 closed
  auto source = std::make_unique<PipeEventSource>(initial);
  const int fd = source->write_fd();
  GpioSwitchConfig config;
  GpioSwitchInput input(config, std::move(source));
  std::string error;
  REQUIRE(input.Start(&error));
  CHECK(input.InitiallyPressed(3));
  // Token 4 already on its switch at start is reported as placed.
  auto events = PopUntil(input, 1);
  REQUIRE(events.size() == 1);
  CHECK(events[0].input == 3);
  CHECK(events[0].pressed);

  // All in the past: the whole sequence resolves as soon as the thread reads it.
  const std::int64_t base = MonotonicNowNs() - 1000 * kMs;
  const std::vector<RawEdge> edges = {
      {base, 0, false},           // token 1 placed (line pulled low)...
      {base + 2 * kMs, 0, true},  // ...bouncing
      {base + 4 * kMs, 0, false},
      {base + 100 * kMs, 2, false},  // 10 ms glitch on switch 3: ignored
      {base + 110 * kMs, 2, true},
      {base + 300 * kMs, 0, true},  // token 1 lifted, with chatter
      {base + 301 * kMs, 0, false},
      {base + 303 * kMs, 0, true},
      {base + 400 * kMs, 4, false},  // record button down
  };
  WriteEdges(fd, edges);
  events = PopUntil(input, 3);
  REQUIRE(events.size() == 3);
  CHECK(events[0].input == 0);
  CHECK(events[0].pressed);
  CHECK(events[0].time_ns == base);
  CHECK(events[1].input == 0);
  CHECK_FALSE(events[1].pressed);
  CHECK(events[1].time_ns == base + 300 * kMs);
  CHECK(events[2].input == kRecordInput);
  CHECK(events[2].pressed);
  // Nothing else: the glitch produced no event.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (input.EdgesSeen() < edges.size() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  SwitchEvent extra;
  CHECK_FALSE(input.Pop(extra));
  input.Stop();
}

TEST_CASE("GPIO event thread emits a live edge only after the debounce time has passed",
          "[platform]") {
  auto source = std::make_unique<PipeEventSource>(
      std::array<bool, kSwitchInputCount>{true, true, true, true, true});
  const int fd = source->write_fd();
  GpioSwitchInput input(GpioSwitchConfig{}, std::move(source));
  REQUIRE(input.Start(nullptr));
  const std::int64_t t = MonotonicNowNs();
  WriteEdges(fd, {{t, 1, false}});
  const auto events = PopUntil(input, 1);
  const std::int64_t seen = MonotonicNowNs();
  REQUIRE(events.size() == 1);
  CHECK(events[0].input == 1);
  CHECK(events[0].time_ns == t);
  CHECK(seen - t >= 30 * kMs);      // the poll timeout waited for the quiet period
  CHECK(input.HeartbeatNs() >= t);  // the thread woke for the deadline: alive for the watchdog
}

// ---- MCP2221A ----

namespace {

// A GET GPIO VALUES response as the datasheet lays it out (DS20005565 table 3-36): byte 0 echoes
// 0x51, byte 1 status, then per pin (value, direction).
Mcp2221Report GetGpioResponse(std::array<int, 4> values, std::array<int, 4> directions,
                              int status = 0) {
  Mcp2221Report r{};
  r[0] = 0x51;
  r[1] = static_cast<std::uint8_t>(status);
  for (std::size_t p = 0; p < 4; ++p) {
    r[2 + 2 * p] = static_cast<std::uint8_t>(values[p]);
    r[3 + 2 * p] = static_cast<std::uint8_t>(directions[p]);
  }
  return r;
}

struct FakeMcp2221 {
  std::atomic<bool> present{true};  // flipped by the test while a poll thread may be reading
  bool configured = false;          // SET SRAM received since last plug-in
  std::array<int, 4> levels = {1, 1, 1, 1};  // pulled up: no token
  std::vector<std::uint8_t> commands;
};

class FakeHid final : public HidTransport {
 public:
  explicit FakeHid(FakeMcp2221& dev) : dev_(&dev) {}
  bool Write(const Mcp2221Report& r) override {
    if (!dev_->present) return false;
    dev_->commands.push_back(r[0]);
    last_ = r;
    return true;
  }
  bool Read(Mcp2221Report& out, int /*timeout_ms*/) override {
    if (!dev_->present) return false;
    out = Mcp2221Report{};
    out[0] = last_[0];
    if (last_[0] == 0x60) {
      // Accept only the documented "GP0-3 = GPIO input" settings.
      dev_->configured = (last_[7] & 0x80) != 0 && last_[8] == 0x08 && last_[9] == 0x08 &&
                         last_[10] == 0x08 && last_[11] == 0x08;
      out[1] = dev_->configured ? 0 : 1;
    } else if (last_[0] == 0x51) {
      out = dev_->configured ? GetGpioResponse(dev_->levels, {1, 1, 1, 1})
                             : GetGpioResponse({0xEE, 0xEE, 0xEE, 0xEE}, {0xEE, 0xEE, 0xEE, 0xEE});
    }
    return true;
  }

 private:
  FakeMcp2221* dev_;
  Mcp2221Report last_{};
};

HidOpener FakeOpener(FakeMcp2221& dev) {
  return [&dev]() -> std::unique_ptr<HidTransport> {
    if (!dev.present) return nullptr;
    return std::make_unique<FakeHid>(dev);
  };
}

}  // namespace

TEST_CASE("MCP2221A GET GPIO response bytes decode to pin levels and directions", "[platform]") {
  const auto state = DecodeGetGpioValues(GetGpioResponse({0, 1, 1, 0}, {1, 1, 0, 1}));
  REQUIRE(state.has_value());
  CHECK(state->high == std::array<bool, 4>{false, true, true, false});
  CHECK(state->input == std::array<bool, 4>{true, true, false, true});
  // Error status, a different command echo, and a pin that is not a GPIO are all rejected.
  CHECK_FALSE(DecodeGetGpioValues(GetGpioResponse({0, 0, 0, 0}, {1, 1, 1, 1}, 1)).has_value());
  auto wrong = GetGpioResponse({0, 0, 0, 0}, {1, 1, 1, 1});
  wrong[0] = 0x61;
  CHECK_FALSE(DecodeGetGpioValues(wrong).has_value());
  CHECK_FALSE(DecodeGetGpioValues(GetGpioResponse({0, 0xEE, 0, 0}, {1, 0xEE, 1, 1})).has_value());
}

TEST_CASE("MCP2221A set-up report makes GP0-3 GPIO inputs and alters nothing else", "[platform]") {
  const auto r = BuildSetSramGpioInputs();
  CHECK(r[0] == 0x60);
  for (std::size_t i = 2; i <= 6; ++i) CHECK((r[i] & 0x80) == 0);  // clock, DAC, ADC, IRQ kept
  CHECK((r[7] & 0x80) != 0);
  for (std::size_t i = 8; i <= 11; ++i) {
    CHECK((r[i] & 0x07) == 0);  // designation GPIO
    CHECK((r[i] & 0x08) != 0);  // direction input
  }
  CHECK(BuildGetGpioValues()[0] == 0x51);
}

TEST_CASE("MCP2221A poller debounces polled pins into token events", "[platform]") {
  FakeMcp2221 dev;
  Logger logger;
  logger.SetEchoToStderr(false);
  DeviceStatusBoard board(logger);
  Mcp2221SwitchInput input(Mcp2221SwitchConfig{}, FakeOpener(dev), board);
  std::int64_t t = 0;
  input.Step(t);
  REQUIRE(input.Connected());
  CHECK(dev.commands.front() == 0x60);  // configured before the first poll
  SwitchEvent e;
  CHECK_FALSE(input.Pop(e));
  dev.levels[2] = 0;  // token on GP2 (switch to ground)
  std::vector<SwitchEvent> events;
  for (int i = 1; i <= 4; ++i) {
    t = i * 15 * kMs;
    if (i == 2) dev.levels[2] = 1;  // one bounce sample
    if (i == 3) dev.levels[2] = 0;
    input.Step(t);
    while (input.Pop(e)) events.push_back(e);
  }
  CHECK(events.empty());  // last change at 45 ms: only 15 ms of quiet at 60 ms
  for (int i = 5; i <= 8; ++i) {
    input.Step(i * 15 * kMs);
    while (input.Pop(e)) events.push_back(e);
  }
  REQUIRE(events.size() == 1);
  CHECK(events[0].input == 2);
  CHECK(events[0].pressed);
  CHECK(events[0].time_ns == 15 * kMs);  // first edge of the burst
  CHECK(input.HeartbeatNs() == 8 * 15 * kMs);
}

TEST_CASE("MCP2221A unplugged and replugged: one log line each, status lost then ok, resumes",
          "[platform]") {
  FakeMcp2221 dev;
  Logger logger;
  logger.SetEchoToStderr(false);
  DeviceStatusBoard board(logger);
  Mcp2221SwitchConfig config;
  config.reopen_interval_ms = 500;
  Mcp2221SwitchInput input(config, FakeOpener(dev), board);
  input.Step(0);
  REQUIRE(board.Get("switches").state == DeviceState::kOk);
  const auto lines_before = logger.Count();

  dev.present = false;
  dev.configured = false;
  input.Step(15 * kMs);
  CHECK_FALSE(input.Connected());
  auto status = board.Get("switches");
  CHECK(status.state == DeviceState::kLost);
  CHECK(status.message.find("unplugged") != std::string::npos);
  REQUIRE(logger.Count() == lines_before + 1);
  CHECK(logger.Recent().back().Text().rfind("warn switches: lost: MCP2221A adapter unplugged", 0) ==
        0);
  // Retries while away stay silent.
  for (int i = 2; i < 100; ++i) input.Step(i * 15 * kMs);
  CHECK(logger.Count() == lines_before + 1);

  // A token was placed on GP0 while the adapter was away; it is reported after the replug.
  dev.levels[0] = 0;
  dev.present = true;
  input.Step(2000 * kMs);
  REQUIRE(input.Connected());
  CHECK(dev.configured);  // SET SRAM sent again after power-up
  status = board.Get("switches");
  CHECK(status.state == DeviceState::kOk);
  CHECK(status.reconnects == 1);
  CHECK(logger.Count() == lines_before + 2);
  SwitchEvent e;
  REQUIRE(input.Pop(e));
  CHECK(e.input == 0);
  CHECK(e.pressed);
}

// ---- keyboard, selection, fallback ----

TEST_CASE("keys 1-4 toggle tokens and R is a momentary record button", "[platform]") {
  KeyboardSwitchInput keys;
  CHECK(keys.OnKey('2', true, 10));
  CHECK(keys.OnKey('2', false, 20));
  CHECK(keys.OnKey('r', true, 30));
  CHECK(keys.OnKey('R', false, 40));
  CHECK(keys.OnKey('2', true, 50));
  CHECK_FALSE(keys.OnKey('x', true, 60));
  CHECK(keys.HeartbeatNs() == -1);  // no thread of its own: exempt from the watchdog
  std::vector<SwitchEvent> events;
  SwitchEvent e;
  while (keys.Pop(e)) events.push_back(e);
  REQUIRE(events.size() == 4);
  CHECK((events[0].input == 1 && events[0].pressed && events[0].time_ns == 10));
  CHECK((events[1].input == kRecordInput && events[1].pressed));
  CHECK((events[2].input == kRecordInput && !events[2].pressed));
  CHECK((events[3].input == 1 && !events[3].pressed && events[3].time_ns == 50));
}

TEST_CASE("one token selects its texture, none the default, several the last placed",
          "[platform]") {
  TokenSelector s;
  CHECK(s.Selected() == TokenSelector::kDefaultTexture);
  CHECK(s.Apply({0, 2, true}));
  CHECK(s.Selected() == 2);
  CHECK(s.Apply({1, 0, true}));
  CHECK(s.Selected() == 0);  // two tokens: the last one placed
  CHECK(s.Apply({2, 3, true}));
  CHECK(s.Selected() == 3);
  CHECK(s.Apply({3, 3, false}));
  CHECK(s.Selected() == 0);  // lifting the last leaves the most recent of the others
  CHECK_FALSE(s.Apply({4, 2, false}));
  CHECK(s.Selected() == 0);  // lifting an older token changes nothing
  CHECK(s.Apply({5, 0, false}));
  CHECK(s.Selected() == TokenSelector::kDefaultTexture);
  CHECK_FALSE(s.Apply({6, kRecordInput, true}));  // the record button is not a token
}

TEST_CASE("GPIO chip absent at start falls back to keys with one warning and a staff status",
          "[platform]") {
  Logger logger;
  logger.SetEchoToStderr(false);
  DeviceStatusBoard board(logger);
  SwitchesConfig config;
  config.backend = "gpio";
  config.gpio.chip = "sas-test-no-such-gpiochip";
  auto inputs = OpenSwitchInputs(config, board);
  CHECK(inputs.hardware == nullptr);
  CHECK(std::string(inputs.ActiveBackend()) == "keyboard");
  const auto status = board.Get("switches");
  CHECK(status.state == DeviceState::kMissing);
  CHECK(status.backend == "keyboard");
  const auto lines = logger.Recent();
  REQUIRE(lines.size() == 1);
  CHECK(lines[0].level == LogLevel::kWarn);
  CHECK(lines[0].Text().find("sas-test-no-such-gpiochip") != std::string::npos);
  CHECK(lines[0].Text().find("fall back to keys 1-4") != std::string::npos);
  // The fallback works.
  inputs.keyboard->OnKey('3', true, 1);
  SwitchEvent e;
  REQUIRE(inputs.Pop(e));
  CHECK(e.input == 2);
}

TEST_CASE("auto backend uses the MCP2221A adapter when there is no GPIO chip", "[platform]") {
  FakeMcp2221 dev;
  Logger logger;
  logger.SetEchoToStderr(false);
  DeviceStatusBoard board(logger);
  SwitchesConfig config;
  config.gpio.chip = "sas-test-no-such-gpiochip";
  auto inputs = OpenSwitchInputs(config, board, nullptr, FakeOpener(dev));
  REQUIRE(inputs.hardware != nullptr);
  CHECK(std::string(inputs.ActiveBackend()) == "mcp2221");
  CHECK(board.Get("switches").state == DeviceState::kOk);
  inputs.hardware->Stop();  // the poll thread read the fake; stop it before `dev` goes
  // A PC without a GPIO header is a normal set-up for "auto": said, but no warning.
  const auto lines = logger.Recent();
  CHECK(std::none_of(lines.begin(), lines.end(),
                     [](const LogLine& l) { return l.level == LogLevel::kWarn; }));
  CHECK(std::any_of(lines.begin(), lines.end(), [](const LogLine& l) {
    return l.Text().rfind("info switches: GPIO chip 'sas-test-no-such-gpiochip' unusable", 0) == 0;
  }));
}

namespace {

// A 5-line chip with unnamed lines, as a small GPIO expander (or gpio-sim) reports itself.
GpioChipInfo FiveLineChip() {
  return {"gpiochip0", "gpio-sim", 5, {"", "", "", "", ""}};
}

// The GPIO lines' source as the libgpiod one makes it: the configured lines resolved on `chip`
// (throwing for the lines it lacks), then a pipe standing in for the line fds.
GpioSwitchInput::SourceFactory FakeChip(GpioChipInfo chip, GpioSwitchConfig config) {
  return [chip, config]() -> std::unique_ptr<GpioEventSource> {
    ResolveGpioLines(chip, config);
    std::array<bool, kSwitchInputCount> high;
    high.fill(true);
    return std::make_unique<PipeEventSource>(high);
  };
}

}  // namespace

TEST_CASE(
    "GPIO lines a chip lacks are all named, by offset or by name, with the lines the chip has",
    "[platform]") {
  GpioSwitchConfig config;  // 17, 27, 22, 23, 24
  const auto five = FiveLineChip();
  CHECK(MissingGpioLines(five, config.lines) ==
        std::vector<std::string>{"17", "27", "22", "23", "24"});
  CHECK_THROWS_MATCHES(
      ResolveGpioLines(five, config), GpioLinesMissing,
      Catch::Message("gpiochip0 lacks lines 17,27,22,23,24 (it has 5 lines: 0-4, unnamed)"));

  config.lines = {"0", "1", "2", "3", ""};  // no record button on GPIO
  CHECK(ResolveGpioLines(five, config) == std::vector<unsigned>{0, 1, 2, 3});
  config.lines = {"0", "1", "2", "99999999999999999999", "4"};
  CHECK(MissingGpioLines(five, config.lines) == std::vector<std::string>{"99999999999999999999"});

  const GpioChipInfo named{"gpiochip2", "pinctrl", 4, {"TOKEN1", "", "TOKEN3", "TOKEN4"}};
  config.lines = {"TOKEN1", "TOKEN2", "TOKEN3", "TOKEN4", "3"};
  CHECK_THROWS_MATCHES(ResolveGpioLines(named, config), GpioLinesMissing,
                       Catch::Message("gpiochip2 lacks line TOKEN2 (it has 4 lines: 0-3; named "
                                      "0=TOKEN1 2=TOKEN3 3=TOKEN4)"));
  config.lines = {"TOKEN4", "1", "TOKEN1", "TOKEN3", ""};
  CHECK(ResolveGpioLines(named, config) == std::vector<unsigned>{3, 1, 0, 2});

  // The chip by any name libgpiod looks it up by.
  const std::vector<GpioChipInfo> chips = {named, five};
  for (const char* spec : {"gpiochip0", "/dev/gpiochip0", "gpio-sim", "0"}) {
    INFO(spec);
    CHECK(FindGpioChip(chips, spec) == &chips[1]);
  }
  CHECK(FindGpioChip(chips, "gpiochip1") == nullptr);
}

TEST_CASE(
    "a GPIO chip that lacks the configured lines is a warning naming the chip, the lines and what "
    "is used instead: the MCP2221A adapter, or the keys",
    "[platform]") {
  SwitchesConfig config;  // auto, gpiochip0, lines 17 27 22 23 24
  const std::string lacks = "gpiochip0 lacks lines 17,27,22,23,24 (it has 5 lines: 0-4, unnamed)";
  {
    INFO("auto, the adapter plugged in");
    FakeMcp2221 dev;
    Logger logger;
    logger.SetEchoToStderr(false);
    DeviceStatusBoard board(logger);
    auto inputs = OpenSwitchInputs(config, board, nullptr, FakeOpener(dev),
                                   FakeChip(FiveLineChip(), config.gpio));
    REQUIRE(inputs.hardware != nullptr);
    CHECK(std::string(inputs.ActiveBackend()) == "mcp2221");
    inputs.hardware->Stop();
    std::vector<std::string> warnings;
    for (const auto& line : logger.Recent()) {
      if (line.level == LogLevel::kWarn) warnings.push_back(line.Text());
    }
    REQUIRE(warnings.size() == 1);
    CHECK(warnings[0] == "warn switches: GPIO chip 'gpiochip0' unusable (" + lacks +
                             "); using the MCP2221A adapter instead");
  }
  {
    INFO("auto, no adapter");
    FakeMcp2221 dev;
    dev.present = false;
    Logger logger;
    logger.SetEchoToStderr(false);
    DeviceStatusBoard board(logger);
    auto inputs = OpenSwitchInputs(config, board, nullptr, FakeOpener(dev),
                                   FakeChip(FiveLineChip(), config.gpio));
    CHECK(inputs.hardware == nullptr);
    const auto lines = logger.Recent();
    REQUIRE(lines.size() == 1);
    CHECK(lines[0].level == LogLevel::kWarn);
    CHECK_THAT(lines[0].Text(),
               Catch::StartsWith("warn switches: missing: GPIO chip 'gpiochip0' unusable (" +
                                 lacks + ") and ") &&
                   Catch::EndsWith("; token switches fall back to keys 1-4 (R records)"));
  }
  {
    INFO("gpio only");
    config.backend = "gpio";
    Logger logger;
    logger.SetEchoToStderr(false);
    DeviceStatusBoard board(logger);
    auto inputs =
        OpenSwitchInputs(config, board, nullptr, nullptr, FakeChip(FiveLineChip(), config.gpio));
    CHECK(inputs.hardware == nullptr);
    const auto lines = logger.Recent();
    REQUIRE(lines.size() == 1);
    CHECK(lines[0].Text() == "warn switches: missing: GPIO chip 'gpiochip0' unusable (" + lacks +
                                 "); token switches fall back to keys 1-4 (R records)");
  }
}

TEST_CASE("MCP2221A asked for but absent at start: keys meanwhile, adapter taken when plugged in",
          "[platform]") {
  FakeMcp2221 dev;
  dev.present = false;
  Logger logger;
  logger.SetEchoToStderr(false);
  DeviceStatusBoard board(logger);
  SwitchesConfig config;
  config.backend = "mcp2221";
  config.mcp2221.reopen_interval_ms = 5;
  config.mcp2221.poll_interval_ms = 2;
  auto inputs = OpenSwitchInputs(config, board, nullptr, FakeOpener(dev));
  auto status = board.Get("switches");
  CHECK(status.state == DeviceState::kMissing);
  CHECK(status.message.find("until it is plugged in") != std::string::npos);
  REQUIRE(logger.Count() == 1);
  inputs.keyboard->OnKey('1', true, 5);
  SwitchEvent e;
  REQUIRE(inputs.Pop(e));
  CHECK(e.input == 0);

  dev.present = true;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (board.Get("switches").state != DeviceState::kOk &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  status = board.Get("switches");
  CHECK(status.state == DeviceState::kOk);
  CHECK(status.backend == "mcp2221");
  CHECK(logger.Count() == 2);
  inputs.hardware->Stop();
}
