// The visitor's hardware inside the appliance VM, made from real kernel interfaces so that the
// installed kiosk meets it through the same drivers and libraries as on the box:
//   - a pen display tablet through uinput (absolute x/y, pressure, tilt, pen tool, tip), which
//     udev classifies as a tablet and libinput hands to the kiosk;
//   - a keyboard through uinput (the record key R and the staff chord reach SDL's evdev input);
//   - an MCP2221A USB-HID GPIO adapter through uhid (vendor 04d8, product 00dd, the adapter's
//     64-byte vendor reports), answering SET SRAM (0x60), GET SRAM (0x61) and GET GPIO VALUES
//     (0x51) as the datasheet describes; hidapi opens its hidraw node.
// Each can be unplugged and plugged again. Commands come one per line on a FIFO; after each, a
// line "ok <n> <command>" (or "error <n> <why>") is appended to the status file, so the scenario
// script knows when a stroke is over.
//
//   fake_devices <control fifo> <status file>      (--help: every mode and its arguments)
// Commands (x, y are fractions of the screen, 0..1; pressure 0..1; tilt in degrees from upright):
//   pen plug|unplug        board plug|unplug        keyboard plug|unplug
//   down X Y PRESSURE TILT       pen into proximity at (X, Y) and tip down
//   drag X Y SECONDS PRESSURE TILT   tip stays down, moves in a straight line to (X, Y)
//   up                     tip up and out of proximity
//   token N on|off         token N (1-4) on its switch: GP(N-1) pulled low (active low)
//   key NAME down|up|tap   r, 1-4, ctrl, alt, s
//   chord SECONDS          ctrl+alt+s held for SECONDS (the staff chord)
//   wait SECONDS
// A second mode keeps samples in memory for a core-dump control (see boot-test.sh):
//   fake_devices hold <file>   reads the file into an ordinary heap buffer, says "holding N
//                              bytes" on stdout (the journal line the visitor waits for), sleeps
// A third watches the loopback capture that arecord is writing (float32 stereo, 48 kHz), so the
// visitor waits for what the speaker does instead of for a fixed time:
//   fake_devices capture-wait <cap.f32> FROM_S loud|quiet DBFS WINDOW_S TIMEOUT_S
//     the first WINDOW_S-long stretch of the speaker channel starting at or after FROM_S s of
//     the capture whose RMS is above (loud) or below (quiet) DBFS; prints the capture time at
//     its end and exits 0, or exits 1 when the capture has not shown one within TIMEOUT_S s of
//     wall time (the file is read again as arecord appends to it)
#include <fcntl.h>
#include <linux/input.h>
#include <linux/uhid.h>
#include <linux/uinput.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "tools/command_line.h"

namespace {

constexpr int kAbsMax = 32767;       // pen x/y range
constexpr int kAbsResolution = 100;  // units per mm: a 328 x 328 mm active area
constexpr int kPressureMax = 4095;
constexpr int kTiltMax = 64;  // degrees (resolution 57 units per radian = 1 unit per degree)

void Sleep(double seconds) {
  if (seconds > 0) std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
}

void Check(bool ok, const std::string& what) {
  if (!ok) throw std::runtime_error(what + ": " + std::strerror(errno));
}

// ------------------------------------------------------------------ uinput devices

class UinputDevice {
 public:
  UinputDevice() = default;
  ~UinputDevice() { Unplug(); }
  bool Plugged() const { return fd_ >= 0; }

  void Unplug() {
    if (fd_ < 0) return;
    ioctl(fd_, UI_DEV_DESTROY);
    close(fd_);
    fd_ = -1;
  }

  void Emit(int type, int code, int value) {
    if (fd_ < 0) return;
    input_event event{};
    event.type = static_cast<std::uint16_t>(type);
    event.code = static_cast<std::uint16_t>(code);
    event.value = value;
    Check(write(fd_, &event, sizeof event) == static_cast<ssize_t>(sizeof event), "uinput write");
  }
  void Sync() { Emit(EV_SYN, SYN_REPORT, 0); }

