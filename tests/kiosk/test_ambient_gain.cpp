// Ambient-adaptive sound gain (kiosk/ambient_gain.h): stays within its bounds, follows the room
// proportionally, changes smoothly (bounded slew, averaged room estimate), and adapts only while
// the kiosk is idle; off, it is 0 dB whatever the microphone hears.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "kiosk/ambient_gain.h"

using sas::kiosk::AmbientGain;
using sas::kiosk::AmbientGainConfig;

namespace {

AmbientGainConfig Enabled() {
  AmbientGainConfig c;
  c.enabled = true;
  c.min_db = -2.0;
  c.max_db = 10.0;
  c.per_db = 0.5;
  c.quiet_dbfs = -60.0;
  c.rate_db_per_s = 1.0;
  c.averaging_s = 5.0;
  return c;
}

// Feeds `seconds` of a constant room level at 10 measurements per second.
void Feed(AmbientGain& gain, double level_dbfs, double seconds, bool idle) {
  for (int i = 0; i < static_cast<int>(seconds * 10.0); ++i) gain.Update(level_dbfs, 0.1, idle);
}

}  // namespace

TEST_CASE("ambient gain settles within its bounds for any room level", "[kiosk]") {
  for (const double room : {-120.0, -80.0, -60.0, -50.0, -40.0, -20.0, 0.0, 30.0}) {
    AmbientGain gain(Enabled());
    Feed(gain, room, 120.0, true);
    INFO("room " << room << " dBFS");
    CHECK(gain.gain_db() >= -2.0);
    CHECK(gain.gain_db() <= 10.0);
    // 0.5 dB per dB above -60 dBFS from -2 dB, clamped: the closed form, not the code's output.
    const double expected = std::clamp(-2.0 + 0.5 * (std::min(room, 0.0) + 60.0), -2.0, 10.0);
    CHECK(gain.gain_db() == Approx(expected).margin(0.01));
  }
}

TEST_CASE("ambient gain never jumps: it slews at the configured rate and averages the room",
          "[kiosk]") {
  AmbientGain gain(Enabled());
  Feed(gain, -60.0, 30.0, true);  // quiet room: at the lower bound
  REQUIRE(gain.gain_db() == Approx(-2.0));
  double previous = gain.gain_db();
  double largest_step = 0.0;
  for (int i = 0; i < 300; ++i) {  // the gallery fills up: +40 dB at once
    gain.Update(-20.0, 0.1, true);
    largest_step = std::max(largest_step, std::fabs(gain.gain_db() - previous));
    previous = gain.gain_db();
  }
  CHECK(largest_step <= 0.1 + 1e-12);  // 1 dB/s at 10 updates per second
  CHECK(gain.gain_db() == Approx(10.0).margin(0.01));
  // A long gap between measurements does not let the gain leap.
  const double before = gain.gain_db();
  gain.Update(-120.0, 3600.0, true);
  CHECK(std::fabs(gain.gain_db() - before) <= 0.5 + 1e-12);
  // A one-off slam (0 dBFS for 0.1 s) in a quiet room barely moves the room estimate.
  AmbientGain quiet(Enabled());
  Feed(quiet, -60.0, 30.0, true);
  quiet.Update(0.0, 0.1, true);
  CHECK(quiet.room_dbfs() < -58.5);
}

TEST_CASE("ambient gain adapts only while idle", "[kiosk]") {
  AmbientGain gain(Enabled());
  Feed(gain, -50.0, 60.0, true);
  const double idle_gain = gain.gain_db();
  const double idle_room = gain.room_dbfs();
  REQUIRE(idle_gain == Approx(3.0).margin(0.01));
  // A visitor scratches loudly next to the microphone: nothing moves.
  Feed(gain, -5.0, 60.0, false);
  CHECK(gain.gain_db() == idle_gain);
  CHECK(gain.room_dbfs() == idle_room);
  // Idle again in a louder room: it follows.
  Feed(gain, -40.0, 60.0, true);
  CHECK(gain.gain_db() == Approx(8.0).margin(0.01));
}

TEST_CASE("ambient gain off is 0 dB and bad measurements are ignored", "[kiosk]") {
  AmbientGain off(AmbientGainConfig{});
  Feed(off, -10.0, 60.0, true);
  CHECK(off.gain_db() == 0.0);
  AmbientGain gain(Enabled());
  Feed(gain, -50.0, 60.0, true);
  const double settled = gain.gain_db();
  gain.Update(std::numeric_limits<double>::quiet_NaN(), 0.1, true);
  gain.Update(-std::numeric_limits<double>::infinity(), 0.1, true);
  gain.Update(-10.0, -1.0, true);
  gain.Update(-10.0, std::numeric_limits<double>::quiet_NaN(), true);
  CHECK(gain.gain_db() == settled);
  gain.Reset();
  CHECK(gain.gain_db() == -2.0);
  CHECK_FALSE(gain.has_room_estimate());
}

TEST_CASE("ambient gain configuration comes from the kiosk's gains keys", "[kiosk]") {
  const auto config = sas::kiosk::ParseKioskConfig(
      "[gains]\nambient_adaptive = true\nambient_min_db = 1\nambient_max_db = 7\n"
      "ambient_per_db = 0.25\nambient_quiet_dbfs = -70\nambient_rate_db_per_s = 2\n",
      "k.toml");
  const AmbientGainConfig a = sas::kiosk::AmbientGainConfigFrom(config);
  CHECK(a.enabled);
  CHECK(a.min_db == 1.0);
  CHECK(a.max_db == 7.0);
  CHECK(a.per_db == 0.25);
  CHECK(a.quiet_dbfs == -70.0);
  CHECK(a.rate_db_per_s == 2.0);
}
