#pragma once
// The live kiosk (issue 7): the full-screen SDL window, the pen (libinput, else SDL mouse/touch),
// the token switches and record button, the microphone and the speaker/transducer, all wired to
// one KioskEngine, plus the staff panel, the watchdog and the device status board.
//
//   sketch-a-scratch kiosk [--config FILE]   (FILE default /etc/sketch-a-scratch/kiosk.toml)

#include <cstdio>
#include <string>
#include <vector>

namespace sas::app {

// Runs until SIGTERM/SIGINT (systemd's stop). Returns the exit code; 1 when no window opens.
int RunKiosk(const std::vector<std::string>& args, std::FILE* out, std::FILE* err);

}  // namespace sas::app