 protected:
  int Open() {
    fd_ = open("/dev/uinput", O_WRONLY | O_NONBLOCK | O_CLOEXEC);
    Check(fd_ >= 0, "open /dev/uinput");
    return fd_;
  }
  void Create(const char* name, std::uint16_t vendor, std::uint16_t product) {
    uinput_setup setup{};
    setup.id.bustype = BUS_USB;
    setup.id.vendor = vendor;
    setup.id.product = product;
    setup.id.version = 1;
    std::snprintf(setup.name, sizeof setup.name, "%s", name);
    Check(ioctl(fd_, UI_DEV_SETUP, &setup) == 0, "UI_DEV_SETUP");
    Check(ioctl(fd_, UI_DEV_CREATE) == 0, "UI_DEV_CREATE");
  }
  void Abs(int code, int minimum, int maximum, int resolution) {
    Check(ioctl(fd_, UI_SET_ABSBIT, code) == 0, "UI_SET_ABSBIT");
    uinput_abs_setup abs{};
    abs.code = static_cast<std::uint16_t>(code);
    abs.absinfo.minimum = minimum;
    abs.absinfo.maximum = maximum;
    abs.absinfo.resolution = resolution;
    Check(ioctl(fd_, UI_ABS_SETUP, &abs) == 0, "UI_ABS_SETUP");
  }
  int fd_ = -1;
};

class Pen : public UinputDevice {
 public:
  void Plug() {
    if (Plugged()) return;
    Open();
    ioctl(fd_, UI_SET_EVBIT, EV_KEY);
    ioctl(fd_, UI_SET_EVBIT, EV_ABS);
    ioctl(fd_, UI_SET_KEYBIT, BTN_TOOL_PEN);
    ioctl(fd_, UI_SET_KEYBIT, BTN_TOUCH);
    ioctl(fd_, UI_SET_KEYBIT, BTN_STYLUS);
    // A display tablet (the pen display): libinput maps it onto the screen.
    ioctl(fd_, UI_SET_PROPBIT, INPUT_PROP_DIRECT);
    Abs(ABS_X, 0, kAbsMax, kAbsResolution);
    Abs(ABS_Y, 0, kAbsMax, kAbsResolution);
    Abs(ABS_PRESSURE, 0, kPressureMax, 0);
    Abs(ABS_TILT_X, -kTiltMax, kTiltMax, 57);
    Abs(ABS_TILT_Y, -kTiltMax, kTiltMax, 57);
    Create("Sketch-a-Scratch test pen display", 0x1d50, 0x5ca7);
    in_proximity_ = tip_down_ = false;
  }

  void Down(double x, double y, double pressure, double tilt_deg) {
    Position(x, y, 0.0, tilt_deg);
    if (!in_proximity_) {
      Emit(EV_KEY, BTN_TOOL_PEN, 1);
      in_proximity_ = true;
      Sync();
      // libinput wants proximity and contact in separate frames, some hover in between.
      Sleep(0.04);
    }
    Position(x, y, pressure, tilt_deg);
    Emit(EV_KEY, BTN_TOUCH, 1);
    tip_down_ = true;
    Sync();
  }

  void Drag(double x, double y, double seconds, double pressure, double tilt_deg) {
    const int steps = std::max(1, static_cast<int>(seconds / 0.005));  // 200 Hz, like a tablet
    for (int i = 1; i <= steps; ++i) {
      const double f = static_cast<double>(i) / steps;
      Position(x0_ + (x - x0_) * f, y0_ + (y - y0_) * f, pressure, tilt_deg, false);
      Sync();
      Sleep(seconds / steps);
    }
    x0_ = x;
    y0_ = y;
  }

  void Up() {
    if (tip_down_) {
      Emit(EV_ABS, ABS_PRESSURE, 0);
      Emit(EV_KEY, BTN_TOUCH, 0);
      tip_down_ = false;
      Sync();
      Sleep(0.04);
    }
    if (in_proximity_) {
      Emit(EV_KEY, BTN_TOOL_PEN, 0);
      in_proximity_ = false;
      Sync();
    }
  }

