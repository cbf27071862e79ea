// The pen mapping (kiosk/pen_mapping.h): pressure to force and penetration, tilt to width and
// style, for a reading from any source.
#include <catch2/catch.hpp>

#include "kiosk/gesture.h"
#include "kiosk/pen_mapping.h"
#include "platform/pen/pen_reading.h"

using sas::kiosk::ApplyPenReading;
using sas::kiosk::GestureMapping;
using sas::kiosk::ProbeShape;
using sas::platform::PenOrigin;
using sas::platform::PenReading;
using sas::synth::ProbeCommand;
using sas::synth::ProbeStyle;

namespace {

constexpr double kReliefM = 0.4e-3;
const ProbeShape kTextureProbe{1.2, ProbeStyle::kRoll};

PenReading Tablet(double pressure, double tilt_x_deg, double tilt_y_deg = 0.0) {
  PenReading pen;
  pen.origin = PenOrigin::kTablet;
  pen.tip_down = pen.in_proximity = true;
  pen.pressure = pressure;
  pen.tilt_x_deg = tilt_x_deg;
  pen.tilt_y_deg = tilt_y_deg;
  return pen;
}

ProbeCommand Map(const PenReading& pen, std::optional<ProbeStyle> forced = {}) {
  ProbeCommand command;
  ApplyPenReading(pen, kReliefM, kTextureProbe, forced, GestureMapping{}, command);
  return command;
}

}  // namespace

TEST_CASE("pen mapping: pressure sets normal force and penetration in proportion, clamped to 0..1",
          "[kiosk]") {
  const GestureMapping mapping;
  for (const double pressure : {0.0, 0.25, 0.8, 1.0}) {
    const ProbeCommand c = Map(Tablet(pressure, 0.0));
    CHECK(c.normal_force_n == Approx(pressure * mapping.max_force_n));
    CHECK(c.penetration_m == Approx(pressure * kReliefM));
  }
  CHECK(Map(Tablet(1.7, 0.0)).normal_force_n == Approx(mapping.max_force_n));
  CHECK(Map(Tablet(-0.3, 0.0)).penetration_m == 0.0);
}

TEST_CASE(
    "pen mapping: an upright pen scrapes narrow, a tilted one rubs wide, up to the widest at "
    "max tilt",
    "[kiosk]") {
  const GestureMapping mapping;
  const ProbeCommand upright = Map(Tablet(0.5, 0.0));
  CHECK(upright.style == ProbeStyle::kScrape);
  CHECK(upright.width_mm == mapping.min_width_mm);
  const ProbeCommand tilted = Map(Tablet(0.5, 45.0));
  CHECK(tilted.style == ProbeStyle::kRub);
  CHECK(tilted.width_mm == Approx(sas::kiosk::WidthFromTiltMm(45.0, mapping)));
  CHECK(Map(Tablet(0.5, 80.0)).width_mm == mapping.max_width_mm);
}

TEST_CASE("pen mapping: tilt along either axis or both counts as the angle from upright",
          "[kiosk]") {
  CHECK(Tablet(0.5, 30.0).TiltDeg() == 30.0);
  CHECK(Tablet(0.5, 0.0, -30.0).TiltDeg() == 30.0);
  // tan(tilt)² = tan(x)² + tan(y)²: 45° on both axes leans atan(√2) from upright.
  CHECK(Tablet(0.5, 45.0, 45.0).TiltDeg() == Approx(54.7356).epsilon(1e-5));
  CHECK(Map(Tablet(0.5, 0.0, 45.0)).width_mm == Approx(Map(Tablet(0.5, 45.0)).width_mm));
}

TEST_CASE("pen mapping: mouse and touch have no tilt and get the texture's own probe", "[kiosk]") {
  PenReading mouse = Tablet(0.6, 50.0);
  mouse.origin = PenOrigin::kMouse;
  const ProbeCommand c = Map(mouse);
  CHECK(c.width_mm == kTextureProbe.width_mm);
  CHECK(c.style == kTextureProbe.style);
  CHECK(c.normal_force_n == Approx(0.6 * GestureMapping{}.max_force_n));
  mouse.origin = PenOrigin::kTouch;
  CHECK(Map(mouse).width_mm == kTextureProbe.width_mm);
}

TEST_CASE(
    "pen mapping: a forced roll keeps the ball's own width however the pen leans, a forced "
    "rub keeps the tilt's",
    "[kiosk]") {
  const GestureMapping mapping;
  const ProbeCommand roll = Map(Tablet(0.5, 50.0), ProbeStyle::kRoll);
  CHECK(roll.style == ProbeStyle::kRoll);
  CHECK(roll.width_mm == mapping.min_width_mm);
  const ProbeCommand rub = Map(Tablet(0.5, 10.0), ProbeStyle::kRub);
  CHECK(rub.style == ProbeStyle::kRub);
  CHECK(rub.width_mm == Approx(sas::kiosk::WidthFromTiltMm(10.0, mapping)));
}

TEST_CASE(
    "pen mapping: a gesture's commands carry the same force, width and style as one reading "
    "held the same way",
    "[kiosk]") {
  const GestureMapping mapping;
  sas::kiosk::Gesture gesture;
  gesture.samples = {{0.0, 10.0, 10.0, 0.6, 40.0}, {0.1, 20.0, 10.0, 0.6, 40.0}};
  const auto commands = sas::kiosk::GestureToCommands(gesture, mapping, 48000.0);
  REQUIRE(commands.size() > 2);
  ProbeCommand reading;
  ApplyPenReading(Tablet(0.6, 40.0), mapping.max_penetration_m, ProbeShape{}, {}, mapping, reading);
  const ProbeCommand& middle = commands[commands.size() / 2].command;
  CHECK(middle.normal_force_n == reading.normal_force_n);
  CHECK(middle.penetration_m == reading.penetration_m);
  CHECK(middle.width_mm == reading.width_mm);
  CHECK(middle.style == reading.style);
}
