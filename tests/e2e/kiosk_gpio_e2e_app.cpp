// The live kiosk with fake GPIO token switches, for the end-to-end test under Xvfb.
// A test driver, not the product: sketch-a-scratch never contains this fake.
// It runs sas::app::RunKiosk, the same code as `sketch-a-scratch --kiosk` (SDL window, PortAudio,
// pen, staff panel, KioskControl, backend choice, the GPIO switch thread with its edge ordering,
// active-low and debounce, the token rule), with one thing replaced through KioskBackends: the
// GPIO lines' event source reads text from a FIFO the test script writes instead of libgpiod's
// line fds (Debian 12's kernel has neither gpio-sim nor gpio-mockup). One event per text line:
//   line <offset> falling|rising     a raw edge on the configured line <offset>, stamped
//                                    CLOCK_MONOTONIC when read (as the kernel stamps its events)
// Lines are mapped to inputs through [switches] gpio_lines exactly as the libgpiod source does
// (offsets only: the fake chip has no line names); every line starts high (no token on it,
// pull-up). An event on a line that is not configured is reported on stderr and dropped.
//   usage: kiosk_gpio_e2e_app --gpio-fifo PATH [--config FILE] [--state-dir DIR]
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "live_kiosk.h"
#include "platform/common/clock.h"
#include "platform/gpio/gpio_switches.h"
#include "tools/command_line.h"

namespace {

using sas::platform::GpioEventSource;
using sas::platform::GpioSwitchConfig;
using sas::platform::kSwitchInputCount;
using sas::platform::RawEdge;

const char* InputName(int input) {
  static const char* const kNames[] = {"token 1", "token 2", "token 3", "token 4", "record"};
  return kNames[input];
}

class FifoEventSource final : public GpioEventSource {
 public:
  // O_RDWR: the FIFO stays open for writing on our side, so a writer closing it is never an EOF
  // (POLLHUP) and opening it never blocks.
  FifoEventSource(int fd, std::string path, std::array<long, kSwitchInputCount> offsets)
      : fd_(fd), path_(std::move(path)), offsets_(offsets) {}
  ~FifoEventSource() override { close(fd_); }

  std::vector<pollfd> Fds() const override { return {{fd_, POLLIN, 0}}; }

  bool Read(const std::vector<pollfd>& ready, std::vector<RawEdge>& out) override {
    if (ready.empty() || (ready[0].revents & POLLIN) == 0) return true;
    char chunk[512];
    for (;;) {
      const ssize_t n = read(fd_, chunk, sizeof chunk);
      if (n <= 0) break;
      pending_.append(chunk, static_cast<std::size_t>(n));
    }
    const std::int64_t now_ns = sas::platform::MonotonicNowNs();
    std::size_t end = 0;
    while ((end = pending_.find('\n')) != std::string::npos) {
      Parse(pending_.substr(0, end), now_ns, out);
      pending_.erase(0, end + 1);
    }
    return true;
  }

  std::array<bool, kSwitchInputCount> InitialLevels() override {
    std::array<bool, kSwitchInputCount> high;
    high.fill(true);
    return high;
  }

  std::string Describe() const override { return "fake GPIO chip on FIFO " + path_; }

 private:
  void Parse(const std::string& text, std::int64_t now_ns, std::vector<RawEdge>& out) const {
    std::istringstream in(text);
    std::string word, edge;
    long offset = -1;
    if (!(in >> word >> offset >> edge) || word != "line" ||
        (edge != "falling" && edge != "rising")) {
      std::fprintf(stderr, "fake gpio: cannot read \"%s\" (line <offset> falling|rising)\n",
                   text.c_str());
      return;
    }
    const auto it = std::find(offsets_.begin(), offsets_.end(), offset);
    if (it == offsets_.end()) {
      std::fprintf(stderr, "fake gpio: line %ld is not one of the configured gpio_lines\n", offset);
      return;
    }
    const int input = static_cast<int>(it - offsets_.begin());
    std::fprintf(stderr, "fake gpio: line %ld (%s) %s\n", offset, InputName(input), edge.c_str());
    out.push_back({now_ns, input, edge == "rising"});
  }

  int fd_;
  std::string path_;
  std::array<long, kSwitchInputCount> offsets_;  // per input; -1 = not configured
  std::string pending_;                          // a text line not yet complete
};

// Builds the source from the configured lines; null (libgpiod is then tried) when the FIFO does
// not open or a line is given by name, with the reason on stderr.
std::unique_ptr<GpioEventSource> MakeFifoSource(const std::string& path,
                                                const GpioSwitchConfig& config) {
  std::array<long, kSwitchInputCount> offsets;
  offsets.fill(-1);
  for (std::size_t i = 0; i < offsets.size(); ++i) {
    const std::string& spec = config.lines[i];
    if (spec.empty()) continue;
    if (!std::all_of(spec.begin(), spec.end(),
                     [](unsigned char c) { return std::isdigit(c) != 0; })) {
      std::fprintf(stderr, "fake gpio: line '%s' is a name; the fake chip knows offsets only\n",
                   spec.c_str());
      return nullptr;
    }
    offsets[i] = std::stol(spec);
  }
  const int fd = open(path.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    std::perror(("fake gpio: " + path).c_str());
    return nullptr;
  }
  return std::make_unique<FifoEventSource>(fd, path, offsets);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "The live kiosk (sketch-a-scratch kiosk) with its GPIO token lines read from a "
      "FIFO, for the end-to-end test under Xvfb.",
      "kiosk_gpio_e2e_app"};
  std::string fifo, config_path, state_dir;
  app.add_option("--gpio-fifo", fifo, "FIFO of \"line <offset> falling|rising\" events")
      ->required();
  // The kiosk's own options, handed on as given (RunKiosk parses them again).
  app.add_option("--config", config_path, "the kiosk's configuration file");
  app.add_option("--state-dir", state_dir, "the kiosk's state folder");
  if (const int code = sas::kiosk::ParseProgramCommandLine(app, argc, argv); code >= 0) return code;
  std::vector<std::string> kiosk_args;
  if (!config_path.empty()) kiosk_args.insert(kiosk_args.end(), {"--config", config_path});
  if (!state_dir.empty()) kiosk_args.insert(kiosk_args.end(), {"--state-dir", state_dir});
  sas::app::KioskBackends backends;
  backends.gpio_events = [fifo](const GpioSwitchConfig& config) {
    return MakeFifoSource(fifo, config);
  };
  return sas::app::RunKiosk(kiosk_args, stdout, stderr, backends);
}