 private:
  void Position(double x, double y, double pressure, double tilt_deg, bool remember = true) {
    Emit(EV_ABS, ABS_X, static_cast<int>(std::lround(std::clamp(x, 0.0, 1.0) * kAbsMax)));
    Emit(EV_ABS, ABS_Y, static_cast<int>(std::lround(std::clamp(y, 0.0, 1.0) * kAbsMax)));
    Emit(EV_ABS, ABS_PRESSURE,
         static_cast<int>(std::lround(std::clamp(pressure, 0.0, 1.0) * kPressureMax)));
    Emit(EV_ABS, ABS_TILT_X, static_cast<int>(std::lround(std::clamp(tilt_deg, 0.0, 60.0))));
    Emit(EV_ABS, ABS_TILT_Y, 0);
    if (remember) {
      x0_ = x;
      y0_ = y;
    }
  }
  bool in_proximity_ = false, tip_down_ = false;
  double x0_ = 0.5, y0_ = 0.5;
};

class Keyboard : public UinputDevice {
 public:
  void Plug() {
    if (Plugged()) return;
    Open();
    ioctl(fd_, UI_SET_EVBIT, EV_KEY);
    // A whole keyboard's keys, so udev calls it a keyboard (ID_INPUT_KEYBOARD) like a real one.
    for (int key = KEY_ESC; key <= KEY_MICMUTE; ++key) ioctl(fd_, UI_SET_KEYBIT, key);
    Create("Sketch-a-Scratch test keyboard", 0x1d50, 0x5ca8);
  }
  void Key(int code, bool down) {
    Emit(EV_KEY, code, down ? 1 : 0);
    Sync();
  }
};

// ------------------------------------------------------------------ MCP2221A over uhid

// The MCP2221A's HID interface: one vendor-defined collection with a 64-byte input and a 64-byte
// output report, no report IDs.
const std::vector<std::uint8_t> kMcp2221Descriptor = {
    0x06, 0x00, 0xFF,              // usage page (vendor 0xFF00)
    0x09, 0x01,                    // usage 1
    0xA1, 0x01,                    // collection (application)
    0x19, 0x01, 0x29, 0x40,        // usage 1..64
    0x15, 0x00, 0x26, 0xFF, 0x00,  // logical 0..255
    0x75, 0x08, 0x95, 0x40,        // 64 x 8 bits
    0x81, 0x02,                    // input (data, variable, absolute)
    0x19, 0x01, 0x29, 0x40,        // usage 1..64
    0x91, 0x02,                    // output (data, variable, absolute)
    0xC0,                          // end collection
};

class Mcp2221 {
 public:
  ~Mcp2221() { Unplug(); }
  bool Plugged() const { return fd_ >= 0; }

  void Plug() {
    std::lock_guard lock(mutex_);
    if (fd_ >= 0) return;
    fd_ = open("/dev/uhid", O_RDWR | O_CLOEXEC);
    Check(fd_ >= 0, "open /dev/uhid");
    uhid_event event{};
    event.type = UHID_CREATE2;
    auto& create = event.u.create2;
    std::snprintf(reinterpret_cast<char*>(create.name), sizeof create.name,
                  "Microchip Technology Inc. MCP2221 USB-I2C/UART Combo");
    std::snprintf(reinterpret_cast<char*>(create.uniq), sizeof create.uniq, "0001234567");
    create.rd_size = static_cast<std::uint16_t>(kMcp2221Descriptor.size());
    std::memcpy(create.rd_data, kMcp2221Descriptor.data(), kMcp2221Descriptor.size());
    create.bus = BUS_USB;
    create.vendor = 0x04d8;
    create.product = 0x00dd;
    create.version = 0x0100;
    Check(write(fd_, &event, sizeof event) == static_cast<ssize_t>(sizeof event), "UHID_CREATE2");
    sram_gp_.fill(0x00);  // power-up designation: not GPIO until SET SRAM makes them inputs
  }

