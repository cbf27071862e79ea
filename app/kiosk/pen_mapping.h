#pragma once
// The pen mapping (paper §4): what a pen asks of the probe. Every caller goes through it — the
// kiosk engine for the live pen, mouse and touch, the headless visit and the attract screen's
// passive stroke, and GestureToCommands for the offline render — so a pen held the same way
// sounds the same everywhere.
//
//   pressure (clamped to 0..1) -> normal force = pressure · max_force_n (default 0..2 N)
//                              -> penetration = pressure · the relief to feel (a light touch feels
//                                 only the peaks, full pressure the whole relief)
//   tilt from upright          -> width, linear from min_width_mm (upright: a scratch) to
//                                 max_width_mm (max_tilt_deg: a rub)
//                              -> style by that width: scrape below rub_width_mm, rub above
// An input with no tilt (mouse, touch, the passive stroke) gets the texture's own probe instead. A
// held barrel button (or its mouse/keyboard stand-in) forces a roll; a forced style (a roll
// stroke, the render command's --style) replaces the style by width and keeps the tilt's width,
// except a roll, whose ball is the pen's own and does not grow when it leans.

#include <optional>

#include "platform/pen/pen_reading.h"
#include "synth/probe_command.h"

namespace sas::kiosk {

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

// The probe a pen without tilt gets: the texture's own (texture.toml [probe]) or the voice's.
struct ProbeShape {
  double width_mm = 0.5;
  synth::ProbeStyle style = synth::ProbeStyle::kScrape;
};

// Pressure -> the command's normal force and penetration (`relief_m`: what full pressure feels).
void ApplyPenPressure(double pressure, double relief_m, const GestureMapping& mapping,
                      synth::ProbeCommand& command);
// Tilt from upright -> the command's width and style; without tilt, `untilted`. `forced` replaces
// the style either way.
void ApplyPenTilt(std::optional<double> tilt_deg, const ProbeShape& untilted,
                  std::optional<synth::ProbeStyle> forced, const GestureMapping& mapping,
                  synth::ProbeCommand& command);
// Both for one reading: its pressure, and its tilt when it has one (a tablet's, or a script's);
// its barrel button held forces a roll unless `forced` says otherwise.
void ApplyPenReading(const platform::PenReading& pen, double relief_m, const ProbeShape& untilted,
                     std::optional<synth::ProbeStyle> forced, const GestureMapping& mapping,
                     synth::ProbeCommand& command);

// The pieces of the tilt mapping above, for callers that pick a width or a tilt themselves.
double WidthFromTiltMm(double tilt_deg, const GestureMapping& mapping);
// Its inverse within the mapping's range: the tilt that gives a probe `width_mm` wide.
double TiltFromWidthDeg(double width_mm, const GestureMapping& mapping);
synth::ProbeStyle StyleFromWidth(double width_mm, const GestureMapping& mapping);
// The probe width for a pen held at `tilt_deg` in `style`: the tilt's width, except for a roll,
// whose ball is the pen's own and does not grow when the pen leans (min_width_mm).
double ProbeWidthMm(synth::ProbeStyle style, double tilt_deg, const GestureMapping& mapping);

}  // namespace sas::kiosk
