// The pen mapping: pressure and tilt to the probe (see pen_mapping.h).
#include "kiosk/pen_mapping.h"

#include <algorithm>

namespace sas::kiosk {
namespace {

double Clamp01(double value) {
  return std::clamp(value, 0.0, 1.0);
}

}  // namespace

void ApplyPenPressure(double pressure, double relief_m, const GestureMapping& mapping,
                      synth::ProbeCommand& command) {
  const double p = Clamp01(pressure);
  command.normal_force_n = p * mapping.max_force_n;
  command.penetration_m = p * relief_m;
}

void ApplyPenTilt(std::optional<double> tilt_deg, const ProbeShape& untilted,
                  std::optional<synth::ProbeStyle> forced, const GestureMapping& mapping,
                  synth::ProbeCommand& command) {
  if (!tilt_deg) {
    command.width_mm = untilted.width_mm;
    command.style = forced.value_or(untilted.style);
    return;
  }
  command.style = forced.value_or(StyleFromWidth(WidthFromTiltMm(*tilt_deg, mapping), mapping));
  command.width_mm = ProbeWidthMm(command.style, *tilt_deg, mapping);
}

void ApplyPenReading(const platform::PenReading& pen, double relief_m, const ProbeShape& untilted,
                     std::optional<synth::ProbeStyle> forced, const GestureMapping& mapping,
                     synth::ProbeCommand& command) {
  ApplyPenPressure(pen.pressure, relief_m, mapping, command);
  if (!forced && pen.barrel_button) forced = synth::ProbeStyle::kRoll;
  ApplyPenTilt(pen.HasTilt() ? std::optional<double>(pen.TiltDeg()) : std::nullopt, untilted,
               forced, mapping, command);
}

double WidthFromTiltMm(double tilt_deg, const GestureMapping& mapping) {
  const double fraction = Clamp01(tilt_deg / mapping.max_tilt_deg);
  return mapping.min_width_mm + fraction * (mapping.max_width_mm - mapping.min_width_mm);
}

double TiltFromWidthDeg(double width_mm, const GestureMapping& mapping) {
  const double fraction =
      Clamp01((width_mm - mapping.min_width_mm) / (mapping.max_width_mm - mapping.min_width_mm));
  return fraction * mapping.max_tilt_deg;
}

synth::ProbeStyle StyleFromWidth(double width_mm, const GestureMapping& mapping) {
  return width_mm >= mapping.rub_width_mm ? synth::ProbeStyle::kRub : synth::ProbeStyle::kScrape;
}

double ProbeWidthMm(synth::ProbeStyle style, double tilt_deg, const GestureMapping& mapping) {
  return style == synth::ProbeStyle::kRoll ? mapping.min_width_mm
                                           : WidthFromTiltMm(tilt_deg, mapping);
}

}  // namespace sas::kiosk
