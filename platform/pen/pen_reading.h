#pragma once
// One pen reading, whatever produced it: the tablet through libinput (pen_source.h), the SDL
// mouse or touch finger the window falls back to (no tilt; the mouse has no pressure either), or
// a script (the headless visit, the attract screen's passive stroke). It travels unchanged from
// the device to the probe: the window's dent reads it, the staff panel shows it and the kiosk's
// one pen mapping (app/kiosk/pen_mapping.h) turns it into a probe command (pressure -> normal
// force and penetration, tilt -> probe width and style, paper §4; a held barrel button -> a roll).
// Standard library only, so every layer can hold it.

#include <cmath>
#include <cstdint>

namespace sas::platform {

enum class PenReadingKind : std::uint8_t {
  kMotion,  // axes changed (tip up or down)
  kTipDown,
  kTipUp,
  kProximityIn,
  kProximityOut,
  kButton,  // a barrel button was pressed or released (barrel_button says which)
};

// Who made the reading. Only a tablet (or a script playing one) has a tilt that counts: mouse and
// touch get the texture's own probe instead.
enum class PenOrigin : std::uint8_t { kMouse, kTouch, kTablet };

struct PenReading {
  std::int64_t time_ns = 0;  // CLOCK_MONOTONIC (a headless run: its virtual clock)
  PenReadingKind kind = PenReadingKind::kMotion;
  double x_px = 0.0;  // screen pixels, origin top-left
  double y_px = 0.0;
  double pressure = 0.0;    // 0..1, and 0 whenever the tip is up
  double tilt_x_deg = 0.0;  // pen tilt towards +x / +y; 0 = upright (mouse and touch: always 0)
  double tilt_y_deg = 0.0;
  bool tip_down = false;
  bool in_proximity = false;  // a tablet's hover range (mouse and touch: not reported)
  // A barrel button of the pen is held (BTN_STYLUS, BTN_STYLUS2 or BTN_STYLUS3): the stroke rolls.
  // In the mouse/touch fallback the right mouse button or the roll key stands in for it, as keys
  // 1-4 stand in for the token switches.
  bool barrel_button = false;
  PenOrigin origin = PenOrigin::kMouse;

  bool HasTilt() const { return origin == PenOrigin::kTablet; }

  // Angle between the pen and the screen normal. A pen leaning along one axis (every script)
  // gives that axis's angle as it is, not after a tan/atan round trip.
  double TiltDeg() const {
    if (tilt_y_deg == 0.0) return std::abs(tilt_x_deg);
    if (tilt_x_deg == 0.0) return std::abs(tilt_y_deg);
    constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
    const double tx = std::tan(tilt_x_deg * kDegToRad);
    const double ty = std::tan(tilt_y_deg * kDegToRad);
    return std::atan(std::sqrt(tx * tx + ty * ty)) / kDegToRad;
  }
};

}  // namespace sas::platform
