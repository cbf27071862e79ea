#pragma once
// Gestures: what the pen did over time, as a time series of (t, x, y, pressure, tilt), and the
// stream of synth::ProbeCommand it turns into at a control rate. Used by the offline renderer and
// tests; the live kiosk maps pen events the same way (GestureMapping), one event at a time.
//
// CSV format (one header line, then one row per sample; '#' comment lines and blank lines are
// skipped):
//     t,x,y,pressure,tilt
//     0.000,10.0,20.0,0.0,10
// t in seconds (strictly increasing, from 0), x and y in millimetres on the surface (the height
// field's origin is its top-left sample), pressure 0..1 (0 = pen up), tilt in degrees from upright
// (0..90). Between rows everything is interpolated linearly; after the last row the pen is lifted.
//
// Mapping (paper §4): velocity = distance between successive rows / their time
// difference (constant along a segment: the paper's Δx = v Δt), direction = the segment's unit
// vector; normal force = pressure · max_force_n (default 0..2 N); penetration = pressure ·
// max_penetration_m (light touch feels only the peaks, full pressure the whole relief); width
// grows linearly with tilt from min_width_mm (upright: scratch) to max_width_mm (max_tilt_deg:
// rub); style = scrape below rub_width_mm, rub above. The passive mode (automatic exploration at a
// set velocity) is just a gesture: PassiveSweep().

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

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

struct GestureMapping {
  double control_rate_hz = 1000.0;    // commands per second (a pen reports at 100..1000 Hz)
  double max_force_n = 2.0;           // normal force at full pressure
  double max_penetration_m = 0.2e-3;  // penetration at full pressure (render: the field's relief)
  double min_width_mm = 0.3;          // upright pen: a scratch
  double max_width_mm = 6.0;          // fully tilted pen: a rub
  double max_tilt_deg = 60.0;         // tilt giving max_width_mm
  double rub_width_mm = 2.0;          // widths at or above this rub, below it scrape
  std::optional<synth::ProbeStyle> style;  // forces one style (e.g. roll) instead of by width
};

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

// Pen tilt -> probe width and style, as above (also for the live kiosk).
double WidthFromTiltMm(double tilt_deg, const GestureMapping& mapping);
// Its inverse within the mapping's range: the tilt that gives a probe `width_mm` wide.
double TiltFromWidthDeg(double width_mm, const GestureMapping& mapping);
synth::ProbeStyle StyleFromWidth(double width_mm, const GestureMapping& mapping);
// The probe width for a pen held at `tilt_deg` in `style`: the tilt's width, except for a roll,
// whose ball is the pen's own and does not grow when the pen leans (min_width_mm).
double ProbeWidthMm(synth::ProbeStyle style, double tilt_deg, const GestureMapping& mapping);

}  // namespace sas::kiosk
