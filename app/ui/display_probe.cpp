// Display probing through SDL2 (see display_probe.h).
#include "ui/display_probe.h"

#include <SDL.h>

namespace sas::ui {

bool IsUnrequestedVirtualDriver(const std::string& driver) {
  // SDL 2.26 falls back to its virtual `offscreen` driver when x11, wayland and KMSDRM all fail.
  const char* requested = SDL_getenv("SDL_VIDEODRIVER");
  const bool virtual_driver = driver == "offscreen" || driver == "dummy";
  return virtual_driver && (requested == nullptr || driver != requested);
}

DisplayInfo ProbeDisplay() {
  DisplayInfo info;
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
