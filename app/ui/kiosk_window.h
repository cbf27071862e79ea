#pragma once
// The kiosk's full-screen SDL2 window: opens at the display's native resolution (the desktop
// mode's size — a 0x0 FULLSCREEN_DESKTOP window stays 1x1 px under X with no window manager),
// borderless, cursor hidden, screensaver inhibited, not minimised when focus goes, keyboard
// grabbed. A visitor has no way out: SDL_QUIT, window-close (Alt-F4 under a window manager),
// Escape, Ctrl-Q and every other key are swallowed; SDL's SIGINT/SIGTERM handlers are disabled so
// systemd's stop still ends the process. A configurable staff chord (default Ctrl+Alt+S held for
// 1 s) toggles the staff panel flag and is reported as an event.
//
// Input mapping: mouse (fallback: no tilt, a press that grows the longer it is held) and the
// first touch finger (pressure from the panel; one without a pressure sensor presses like the
// mouse) become pen readings (platform/pen/pen_reading.h) in screen pixels with CLOCK_MONOTONIC
// timestamps; mouse events SDL synthesises from touch are dropped so one touch is one stroke.
// While a press rests (no motion for kPressReportS), a reading with the grown pressure is sent
// every kPressReportS, so a press held still pops a bubble. The right mouse button drags like the
// left one but rolls, and so does any stroke while the roll key (Space) is held: both stand in for
// the pen's barrel button. Keys 1-4 / 0 stand in for the token switches, R for the record button.
// The pen (libinput, platform/pen) produces the same reading and bypasses this window.
//
// Drawing: Present() draws a Frame (texture_view.h) — pictures as GPU textures uploaded once per
// picture, the cross-fade with alpha blending, the small deformation patch as a streaming texture,
// overlays as blended rectangles — and presents with vsync, so frames come at the display's
// refresh rate and only when the caller has one (TextureView::NeedsRedraw).

#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "ui/image_rgba.h"
#include "ui/texture_view.h"
#include "ui/ui_event.h"

namespace sas::ui {

class WindowError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct StaffChordConfig {
  std::string keys = "ctrl+alt+s";  // modifiers (ctrl, alt, shift, super) + one SDL key name
  double hold_s = 1.0;              // held this long before it counts (0 = at the key press)
};

// How the mouse (or a touch without pressure) presses: `light` at the touch, rising linearly to
// `firm` over `rise_s` held. 0.3 is the lightest press the level calibration covers, so a quick
// drag (under half a second: below 0.47) sounds like a light pen stroke; 0.9 is the firmest the
// kiosk's figures hold (pressure 0.1-0.9). Over 1.8 s the press passes 0.625 after 0.98 s: a
// bubble's pop (2.5 N, of the 4 N a full pen press stands for on the bubble wrap) comes after
// about a second held still or pressing on, as a visitor pushing on a bubble expects.
struct PressRamp {
  float light = 0.3f;
  float firm = 0.9f;
  double rise_s = 1.8;
  // The press `held_s` after the touch.
  float At(double held_s) const;
};

struct KioskWindowOptions {
  std::string title = "Sketch-a-Scratch";
  StaffChordConfig staff_chord{};
  PressRamp press{};  // the mouse has no pressure sensor
  bool vsync = true;
  bool grab_keyboard = true;  // window-manager shortcuts (Alt-Tab, Alt-F4) come to us instead
};

class KioskWindow {
 public:
  // While a mouse or touch press rests, its grown pressure is reported this often (s).
  static constexpr double kPressReportS = 0.01;

  explicit KioskWindow(KioskWindowOptions options = {});
  ~KioskWindow();
  KioskWindow(KioskWindow&&) noexcept;
  KioskWindow& operator=(KioskWindow&&) noexcept;
  KioskWindow(const KioskWindow&) = delete;
  KioskWindow& operator=(const KioskWindow&) = delete;

  // Initialises SDL video and opens the window. Throws WindowError (no display, bad chord...).
  void Open();
  void Close();
  bool is_open() const;

  // Drawable size in pixels (frames must be this size) and the display's refresh rate.
  int width_px() const;
  int height_px() const;
  int refresh_hz() const;
  std::string driver() const;
  std::string renderer_name() const;

  // Drains SDL's queue into UiEvents. With wait_ms > 0 it first sleeps up to that long for an
  // event (use when no frame is due: an idle kiosk then costs no CPU). At most `max_sdl_events`
  // of SDL's events are taken; the rest wait in SDL's queue with their timestamps for the next
  // call (which then does not sleep), so a flood of pointer motion cannot make one call long.
  std::vector<UiEvent> PollEvents(int wait_ms = 0,
                                  std::size_t max_sdl_events = static_cast<std::size_t>(-1));

  // Draws `frame` and presents it (blocks until vblank with vsync). When `read_back` is given the
  // drawn pixels are copied into it before presenting (tests, snapshots of the real path).
  void Present(const Frame& frame, ImageRgba* read_back = nullptr);

  bool staff_panel_open() const;
  void set_staff_panel_open(bool open);  // e.g. closed by the staff panel's own button

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sas::ui
