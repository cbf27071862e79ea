#pragma once
// Gestures: what the pen did over time, as a time series of (t, x, y, pressure, tilt), and the
// stream of synth::ProbeCommand it turns into at a control rate. Used by the offline renderer and
// tests; the live kiosk maps pen readings through the same pen mapping (pen_mapping.h), one
// reading at a time.
//
// CSV format (one header line, then one row per sample; '#' comment lines and blank lines are
// skipped):
//     t,x,y,pressure,tilt
//     0.000,10.0,20.0,0.0,10
// t in seconds (strictly increasing, from 0), x and y in millimetres on the surface (the height
// field's origin is its top-left sample), pressure 0..1 (0 = pen up), tilt in degrees from upright
// (0..90). Between rows everything is interpolated linearly; after the last row the pen is lifted.
//
// Mapping: velocity = distance between successive rows / their time difference (constant along a
// segment: the paper's Δx = v Δt), direction = the segment's unit vector; pressure and tilt go
// through the pen mapping (pen_mapping.h) with max_penetration_m as the relief to feel. The
// passive mode (automatic exploration at a set velocity) is just a gesture: PassiveSweep().

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "kiosk/pen_mapping.h"
#include "synth/probe_command.h"

namespace sas::kiosk {

class GestureError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct GestureSample {
  double t_s = 0.0;
  double x_mm = 0.0;
  double y_mm = 0.0;
  double pressure = 0.0;  // 0..1
  double tilt_deg = 0.0;  // 0 = upright
};

struct Gesture {
  std::string name;
  std::vector<GestureSample> samples;  // at least two, t strictly increasing
  double landing_speed_mps = 0.1;      // how fast the tip meets the surface when it goes down

  double duration_s() const { return samples.empty() ? 0.0 : samples.back().t_s; }
};

// Below this pressure a gesture's pen is not touching (sensor noise).
inline constexpr double kGesturePenUpPressure = 1e-3;

// The gesture at `t_s`: its rows interpolated linearly, held at the first row before it and at the
// last row after it.
GestureSample GestureAt(const Gesture& gesture, double t_s);

// A probe command at an absolute frame of the rendering (frame 0 = gesture time 0).
struct TimedCommand {
  std::int64_t frame = 0;
  synth::ProbeCommand command;
};

// Parses CSV text; `source_name` names the file in messages ("<file>:<line>: <column>: <what>").
Gesture ParseGestureCsv(const std::string& text, const std::string& source_name);
Gesture LoadGestureCsv(const std::string& path);

// The built-in gestures: "slow stroke", "fast scribble", "tap", "passive sweep" (spaces, '-' and
// '_' are interchangeable). They stay within x 5..75 mm, y 5..35 mm (the built-in profiles).
std::vector<std::string> BuiltinGestureNames();
std::optional<Gesture> FindBuiltinGesture(const std::string& name);
// The paper's passive mode: pen down at (x0, y0) with constant pressure and no tilt, moving along
// +x at `velocity_mps` for `length_mm`, then lifted.
Gesture PassiveSweep(double velocity_mps, double length_mm, double pressure, double x0_mm = 5.0,
                     double y0_mm = 20.0);

// The command stream: one command per control tick from t = 0 to the end of the gesture, then a
// final pen-up. Frames are round(t · sample_rate_hz), strictly increasing.
std::vector<TimedCommand> GestureToCommands(const Gesture& gesture, const GestureMapping& mapping,
                                            double sample_rate_hz);

}  // namespace sas::kiosk
