#pragma once
// One normalised stylus reading, whatever produced it: SDL mouse (fallback; no pressure or tilt),
// SDL touch finger (pressure when the panel reports it) or, later, the pen through libinput's
// tablet-tool API (platform/pen). Everything downstream — the tip deformation here, the probe
// mapping in the kiosk (pressure -> penetration/normal force, tilt -> probe width, paper §4) —
// reads only this struct, so the three sources are interchangeable.

#include <cmath>
#include <cstdint>

namespace sas::ui {

enum class StylusSource : std::uint8_t { kMouse, kTouch, kPen };

struct StylusSample {
  std::int64_t time_ns = 0;  // CLOCK_MONOTONIC, the time base of every input event
  float x_px = 0.0f;         // screen pixels, origin top-left
  float y_px = 0.0f;
  float pressure = 0.0f;    // 0..1 (0 whenever the tip is up)
  float tilt_x_deg = 0.0f;  // pen tilt towards +x / +y; 0 = upright (mouse and touch: always 0)
  float tilt_y_deg = 0.0f;
  bool tip_down = false;
  StylusSource source = StylusSource::kMouse;

  // Angle between the pen and the screen normal, from the two tilt components.
  float TiltDeg() const {
    constexpr float kDegToRad = 3.14159265358979f / 180.0f;
    const float tx = std::tan(tilt_x_deg * kDegToRad);
    const float ty = std::tan(tilt_y_deg * kDegToRad);
    return std::atan(std::sqrt(tx * tx + ty * ty)) / kDegToRad;
  }
};

}  // namespace sas::ui
