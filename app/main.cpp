// sketch-a-scratch: the kiosk's one executable. With no arguments it starts the kiosk on the
// display, or, on a machine with no display, runs its headless default. Subcommands serve staff
// and engineers (device list, offline render, calibration).
#include <cstdio>
#include <string>
#include <vector>

#include "files/kiosk_config.h"
#include "headless_demo.h"
#include "kiosk/device_configs.h"
#include "live_kiosk.h"
#include "platform/discovery.h"
#include "sas/version.h"
#include "tools/command_line.h"
#include "tools/impact_command.h"
#include "texture_command.h"
#include "tools/render_command.h"
#include "ui/display_probe.h"

namespace {

using Args = std::vector<std::string>;
using sas::kiosk::kExitOk;

constexpr const char* kCommands =
    "Commands (each answers --help):\n"
    "  demo [--out DIR] [--quick]  the headless visit even when there is a display\n"
    "  kiosk [--config FILE] [--state-dir DIR]\n"
    "                              the kiosk (exits 1 when there is no display); also --kiosk\n"
    "  render --out FILE.wav ...   render a material, surface and gesture to a 2-channel WAV\n"
    "  impact ...                  one probe impact on a rigid wall, JSON vs the closed form\n"
    "  texture new|check|preview|install ...\n"
    "                              a curator's own texture: from a photo or scan, checked, "
    "installed\n"
    "Exit status: 0 ok, 1 runtime error, 2 usage error.";

int RunDemo(const Args& args) {
  sas::app::HeadlessOptions options;
  CLI::App app(
      "Runs the scripted headless visit (the kiosk's engine, offline), writing WAVs, "
      "PNGs and visit.txt.",
      "demo");
  sas::app::AddHeadlessOptions(app, options);
  app.add_option("--config", options.config_path,
                 "a kiosk.toml whose tokens ([textures]) and staff textures (staff_dir) the visit "
                 "shows (default: the shipped four)");
  if (const int code = sas::kiosk::ParseCommandLine(app, args, stdout, stderr); code >= 0) {
    return code;
  }
  return sas::app::RunHeadlessDemo(options, stdout, stderr);
}

// Prints every device class, found or not, and says what the kiosk will do without it, with the
// device choices of the configuration at `config_path` (the built-in ones when it cannot be used,
// which the report then says).
void PrintDeviceReport(const sas::ui::DisplayInfo& display, const std::string& config_path) {
  sas::platform::DeviceSelection selection;
  sas::platform::DeviceFinding config{"config", true, config_path};
  try {
    selection = sas::kiosk::DeviceSelectionFor(sas::kiosk::LoadKioskConfig(config_path));
  } catch (const sas::kiosk::ConfigError& error) {
    config = {"config", false,
              std::string(error.what()) + " -- the devices below are for the built-in defaults"};
  }
  auto report = sas::platform::DiscoverDevices(selection);
  report.insert(report.begin(), config);
  if (display.available) {
    report.insert(report.begin(), {"display", true,
                                   display.driver + " " + std::to_string(display.width_px) + "x" +
                                       std::to_string(display.height_px) + " @ " +
                                       std::to_string(display.refresh_hz) + " Hz"});
  } else {
    report.insert(report.begin(), {"display", false, "no display (" + display.problem + ")"});
  }
  for (const auto& finding : report) {
    std::printf("  %-8s %-9s %s\n", finding.category.c_str(), finding.found ? "found" : "NOT FOUND",
                finding.detail.c_str());
  }
}

// No command: the kiosk on the display, or the headless visit when there is none. With a display
// the kiosk always runs (silent without an audio device): never the demo on the box.
int RunDefault(const Args& args) {
  sas::app::HeadlessOptions options;
  bool version = false;
  bool list_devices = false;
  std::string config_path = "/etc/sketch-a-scratch/kiosk.toml";
  CLI::App app(
      "Sketch-a-Scratch: with no command, the kiosk on the display, or with no display "
      "the headless visit (--out, --quick shape it).",
      "");
  app.footer(kCommands);
  sas::app::AddHeadlessOptions(app, options);
  app.add_flag("--version", version, "print the version");
  app.add_flag("--list-devices", list_devices,
               "print the display, audio devices, GPIO chips, USB adapters and tablets found, and "
               "which the kiosk would use with its configuration");
  app.add_option("--config", config_path,
                 "the kiosk's configuration file, for --list-devices and the kiosk (default "
                 "/etc/sketch-a-scratch/kiosk.toml)");
  if (const int code = sas::kiosk::ParseCommandLine(app, args, stdout, stderr); code >= 0) {
    return code;
  }
  if (version) {
    std::printf("sketch-a-scratch %s\n", sas::kVersion);
    return kExitOk;
  }
  if (list_devices) {
    PrintDeviceReport(sas::ui::ProbeDisplay(), config_path);
    return kExitOk;
  }
  std::printf("Sketch-a-Scratch %s\n", sas::kVersion);
  const auto display = sas::ui::ProbeDisplay();
  std::printf("Hardware:\n");
  PrintDeviceReport(display, config_path);
  std::fflush(stdout);
  // --out/--quick only shape the headless visit: the kiosk on a display takes its configuration.
  if (display.available) return sas::app::RunKiosk({"--config", config_path}, stdout, stderr);
  std::printf("No display (%s).\n", display.problem.c_str());
  return sas::app::RunHeadlessDemo(options, stdout, stderr);
}

}  // namespace

int main(int argc, char** argv) {
  const Args args(argv + 1, argv + argc);
  // A subcommand takes the rest of the line; anything else (options, nothing, a stray word) is
  // the top-level command line, whose parser reports what it does not know.
  const std::string command = args.empty() ? "" : args[0];
  const Args rest(args.begin() + (args.empty() ? 0 : 1), args.end());
  if (command == "help") return RunDefault({"--help"});
  if (command == "render") return sas::kiosk::RunRenderCommand(rest, stdout, stderr);
  if (command == "impact") return sas::kiosk::RunImpactCommand(rest, stdout, stderr);
  if (command == "demo") return RunDemo(rest);
  if (command == "texture") return sas::app::RunTextureCommand(rest, stdout, stderr);
  if (command == "kiosk" || command == "--kiosk") return sas::app::RunKiosk(rest, stdout, stderr);
  return RunDefault(args);
}
