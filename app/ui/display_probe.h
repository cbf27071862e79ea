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

// True for SDL's virtual drivers (offscreen, dummy) unless SDL_VIDEODRIVER names that driver: SDL
// falls back to them when x11, wayland and KMSDRM all fail, and nobody can see such a window.
bool IsUnrequestedVirtualDriver(const std::string& driver);

}  // namespace sas::ui