  void Unplug() {
    std::lock_guard lock(mutex_);
    if (fd_ < 0) return;
    uhid_event event{};
    event.type = UHID_DESTROY;
    [[maybe_unused]] const ssize_t n = write(fd_, &event, sizeof event);
    close(fd_);
    fd_ = -1;
  }

  void SetToken(int pin, bool on) { low_[static_cast<std::size_t>(pin)] = on; }
  std::uint64_t requests() const { return requests_.load(); }

  // Serves the kernel's events (the host's output reports) until stop; polls with a timeout so
  // unplug/plug from the command thread are picked up.
  void Serve(const std::atomic<bool>& stop) {
    while (!stop.load()) {
      int fd;
      {
        std::lock_guard lock(mutex_);
        fd = fd_;
      }
      if (fd < 0) {
        Sleep(0.01);
        continue;
      }
      pollfd p{fd, POLLIN, 0};
      if (poll(&p, 1, 20) <= 0) continue;
      std::lock_guard lock(mutex_);
      if (fd_ != fd) continue;  // unplugged meanwhile
      uhid_event event{};
      if (read(fd_, &event, sizeof event) <= 0) continue;
      if (event.type == UHID_OUTPUT) {
        const std::uint8_t* data = event.u.output.data;
        std::size_t size = event.u.output.size;
        // hidraw passes the report-ID byte (0: none) in front of the 64 command bytes.
        if (size == 65 && data[0] == 0) {
          ++data;
          --size;
        }
        if (size >= 1) Answer(data, size);
      } else if (event.type == UHID_GET_REPORT) {
        uhid_event reply{};
        reply.type = UHID_GET_REPORT_REPLY;
        reply.u.get_report_reply.id = event.u.get_report.id;
        reply.u.get_report_reply.err = EIO;
        [[maybe_unused]] const ssize_t n = write(fd_, &reply, sizeof reply);
      }
    }
  }

 private:
  void Answer(const std::uint8_t* command, std::size_t size) {
    std::array<std::uint8_t, 64> response{};
    response[0] = command[0];
    response[1] = 0x00;  // success
    switch (command[0]) {
      case 0x60:  // SET SRAM SETTINGS: byte 7 bit 7 = alter GP designation, bytes 8..11 = GP0..3
        if (size >= 12 && (command[7] & 0x80) != 0) {
          for (std::size_t p = 0; p < 4; ++p) sram_gp_[p] = command[8 + p];
        }
        break;
      case 0x61:  // GET SRAM SETTINGS: GP settings at 22..25
        for (std::size_t p = 0; p < 4; ++p) response[22 + p] = sram_gp_[p];
        break;
      case 0x51:  // GET GPIO VALUES: value at 2+2p, direction at 3+2p (0xEE: not a GPIO)
        for (std::size_t p = 0; p < 4; ++p) {
          const bool gpio = (sram_gp_[p] & 0x07) == 0;
          const bool input = (sram_gp_[p] & 0x08) != 0;
          response[2 + 2 * p] = gpio ? (low_[p].load() ? 0 : 1) : 0xEE;
          response[3 + 2 * p] = gpio ? (input ? 1 : 0) : 0xEE;
        }
        break;
      default:
        break;
    }
    ++requests_;
    uhid_event input{};
    input.type = UHID_INPUT2;
    input.u.input2.size = static_cast<std::uint16_t>(response.size());
    std::memcpy(input.u.input2.data, response.data(), response.size());
    [[maybe_unused]] const ssize_t n = write(fd_, &input, sizeof input);
  }

