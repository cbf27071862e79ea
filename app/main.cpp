// sketch-a-scratch: the kiosk's one executable. With no arguments it starts the kiosk on the
// display, or, on a machine with no display, runs its headless default. Subcommands serve staff
// and engineers (device list, offline render, calibration).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "kiosk/impact_command.h"
#include "kiosk/render_command.h"
#include "platform/discovery.h"
#include "sas/version.h"
#include "ui/display_probe.h"

namespace {

using Args = std::vector<std::string>;

void PrintUsage() {
  std::printf(
      "usage: sketch-a-scratch [command] [options]\n"
      "  (no command)     start the kiosk; headless default when there is no display\n"
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

int RunDefault() {
  std::printf("Sketch-a-Scratch %s\n", sas::kVersion);
  const auto display = sas::ui::ProbeDisplay();
  std::printf("Hardware:\n");
  PrintDeviceReport(display);
  if (!display.available) {
    std::printf(
        "No display: running the headless default (hardware report only in this "
        "version).\n");
  } else {
    std::printf("Display found; the full-screen kiosk is not built yet in this version.\n");
  }
  return EXIT_SUCCESS;
}

}  // namespace

int main(int argc, char** argv) {
  const Args args(argv + 1, argv + argc);
  if (args.empty()) return RunDefault();
  const std::string& command = args[0];
  if (command == "--help" || command == "-h" || command == "help") {
    PrintUsage();
    return EXIT_SUCCESS;
  }
  if (command == "--version") {
    std::printf("sketch-a-scratch %s\n", sas::kVersion);
    return EXIT_SUCCESS;
  }
  if (command == "render") {
    return sas::kiosk::RunRenderCommand(Args(args.begin() + 1, args.end()), stdout, stderr);
  }
  if (command == "impact") {
    return sas::kiosk::RunImpactCommand(Args(args.begin() + 1, args.end()), stdout, stderr);
  }
  if (command == "--list-devices") {
    PrintDeviceReport(sas::ui::ProbeDisplay());
    return EXIT_SUCCESS;
  }
  std::fprintf(stderr, "sketch-a-scratch: unknown command '%s'\n", command.c_str());
  PrintUsage();
  return 2;
}
