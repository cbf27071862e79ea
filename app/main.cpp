// sketch-a-scratch: the kiosk's one executable. With no arguments it starts the kiosk on the
// display, or, on a machine with no display, runs its headless default. Subcommands serve staff
// and engineers (device list, offline render, calibration).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "headless_demo.h"
#include "kiosk/impact_command.h"
#include "kiosk/render_command.h"
#include "live_kiosk.h"
#include "platform/discovery.h"
#include "sas/version.h"
#include "ui/display_probe.h"

namespace {

using Args = std::vector<std::string>;

int RunDemo(const Args& args) {
  sas::app::HeadlessOptions options;
  std::string error;
  if (!sas::app::ParseHeadlessArgs(args, &options, &error)) {
    std::fprintf(stderr, "sketch-a-scratch: %s\n", error.c_str());
    return 2;
  }
  return sas::app::RunHeadlessDemo(options, stdout, stderr);
}

void PrintUsage() {
  std::printf(
      "usage: sketch-a-scratch [command] [options]\n"
      "  (no command) [--out DIR]\n"
      "                   start the kiosk; with no display, the headless default: a scripted\n"
      "                   visit written as WAVs and PNGs to DIR (default sketch-a-scratch-demo)\n"
      "  demo [--out DIR] the headless visit even when there is a display\n"
      "  kiosk [--config FILE]  the kiosk (fails when there is no display)\n"
      "  render ...       render a material, surface and gesture to a 2-channel WAV\n"
      "                   (sketch-a-scratch render --help)\n"
      "  impact ...       simulate one probe impact on a rigid wall, print JSON vs closed form\n"
      "  --list-devices   print the audio devices, GPIO chips, USB adapters and tablets found\n"
      "  --version        print the version\n"
      "  --help           this text\n");
}

// Prints every device class, found or not, and says what the kiosk will do without it.
void PrintDeviceReport(const sas::ui::DisplayInfo& display) {
  auto report = sas::platform::DiscoverDevices();
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
  std::printf("Sketch-a-Scratch %s\n", sas::kVersion);
  const auto display = sas::ui::ProbeDisplay();
  std::printf("Hardware:\n");
  PrintDeviceReport(display);
  std::fflush(stdout);
  // --out/--quick only shape the headless visit: the kiosk on a display takes its configuration.
  if (display.available) return sas::app::RunKiosk({}, stdout, stderr);
  std::printf("No display (%s).\n", display.problem.c_str());
  return RunDemo(args);
}

}  // namespace

int main(int argc, char** argv) {
  const Args args(argv + 1, argv + argc);
  if (args.empty() || args[0].rfind("--out", 0) == 0 || args[0] == "--quick") {
    return RunDefault(args);
  }
  const std::string& command = args[0];
  const Args rest(args.begin() + 1, args.end());
  if (command == "--help" || command == "-h" || command == "help") {
    PrintUsage();
    return EXIT_SUCCESS;
  }
  if (command == "--version") {
    std::printf("sketch-a-scratch %s\n", sas::kVersion);
    return EXIT_SUCCESS;
  }
  if (command == "render") {
    return sas::kiosk::RunRenderCommand(rest, stdout, stderr);
  }
  if (command == "impact") return sas::kiosk::RunImpactCommand(rest, stdout, stderr);
  if (command == "demo") return RunDemo(rest);
  if (command == "kiosk" || command == "--kiosk") return sas::app::RunKiosk(rest, stdout, stderr);
  if (command == "--list-devices") {
    PrintDeviceReport(sas::ui::ProbeDisplay());
    return EXIT_SUCCESS;
  }
  std::fprintf(stderr, "sketch-a-scratch: unknown command '%s'\n", command.c_str());
  PrintUsage();
  return 2;
}