  std::mutex mutex_;
  int fd_ = -1;
  std::array<std::uint8_t, 4> sram_gp_{};
  std::array<std::atomic<bool>, 4> low_{};
  std::atomic<std::uint64_t> requests_{0};
};

// ------------------------------------------------------------------ commands

const std::map<std::string, int> kKeys = {{"r", KEY_R},           {"1", KEY_1},        {"2", KEY_2},
                                          {"3", KEY_3},           {"4", KEY_4},        {"s", KEY_S},
                                          {"ctrl", KEY_LEFTCTRL}, {"alt", KEY_LEFTALT}};

class Devices {
 public:
  void Run(const std::string& command) {
    std::istringstream in(command);
    std::string verb;
    in >> verb;
    const auto need = [&](auto&... values) {
      ((in >> values), ...);
      if (!in) throw std::runtime_error("bad arguments");
    };
    if (verb == "pen" || verb == "board" || verb == "keyboard") {
      std::string what;
      need(what);
      const bool plug = what == "plug";
      if (!plug && what != "unplug") throw std::runtime_error("plug or unplug");
      if (verb == "pen") plug ? pen_.Plug() : pen_.Unplug();
      if (verb == "keyboard") plug ? keyboard_.Plug() : keyboard_.Unplug();
      if (verb == "board") plug ? board_.Plug() : board_.Unplug();
    } else if (verb == "down") {
      double x, y, p, tilt;
      need(x, y, p, tilt);
      pen_.Down(x, y, p, tilt);
    } else if (verb == "drag") {
      double x, y, seconds, p, tilt;
      need(x, y, seconds, p, tilt);
      pen_.Drag(x, y, seconds, p, tilt);
    } else if (verb == "up") {
      pen_.Up();
    } else if (verb == "token") {
      int n;
      std::string state;
      need(n, state);
      if (n < 1 || n > 4) throw std::runtime_error("token 1-4");
      board_.SetToken(n - 1, state == "on");
    } else if (verb == "key") {
      std::string name, action;
      need(name, action);
      const auto it = kKeys.find(name);
      if (it == kKeys.end()) throw std::runtime_error("unknown key " + name);
      if (action == "down" || action == "tap") keyboard_.Key(it->second, true);
      if (action == "tap") Sleep(0.1);
      if (action == "up" || action == "tap") keyboard_.Key(it->second, false);
    } else if (verb == "chord") {
      double seconds;
      need(seconds);
      for (const char* k : {"ctrl", "alt", "s"}) keyboard_.Key(kKeys.at(k), true), Sleep(0.05);
      Sleep(seconds);
      for (const char* k : {"s", "alt", "ctrl"}) keyboard_.Key(kKeys.at(k), false), Sleep(0.05);
    } else if (verb == "wait") {
      double seconds;
      need(seconds);
      Sleep(seconds);
    } else {
      throw std::runtime_error("unknown command");
    }
  }

  Mcp2221& board() { return board_; }

