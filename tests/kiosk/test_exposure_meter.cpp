// The speaker's exposure figure for staff (kiosk/exposure_meter.h): Leq over the last visit and
// the last hour, from the audio side's running totals.
#include <catch2/catch.hpp>

#include <cmath>

#include "kiosk/exposure_meter.h"

using sas::kiosk::ExposureMeter;

namespace {
constexpr std::int64_t kS = 1'000'000'000;
constexpr double kFs = 48000.0;
}  // namespace

TEST_CASE("exposure meter: a visit's Leq is its own mean square, the hour's includes the quiet "
          "time and forgets what is older than an hour",
          "[kiosk][safety]") {
  ExposureMeter meter;
  CHECK_FALSE(meter.LastHourDb());
  CHECK_FALSE(meter.LastVisitDb());
  double energy = 0.0;
  std::uint64_t frames = 0;
  std::int64_t t = 0;
  // Feeds `seconds` of audio at `db` dBFS RMS, one update a tenth of a second.
  const auto feed = [&](double seconds, double db, bool in_visit) {
    const double ms = std::pow(10.0, db / 10.0);
    for (int i = 0; i < static_cast<int>(seconds * 10); ++i) {
      energy += ms * kFs / 10.0;
      frames += static_cast<std::uint64_t>(kFs / 10.0);
      t += kS / 10;
      meter.Update(t, energy, frames, in_visit);
    }
  };
  feed(600.0, -60.0, false);  // 10 min of near silence on the attract screen
  feed(300.0, -20.0, true);   // a 5 min visit at -20 dBFS
  REQUIRE(meter.LastVisitDb());
  CHECK(*meter.LastVisitDb() == Approx(-20.0).margin(0.05));
  feed(300.0, -60.0, false);
  CHECK(*meter.LastVisitDb() == Approx(-20.0).margin(0.05));  // the last finished visit
  // 20 min so far: (10 min · 1e-6 + 5 min · 1e-2 + 5 min · 1e-6) / 20 min.
  const double hour_db = 10.0 * std::log10((10.0 * 1e-6 + 5.0 * 1e-2 + 5.0 * 1e-6) / 20.0);
  CHECK(*meter.LastHourDb() == Approx(hour_db).margin(0.05));
  // An hour and a half later the visit has left the hour.
  feed(5400.0, -60.0, false);
  CHECK(*meter.LastHourDb() == Approx(-60.0).margin(0.05));
  CHECK(*meter.LastVisitDb() == Approx(-20.0).margin(0.05));
  // A new visit replaces it while it goes on.
  feed(60.0, -30.0, true);
  CHECK(*meter.LastVisitDb() == Approx(-30.0).margin(0.05));
}
