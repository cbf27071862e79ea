// Gestures: CSV parsing and its errors; the pen -> probe command mapping; the built-in gestures
// give plausible command streams (the passive sweep at one constant velocity, Δx = v Δt).
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "kiosk/gesture.h"
#include "support/temp_dir.h"
#include "tools/builtin_profiles.h"

using sas::kiosk::BuiltinGestureNames;
using sas::kiosk::FindBuiltinGesture;
using sas::kiosk::Gesture;
using sas::kiosk::GestureError;
using sas::kiosk::GestureMapping;
using sas::kiosk::GestureToCommands;
using sas::kiosk::LoadGestureCsv;
using sas::kiosk::ParseGestureCsv;
using sas::kiosk::PassiveSweep;
using sas::kiosk::TimedCommand;
using sas::synth::ProbeStyle;

namespace {

constexpr double kFs = 48000.0;

Gesture Csv(const std::string& rows) {
  return ParseGestureCsv("t,x,y,pressure,tilt\n" + rows, "g.csv");
}

// Parse errors for a body of rows; the header is line 1, the first row line 2.
std::string ErrorOf(const std::string& text) {
  try {
    ParseGestureCsv(text, "g.csv");
  } catch (const GestureError& error) {
    return error.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("gesture CSV rows are read as seconds, millimetres, pressure and degrees", "[kiosk]") {
  const Gesture gesture = ParseGestureCsv(
      "# a comment\n"
      "t,x,y,pressure,tilt\n"
      "\n"
      "0.0, 10.5, 20.25, 0.0, 5\r\n"
      "0.5,12,21,0.75,45\n",
      "g.csv");
  REQUIRE(gesture.samples.size() == 2);
  CHECK(gesture.samples[0].x_mm == 10.5);
  CHECK(gesture.samples[0].y_mm == 20.25);
  CHECK(gesture.samples[0].tilt_deg == 5.0);
  CHECK(gesture.samples[1].t_s == 0.5);
  CHECK(gesture.samples[1].pressure == 0.75);
  CHECK(gesture.samples[1].tilt_deg == 45.0);
  CHECK(gesture.duration_s() == 0.5);
}

TEST_CASE("gesture CSV errors name file, line and column", "[kiosk]") {
  CHECK_THAT(ErrorOf("time,x,y,pressure,tilt\n0,1,1,0,0\n"), Catch::Contains("g.csv:1: header:"));
  CHECK_THAT(ErrorOf("t,x,y,pressure,tilt\n0,1,1,0,0\n0.1,1,1,0\n"),
             Catch::Contains("g.csv:3: row: expected 5 values, got 4"));
  CHECK_THAT(ErrorOf("t,x,y,pressure,tilt\n0,1,1,0,0\n0.1,1,abc,0,0\n"),
             Catch::Contains("g.csv:3: y: \"abc\" is not a number"));
  CHECK_THAT(ErrorOf("t,x,y,pressure,tilt\n0,1,1,0,0\n0.1,1,1,nan,0\n"),
             Catch::Contains("g.csv:3: pressure:") && Catch::Contains("finite"));
  CHECK_THAT(ErrorOf("t,x,y,pressure,tilt\n0,1,1,0,0\n0.1,1,1,1.5,0\n"),
             Catch::Contains("g.csv:3: pressure: 1.5 is out of range"));
  CHECK_THAT(ErrorOf("t,x,y,pressure,tilt\n0,1,1,0,0\n0.1,1,1,0.5,95\n"),
             Catch::Contains("g.csv:3: tilt: 95 is out of range"));
  CHECK_THAT(ErrorOf("t,x,y,pressure,tilt\n0,1,1,0,0\n0.2,1,1,0,0\n\n0.2,2,1,0,0\n"),
             Catch::Contains("g.csv:5: t: time must increase"));
  CHECK_THAT(ErrorOf("t,x,y,pressure,tilt\n0,-3,1,0,0\n"), Catch::Contains("g.csv:2: x:"));
  CHECK_THAT(ErrorOf("t,x,y,pressure,tilt\n0,1,1,0,0\n"), Catch::Contains("at least two rows"));
  CHECK_THAT(ErrorOf(""), Catch::Contains("g.csv:1: header: missing"));
  CHECK_THROWS_WITH(LoadGestureCsv("/nonexistent/g.csv"),
                    Catch::Contains("/nonexistent/g.csv") && Catch::Contains("cannot open"));
}

TEST_CASE("a gesture file round-trips through the loader", "[kiosk]") {
  sas::test::TempDir dir;
  const auto path = dir.Write("stroke.csv", "t,x,y,pressure,tilt\n0,1,2,0.5,0\n1,3,2,0.5,0\n");
  const Gesture gesture = LoadGestureCsv(path);
  REQUIRE(gesture.samples.size() == 2);
  CHECK(gesture.samples[1].x_mm == 3.0);
}

TEST_CASE("velocity is the distance between rows over their time, along the segment's direction",
          "[kiosk]") {
  // A 3-4-5 segment: 5 mm in 0.1 s = 0.05 m/s, direction (0.6, 0.8).
  const Gesture gesture = Csv("0,10,10,0.5,0\n0.1,13,14,0.5,0\n");
  const auto commands = GestureToCommands(gesture, GestureMapping{}, kFs);
  REQUIRE(commands.size() > 10);
  for (std::size_t i = 0; i + 1 < commands.size(); ++i) {
    const auto& c = commands[i].command;
    CHECK(c.velocity_mps == Approx(0.05).epsilon(1e-12));
    CHECK(c.direction_x == Approx(0.6).epsilon(1e-12));
    CHECK(c.direction_y == Approx(0.8).epsilon(1e-12));
    // Position is the linear interpolation of the rows at the command's time, in metres.
    const double t = static_cast<double>(commands[i].frame) / kFs;
    CHECK(c.x_m == Approx((10.0 + 30.0 * t) * 1e-3).epsilon(1e-9));
    CHECK(c.y_m == Approx((10.0 + 40.0 * t) * 1e-3).epsilon(1e-9));
  }
}

TEST_CASE("pressure maps linearly to 0..2 N and penetration, tilt to width from scratch to rub",
          "[kiosk]") {
  GestureMapping mapping;
  mapping.max_penetration_m = 1e-4;
  const auto light = GestureToCommands(Csv("0,10,10,0.25,0\n0.05,10,10,0.25,0\n"), mapping, kFs);
  CHECK(light.front().command.tip_down);
  CHECK(light.front().command.normal_force_n == Approx(0.5));
  CHECK(light.front().command.penetration_m == Approx(0.25e-4));
  CHECK(light.front().command.width_mm == Approx(mapping.min_width_mm));
  CHECK(light.front().command.style == ProbeStyle::kScrape);

  const auto full = GestureToCommands(Csv("0,10,10,1,60\n0.05,10,10,1,75\n"), mapping, kFs);
  CHECK(full.front().command.normal_force_n == Approx(2.0));
  CHECK(full.front().command.penetration_m == Approx(1e-4));
  CHECK(full.front().command.width_mm == Approx(mapping.max_width_mm));
  CHECK(full.front().command.style == ProbeStyle::kRub);

  // Half the maximum tilt gives the middle width; zero pressure lifts the pen.
  const auto half = GestureToCommands(Csv("0,10,10,0,30\n0.05,10,10,0,30\n"), mapping, kFs);
  CHECK(half.front().command.width_mm ==
        Approx(0.5 * (mapping.min_width_mm + mapping.max_width_mm)));
  CHECK_FALSE(half.front().command.tip_down);
  // The tilt for a width inverts the mapping within its range and holds at its ends.
  CHECK(sas::kiosk::TiltFromWidthDeg(0.5 * (mapping.min_width_mm + mapping.max_width_mm),
                                     mapping) == Approx(30.0));
  CHECK(sas::kiosk::WidthFromTiltMm(sas::kiosk::TiltFromWidthDeg(2.1, mapping), mapping) ==
        Approx(2.1));
  CHECK(sas::kiosk::TiltFromWidthDeg(0.0, mapping) == 0.0);
  CHECK(sas::kiosk::TiltFromWidthDeg(50.0, mapping) == Approx(mapping.max_tilt_deg));
  CHECK(half.front().command.normal_force_n == 0.0);

  mapping.style = ProbeStyle::kRoll;  // a forced style wins over the width
  const auto rolled = GestureToCommands(Csv("0,10,10,1,60\n0.05,10,10,1,60\n"), mapping, kFs);
  CHECK(rolled.front().command.style == ProbeStyle::kRoll);
}

TEST_CASE("the passive sweep keeps one constant velocity and advances x by v times dt", "[kiosk]") {
  const double v = 0.05;
  const Gesture sweep = PassiveSweep(v, 70.0, 0.4);
  CHECK(sweep.duration_s() == Approx(1.4));
  const auto commands = GestureToCommands(sweep, GestureMapping{}, kFs);
  REQUIRE(commands.size() > 1000);
  for (std::size_t i = 0; i + 1 < commands.size(); ++i) {
    const auto& c = commands[i].command;
    REQUIRE(c.tip_down);
    CHECK(c.velocity_mps == Approx(v).epsilon(1e-12));
    CHECK(c.direction_x == 1.0);
    CHECK(c.normal_force_n == Approx(0.8));
    if (i + 2 < commands.size()) {  // the last pair is the pen-up
      const double dt = static_cast<double>(commands[i + 1].frame - commands[i].frame) / kFs;
      CHECK(commands[i + 1].command.x_m - c.x_m == Approx(v * dt).epsilon(1e-9));
    }
  }
  CHECK_FALSE(commands.back().command.tip_down);
  // The built-in of that name is the same kind of gesture.
  const auto builtin = FindBuiltinGesture("passive sweep");
  REQUIRE(builtin);
  const auto builtin_commands = GestureToCommands(*builtin, GestureMapping{}, kFs);
  for (std::size_t i = 0; i + 1 < builtin_commands.size(); ++i) {
    CHECK(builtin_commands[i].command.velocity_mps ==
          Approx(builtin_commands[0].command.velocity_mps).epsilon(1e-12));
  }
}

TEST_CASE(
    "every built-in gesture gives increasing frames, stays on the built-in profiles and "
    "ends with the pen lifted",
    "[kiosk]") {
  const double width_m = sas::kiosk::kBuiltinProfileWidth * sas::kiosk::kProfilePitchM;
  const double height_m = sas::kiosk::kBuiltinProfileHeight * sas::kiosk::kProfilePitchM;
  for (const auto& name : BuiltinGestureNames()) {
    INFO(name);
    const auto gesture = FindBuiltinGesture(name);
    REQUIRE(gesture);
    const auto commands = GestureToCommands(*gesture, GestureMapping{}, kFs);
    REQUIRE(commands.size() >= 2);
    int down = 0;
    for (std::size_t i = 0; i < commands.size(); ++i) {
      if (i > 0) CHECK(commands[i].frame > commands[i - 1].frame);
      const auto& c = commands[i].command;
      CHECK(c.x_m >= 0.0);
      CHECK(c.x_m <= width_m);
      CHECK(c.y_m >= 0.0);
      CHECK(c.y_m <= height_m);
      CHECK(std::isfinite(c.velocity_mps));
      CHECK(std::hypot(c.direction_x, c.direction_y) == Approx(1.0));
      down += c.tip_down ? 1 : 0;
    }
    CHECK(down > 0);
    CHECK_FALSE(commands.back().command.tip_down);
    // The last command is at the gesture's end (1 ms control ticks).
    CHECK(static_cast<double>(commands.back().frame) / kFs ==
          Approx(gesture->duration_s()).margin(2e-3));
  }
}

TEST_CASE("built-in gestures differ the way their names say", "[kiosk]") {
  const auto mean_down_speed = [](const std::vector<TimedCommand>& commands) {
    double sum = 0.0;
    int count = 0;
    for (const auto& c : commands) {
      if (c.command.tip_down) {
        sum += c.command.velocity_mps;
        ++count;
      }
    }
    return count > 0 ? sum / count : 0.0;
  };
  const auto commands = [](const char* name) {
    return GestureToCommands(*FindBuiltinGesture(name), GestureMapping{}, kFs);
  };
  const auto slow = commands("slow stroke");
  const auto fast = commands("fast scribble");
  const auto tap = commands("tap");
  CHECK(mean_down_speed(slow) == Approx(0.03).epsilon(1e-9));  // 30 mm/s throughout
  CHECK(mean_down_speed(fast) > 5.0 * mean_down_speed(slow));
  CHECK(mean_down_speed(tap) == 0.0);  // taps do not slide

  // The scribble goes back and forth: its x direction changes sign several times.
  int reversals = 0;
  for (std::size_t i = 1; i < fast.size(); ++i) {
    if (fast[i].command.direction_x * fast[i - 1].command.direction_x < 0.0) ++reversals;
  }
  CHECK(reversals >= 5);

  // Four separate touches, each landing faster than a stroke's default.
  int touches = 0;
  for (std::size_t i = 1; i < tap.size(); ++i) {
    if (tap[i].command.tip_down && !tap[i - 1].command.tip_down) ++touches;
  }
  CHECK(touches + (tap.front().command.tip_down ? 1 : 0) == 4);
  CHECK(tap.front().command.landing_speed_mps > 0.1);
}

TEST_CASE("built-in gesture names accept spaces, dashes and underscores but not others",
          "[kiosk]") {
  CHECK(FindBuiltinGesture("slow-stroke"));
  CHECK(FindBuiltinGesture("Fast_Scribble"));
  CHECK(FindBuiltinGesture("passive sweep"));
  CHECK_FALSE(FindBuiltinGesture("slow"));
}