 private:
  Pen pen_;
  Keyboard keyboard_;
  Mcp2221 board_;
};

int Hold(const char* path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<char> held((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (held.empty()) return 2;
  std::printf("holding %zu bytes\n", held.size());
  std::fflush(stdout);
  for (;;) pause();
}

int CaptureWait(const char* path, double from_s, bool loud, double dbfs, double window_s,
                double timeout_s) {
  constexpr double kRate = 48000.0;
  constexpr std::size_t kFrameBytes = 2 * sizeof(float);
  const double threshold = std::pow(10.0, dbfs / 20.0);
  const auto window = static_cast<std::size_t>(std::max(1.0, window_s * kRate));
  // The window slides in 10 ms hops; its sum of squares is kept from per-hop sums.
  const auto hop = static_cast<std::size_t>(kRate / 100.0);
  const std::size_t hops_per_window = std::max<std::size_t>(1, (window + hop - 1) / hop);
  std::vector<double> hop_energy;
  std::size_t next_frame = static_cast<std::size_t>(std::max(0.0, from_s) * kRate);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  std::vector<float> buffer(2 * hop);
  for (;;) {
    std::ifstream in(path, std::ios::binary);
    if (in) {
      in.seekg(static_cast<std::streamoff>(next_frame * kFrameBytes));
      while (in.read(reinterpret_cast<char*>(buffer.data()),
                     static_cast<std::streamsize>(buffer.size() * sizeof(float)))) {
        double energy = 0.0;
        for (std::size_t i = 0; i < hop; ++i) energy += double(buffer[2 * i]) * buffer[2 * i];
        hop_energy.push_back(energy);
        next_frame += hop;
        if (hop_energy.size() < hops_per_window) continue;
        double sum = 0.0;
        for (std::size_t i = hop_energy.size() - hops_per_window; i < hop_energy.size(); ++i)
          sum += hop_energy[i];
        const double rms = std::sqrt(sum / double(hops_per_window * hop));
        if (loud ? rms > threshold : rms < threshold) {
          std::printf("%.3f\n", double(next_frame) / kRate);
          return 0;
        }
      }
    }
    if (std::chrono::steady_clock::now() > deadline) {
      std::fprintf(stderr, "capture-wait: no %s stretch after %.2f s within %.0f s\n",
                   loud ? "loud" : "quiet", from_s, timeout_s);
      return 1;
    }
    Sleep(0.05);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "The visitor's devices inside the appliance VM (uinput pen and keyboard, uhid "
      "MCP2221A), driven by commands on a FIFO; or one of the helper modes below.",
      "fake_devices"};
  std::string control_path, status_path;
  app.add_option("control_fifo", control_path, "FIFO the commands arrive on, one per line");
  app.add_option("status_file", status_path, "file each command's \"ok N\" or \"error N\" goes to");
  CLI::App* hold = app.add_subcommand("hold", "read FILE into memory, say so, and sleep");
  std::string hold_path;
  hold->add_option("file", hold_path, "the file to hold")->required();
  CLI::App* wait = app.add_subcommand(
      "capture-wait",
      "wait for the first WINDOW_S stretch of the speaker channel from FROM_S on whose RMS is "
      "above (loud) or below (quiet) DBFS; print its end (capture seconds) or exit 1 after "
      "TIMEOUT_S");
  std::string capture_path, mode;
  double from_s = 0.0, dbfs = 0.0, window_s = 0.0, timeout_s = 0.0;
  wait->add_option("capture", capture_path, "float32 stereo 48 kHz capture arecord writes")
      ->required();
  wait->add_option("from_s", from_s, "capture time to start looking at")->required();
  wait->add_option("mode", mode, "loud or quiet")
      ->required()
      ->check(CLI::IsMember({"loud", "quiet"}));
  wait->add_option("dbfs", dbfs, "RMS threshold, dBFS")->required();
  wait->add_option("window_s", window_s, "stretch length, s")->required();
  wait->add_option("timeout_s", timeout_s, "wall-clock time to give up after, s")->required();
  app.require_subcommand(0, 1);
  // Without a mode both files are needed (CLI11 cannot say "required unless a subcommand").
  app.callback([&] {
    if (app.get_subcommands().empty() && status_path.empty()) {
      throw CLI::RequiredError(control_path.empty() ? "control_fifo" : "status_file");
    }
  });
  if (const int code = sas::kiosk::ParseProgramCommandLine(app, argc, argv); code >= 0) return code;
  if (hold->parsed()) return Hold(hold_path.c_str());
  if (wait->parsed()) {
    return CaptureWait(capture_path.c_str(), from_s, mode == "loud", dbfs, window_s, timeout_s);
  }
  Devices devices;
  std::atomic<bool> stop{false};
  std::thread uhid([&] { devices.board().Serve(stop); });
  std::FILE* status = std::fopen(status_path.c_str(), "a");
  if (status == nullptr) return 1;
  // Held open for reading and writing: a writer that comes and goes never ends our reads.
  const int control = open(control_path.c_str(), O_RDWR | O_CLOEXEC);
  if (control < 0) return 1;
  std::FILE* in = fdopen(control, "r");
  char line[512];
  long n = 0;
  while (std::fgets(line, sizeof line, in) != nullptr) {
    std::string command(line);
    while (!command.empty() && (command.back() == '\n' || command.back() == '\r'))
      command.pop_back();
    if (command.empty()) continue;
    ++n;
    if (command == "quit") break;
    try {
      devices.Run(command);
      std::fprintf(status, "ok %ld %s\n", n, command.c_str());
    } catch (const std::exception& e) {
      std::fprintf(status, "error %ld %s: %s\n", n, command.c_str(), e.what());
    }
    std::fflush(status);
  }
  stop.store(true);
  uhid.join();
  return 0;
}
