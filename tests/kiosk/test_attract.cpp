// The attract screen's passive exploration: while idle the engine strokes the picture itself in
// bursts (heard, gently), the microphone's room measurement is allowed only in the quiet gaps,
// a hover does not end it, and a touch does at once without lifting the visitor's own stroke.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "kiosk/kiosk_engine.h"

using sas::kiosk::KioskEngine;
using sas::platform::PenReading;

namespace {

constexpr int kFrames = 128;
constexpr std::int64_t kBlockNs = 2'666'667;

struct Run {
  explicit Run(bool attract_stroke) : engine(Options(attract_stroke)) {
    engine.SetAudioRunning(true);
  }
  static sas::kiosk::KioskEngineOptions Options(bool attract_stroke) {
    sas::kiosk::KioskEngineOptions options;
    options.virtual_clock = true;
    options.cues_dir = "/nonexistent";
    options.attract_stroke = attract_stroke;
    options.config.invitation_interval_s = 0.0;
    return options;
  }
  // Speaker RMS over `seconds` (the transducer's in `haptic_rms`); `listening` counts the blocks
  // the room could be measured in.
  double Advance(double seconds, int* listening = nullptr, double* haptic_rms = nullptr) {
    std::vector<float> out(kFrames * 2);
    double sum = 0.0, haptic_sum = 0.0;
    std::size_t n = 0;
    for (double s = 0.0; s < seconds; s += kFrames / 48000.0) {
      engine.Tick(t);
      if (listening && engine.AmbientListening()) ++*listening;
      engine.audio().Render(out.data(), kFrames, 2);
      for (int i = 0; i < kFrames; ++i) {
        sum += static_cast<double>(out[2 * i]) * out[2 * i];
        haptic_sum += static_cast<double>(out[2 * i + 1]) * out[2 * i + 1];
      }
      n += kFrames;
      t += kBlockNs;
    }
    if (haptic_rms) *haptic_rms = std::sqrt(haptic_sum / static_cast<double>(n));
    return std::sqrt(sum / static_cast<double>(n));
  }
  PenReading Pen(double x, bool down) const {
    PenReading pen;
    pen.time_ns = t;
    pen.x_px = x;
    pen.y_px = 540.0;
    pen.pressure = down ? 0.7 : 0.0;
    pen.tip_down = down;
    return pen;
  }
  KioskEngine engine;
  std::int64_t t = 0;
};

}  // namespace

TEST_CASE("idle, the engine strokes the picture in bursts and lets the room be measured between",
          "[kiosk]") {
  Run run(true);
  int listening = 0;
  const double gap = run.Advance(5.0, &listening);  // the first 6 s are quiet
  CHECK(gap < 1e-6);
  CHECK(listening > 0);
  CHECK_FALSE(run.engine.passive_pen().has_value());
  run.Advance(1.5);
  REQUIRE(run.engine.passive_pen().has_value());  // its dent travels with it
  const double x0 = run.engine.passive_pen()->x_px;
  listening = 0;
  const double burst = run.Advance(5.0, &listening);
  CHECK(20.0 * std::log10(burst) > -70.0);  // heard
  CHECK(listening == 0);                    // the microphone would hear the box itself
  CHECK(run.engine.passive_pen()->x_px != x0);
  CHECK(run.engine.session().mode() == sas::kiosk::SessionMode::kAttract);
  CHECK(run.engine.session().counters().sessions == 0);  // nobody visited
  // After the burst and its ring-out the room is measured again.
  run.Advance(2.0);
  listening = 0;
  run.Advance(3.0, &listening);
  CHECK(listening > 0);
  CHECK_FALSE(run.engine.passive_pen().has_value());

  // Gentle: a visitor's stroke of the same kind on the same texture is louder.
  Run visitor(false);
  visitor.Advance(1.0);
  double visitor_sum = 0.0;
  for (int i = 0; i < 400; ++i) {
    visitor.engine.OnPen(visitor.Pen(480.0 + 0.6 * i, true));
    visitor_sum += std::pow(visitor.Advance(kFrames / 48000.0), 2.0);
  }
  const double visitor_rms = std::sqrt(visitor_sum / 400.0);
  CHECK(20.0 * std::log10(visitor_rms / burst) > 3.0);
}

TEST_CASE("a hover leaves the passive stroke going and a touch takes over at once", "[kiosk]") {
  Run run(true);
  run.Advance(7.0);
  REQUIRE(run.engine.passive_pen().has_value());
  run.engine.OnPen(run.Pen(300.0, false));  // a mouse moved by a passer-by
  run.Advance(0.1);
  CHECK(run.engine.passive_pen().has_value());
  CHECK(run.engine.session().mode() == sas::kiosk::SessionMode::kAttract);
  run.engine.OnPen(run.Pen(300.0, true));  // a visitor touches
  CHECK_FALSE(run.engine.passive_pen().has_value());
  CHECK(run.engine.session().mode() == sas::kiosk::SessionMode::kExploring);
  CHECK(run.engine.session().counters().sessions == 1);
  // The visitor's stroke sounds on: nothing of the passive probe lifts it.
  double sum = 0.0;
  for (int i = 0; i < 200; ++i) {
    run.engine.OnPen(run.Pen(300.0 + 0.6 * i, true));
    sum += std::pow(run.Advance(kFrames / 48000.0), 2.0);
  }
  CHECK(20.0 * std::log10(std::sqrt(sum / 200.0)) > -70.0);
  CHECK_FALSE(run.engine.passive_pen().has_value());
}

TEST_CASE("whatever ends the attract screen lifts the passive probe: no stroke sound 0.5 s later",
          "[kiosk]") {
  // The language key, the record button, a token and the staff chord each end the attract
  // screen without a touch; the passive stroke must not go on scraping under the visit.
  const auto db = [](double rms) { return 20.0 * std::log10(std::max(rms, 1e-12)); };
  for (const char* how : {"language key", "record button", "token", "staff chord"}) {
    CAPTURE(how);
    Run run(true);
    run.Advance(7.5);  // 1.5 s into the first burst
    REQUIRE(run.engine.passive_pen().has_value());
    double burst_haptic = 0.0;
    const double burst = run.Advance(0.5, nullptr, &burst_haptic);
    REQUIRE(db(burst) > -70.0);
    const std::string what = how;
    if (what == "language key") {
      REQUIRE(run.engine.NextLanguage(run.t));
    } else if (what == "record button") {
      run.engine.OnRecordButton(run.t, true);
      run.engine.OnRecordButton(run.t + 100'000'000, false);
    } else if (what == "token") {
      run.engine.OnToken(run.t, 1);
    } else {
      run.engine.OnStaffChord(run.t);
    }
    run.Advance(0.5);
    CHECK_FALSE(run.engine.passive_pen().has_value());
    double haptic = 0.0;
    const double after = run.Advance(0.5, nullptr, &haptic);
    INFO("burst " << db(burst) << " dBFS sound, " << db(burst_haptic) << " dBFS vibration; 0.5 s "
                  << "after: " << db(after) << " / " << db(haptic) << " dBFS");
    CHECK(db(after) < -90.0);
    CHECK(db(haptic) < -90.0);
  }
}
