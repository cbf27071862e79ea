// Display probing through SDL2 (see display_probe.h).
#include "ui/display_probe.h"

#include <SDL.h>

#include <string>

namespace sas::ui {

void SkipUnreachableWayland() {
  // SDL_GetHint falls back to the SDL_VIDEODRIVER environment variable.
  if (SDL_GetHint(SDL_HINT_VIDEODRIVER) != nullptr) return;
  for (const char* name : {"WAYLAND_DISPLAY", "WAYLAND_SOCKET", "XDG_RUNTIME_DIR"}) {
    const char* value = SDL_getenv(name);
    if (value != nullptr && *value != '\0') return;
  }
  // Every driver in SDL's own order but wayland: SDL tries a list in the order given, so the
  // choice is what it would have made (x11, KMSDRM, then the virtual offscreen fallback).
  std::string drivers;
  for (int i = 0; i < SDL_GetNumVideoDrivers(); ++i) {
    const std::string driver = SDL_GetVideoDriver(i);
    if (driver == "wayland") continue;
    drivers += (drivers.empty() ? "" : ",") + driver;
  }
  SDL_SetHint(SDL_HINT_VIDEODRIVER, drivers.c_str());
}

bool IsUnrequestedVirtualDriver(const std::string& driver) {
  // SDL 2.26 falls back to its virtual `offscreen` driver when x11, wayland and KMSDRM all fail.
  const char* requested = SDL_getenv("SDL_VIDEODRIVER");
  const bool virtual_driver = driver == "offscreen" || driver == "dummy";
  return virtual_driver && (requested == nullptr || driver != requested);
}

DisplayInfo ProbeDisplay() {
  DisplayInfo info;
  SkipUnreachableWayland();
  if (SDL_InitSubSystem(SDL_INIT_VIDEO) != 0) {
    info.problem = SDL_GetError();
    return info;
  }
  if (const char* driver = SDL_GetCurrentVideoDriver()) info.driver = driver;
  // That is no screen a visitor can see: count it only when asked for by name (render tests).
  if (IsUnrequestedVirtualDriver(info.driver)) {
    info.problem =
        "no x11, wayland or KMSDRM display (only SDL's virtual '" + info.driver + "' driver)";
    SDL_QuitSubSystem(SDL_INIT_VIDEO);
    return info;
  }
  SDL_DisplayMode mode{};
  if (SDL_GetNumVideoDisplays() < 1) {
    info.problem = "video driver '" + info.driver + "' reports no display";
  } else if (SDL_GetDesktopDisplayMode(0, &mode) != 0) {
    info.problem = SDL_GetError();
  } else {
    info.available = true;
    info.width_px = mode.w;
    info.height_px = mode.h;
    info.refresh_hz = mode.refresh_rate;
  }
  SDL_QuitSubSystem(SDL_INIT_VIDEO);
  return info;
}

}  // namespace sas::ui
