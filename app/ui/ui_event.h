#pragma once
// What the kiosk window reports to the wiring each time it is polled: stylus events (already in
// screen pixels with pressure), the keyboard stand-ins for the token switches and the record
// button (keys 1-4, 0 and R), the staff chord, and display changes. Quit requests, Alt-F4,
// Escape and window-close never appear here: a visitor has no way out.

#include <cstdint>

#include "platform/pen/pen_reading.h"

namespace sas::ui {

struct UiEvent {
  enum class Kind : std::uint8_t {
    kPointerDown,  // tip touched the screen; `stylus` holds position and pressure
    kPointerMove,  // moved, tip down or hovering (stylus.tip_down says which), or a resting press
                   // grew or the roll changed (stylus.kind kButton: the position is the last one)
    kPointerUp,    // tip lifted; `stylus` is the last position with pressure 0
    kTokenKey,     // keyboard token fallback: `token` 0..3 for keys 1..4, -1 for key 0
    kRecordKey,    // keyboard record button: `pressed` true on press, false on release
    kLanguageKey,  // the visitor's language key (L) pressed: the next language
    kStaffChord,   // the staff chord completed; `pressed` = staff panel now open
    kRedraw,       // the window was exposed or resized: draw a full frame even if nothing changed
  };
  Kind kind = Kind::kPointerMove;
  std::int64_t time_ns = 0;  // CLOCK_MONOTONIC
  platform::PenReading stylus{};
  int token = -1;
  bool pressed = false;
};

}  // namespace sas::ui
