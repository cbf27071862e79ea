#pragma once
// Finds out whether there is a screen to draw on, without opening a window. The kiosk decides
// from this between full-screen exploration and its headless default (a scripted visit).

#include <string>

namespace sas::ui {

struct DisplayInfo {
  bool available = false;
  std::string driver;  // SDL video driver that initialised (x11, wayland, KMSDRM, offscreen...)
  int width_px = 0;    // desktop mode of display 0: the native resolution we go full-screen at
  int height_px = 0;
  int refresh_hz = 0;
  std::string problem;  // why no display, when !available
};

// Initialises SDL's video subsystem (honouring SDL_VIDEODRIVER), reads display 0's desktop mode
// and shuts video down again. Never throws.
DisplayInfo ProbeDisplay();

// With no Wayland compositor anyone could reach (WAYLAND_DISPLAY, WAYLAND_SOCKET and
// XDG_RUNTIME_DIR all unset, as on CI, a headless machine or a system service), tells SDL to
// leave its wayland driver out of this process's video starts: its probe would only make
// libwayland print "error: XDG_RUNTIME_DIR is invalid or not set" on stderr. Nothing changes when
// SDL_VIDEODRIVER names drivers, or when any of those variables is set (a WAYLAND_DISPLAY without
// XDG_RUNTIME_DIR is a real mistake, and libwayland still says so). Called before every
// SDL_InitSubSystem(SDL_INIT_VIDEO).
void SkipUnreachableWayland();

// True for SDL's virtual drivers (offscreen, dummy) unless SDL_VIDEODRIVER names that driver: SDL
// falls back to them when x11, wayland and KMSDRM all fail, and nobody can see such a window.
bool IsUnrequestedVirtualDriver(const std::string& driver);

}  // namespace sas::ui
