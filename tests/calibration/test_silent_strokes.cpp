// No stroke over a texture is silent: what the kiosk plays (its engine on the virtual clock, the
// shipped configuration's gains, as `render --texture` plays it: tests/tools/test_render_kiosk.cpp
// shows the two give the same samples) for every kiosk texture and style at the slowest and the
// fastest hand (10 and 600 mm/s) and a light and a firm press (0.1 and 0.9), on a diagonal through
// places no calibration uses. While the pen moves, every 100 ms of the sound must be above
// -90 dBFS (a plain RMS meter, not the calibration's K-weighting). And a pen lifted in one step
// (a pen-up report straight after a pressed one) rings no louder than the stroke it ends.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include "files/kiosk_config.h"
#include "kiosk/gesture.h"
#include "kiosk/kiosk_engine.h"
#include "kiosk/virtual_visit.h"
#include "sas/version.h"

namespace {

using sas::synth::ProbeStyle;

constexpr double kSilentDbfs = -90.0;

// The strokes that are silent today: none. A slow roll over a smooth stretch rang nothing
// (-92 to -101 dBFS) until the rolling contact's creep noise (synth/scene.cpp, kRollingCreep). A
// stroke that becomes silent fails; one listed here must become audible to leave.
const std::set<std::string>& KnownSilent() {
  static const std::set<std::string> keys = {};
  return keys;
}

constexpr const char* kKioskTextures[] = {"bubble_wrap", "broken_glass", "wooden_board",
                                          "cracked_ground"};

// The kiosk as shipped (install/kiosk.toml) showing `texture`, on the virtual clock, no cues.
sas::kiosk::KioskEngineOptions ShippedKiosk(const char* texture) {
  sas::kiosk::KioskEngineOptions options;
  options.config =
      sas::kiosk::LoadKioskConfig(std::string(sas::kSourceDir) + "/install/kiosk.toml");
  options.config.default_texture = texture;
  options.virtual_clock = true;
  options.spoken_cues = false;
  return options;
}

double QuietestWindowDbfs(const std::vector<float>& out, std::size_t from, std::size_t to,
                          std::size_t window) {
  double quietest = 1e300;
  for (std::size_t start = from; start + window <= to; start += window) {
    double sum = 0.0;
    for (std::size_t i = start; i < start + window; ++i) {
      const double s = out[2 * i];
      sum += s * s;
    }
    quietest = std::min(quietest, sum / static_cast<double>(window));
  }
  return quietest > 0.0 ? 10.0 * std::log10(quietest) : -999.0;
}

}  // namespace

TEST_CASE("no stroke over a kiosk texture is silent while the pen moves, in any style",
          "[calibration]") {
  std::set<std::string> silent;
  double quietest_stroke = 1e300;  // the margin over the line, for the record
  std::string quietest_key;
  for (const char* texture : kKioskTextures) {
    sas::kiosk::KioskEngine engine(ShippedKiosk(texture));
    REQUIRE(engine.texture_failures().empty());
    sas::kiosk::VirtualVisit visit(engine);
    const double fs = visit.sample_rate_hz();
    // The engine plays a pen report one buffer after it came (player/player.h).
    const double delay_s = visit.block_frames() / fs;
    for (const double speed_mm_s : {10.0, 600.0}) {
      for (const double pressure : {0.1, 0.9}) {
        for (const ProbeStyle style : {ProbeStyle::kScrape, ProbeStyle::kRub, ProbeStyle::kRoll}) {
          const double duration_s = speed_mm_s > 100.0 ? 0.6 : 1.2;
          const double length_mm = speed_mm_s * duration_s;
          sas::kiosk::Gesture gesture;
          gesture.name = "diagonal";
          // 3 : 1 across the picture, 20 mm from its top-left corner.
          const double dx = length_mm * 3.0 / std::sqrt(10.0);
          const double dy = length_mm / std::sqrt(10.0);
          gesture.samples = {{0.0, 20.0, 25.0, pressure, 0.0},
                             {duration_s, 20.0 + dx, 25.0 + dy, pressure, 0.0}};
          const double t0 = visit.now_s();
          visit.Advance(duration_s + 0.6, sas::kiosk::GesturePenScript(gesture, engine, t0, style));
          // The landing's first 50 ms and the last 20 ms before the lift are left out: what is
          // judged is the pen moving over the texture.
          const auto from = static_cast<std::size_t>(std::llround((t0 + delay_s + 0.05) * fs));
          const auto to =
              static_cast<std::size_t>(std::llround((t0 + delay_s + duration_s - 0.02) * fs));
          const double quietest =
              QuietestWindowDbfs(visit.output(), from, to, static_cast<std::size_t>(0.1 * fs));
          char figures[48];
          std::snprintf(figures, sizeof figures, "/%.0fmm/s/p%.1f", speed_mm_s, pressure);
          const std::string key =
              std::string(texture) + "/" + std::string(sas::synth::ProbeStyleName(style)) + figures;
          INFO(key << ": quietest 100 ms " << quietest << " dBFS");
          if (quietest < quietest_stroke) {
            quietest_stroke = quietest;
            quietest_key = key;
          }
          if (quietest <= kSilentDbfs) {
            silent.insert(key);
            CHECK(KnownSilent().count(key) == 1);
          }
        }
      }
    }
  }
  WARN("quietest stroke: " << quietest_key << ", " << quietest_stroke << " dBFS in 100 ms");
  for (const std::string& key : KnownSilent()) {
    INFO("listed as silent but heard: " << key);
    CHECK(silent.count(key) == 1);
  }
}

namespace {

// The lifts that still end louder than their stroke: none. A loud lift fails; one listed here
// must become quiet to leave.
const std::set<std::string>& KnownLoudLifts() {
  static const std::set<std::string> keys = {};
  return keys;
}

}  // namespace

TEST_CASE(
    "a pen lifted in one step over a kiosk texture makes no sound louder than the stroke it "
    "ends, landing included",
    "[calibration]") {
  std::set<std::string> loud;
  for (const char* texture : kKioskTextures) {
    sas::kiosk::KioskEngine engine(ShippedKiosk(texture));
    REQUIRE(engine.texture_failures().empty());
    sas::kiosk::VirtualVisit visit(engine);
    const double fs = visit.sample_rate_hz();
    const double delay_s = visit.block_frames() / fs;
    for (const double speed_mm_s : {30.0, 300.0}) {
      for (const double pressure : {0.1, 0.3, 0.5, 0.7, 0.9}) {
        for (const ProbeStyle style : {ProbeStyle::kScrape, ProbeStyle::kRub, ProbeStyle::kRoll}) {
          constexpr double kDurationS = 0.5;
          const double length_mm = speed_mm_s * kDurationS;
          sas::kiosk::Gesture gesture;
          gesture.name = "lifted";
          // 1 : 2 down the picture from a place the silent strokes do not use.
          const double dx = length_mm / std::sqrt(5.0), dy = 2.0 * length_mm / std::sqrt(5.0);
          gesture.samples = {{0.0, 90.0, 30.0, pressure, 0.0},
                             {kDurationS, 90.0 + dx, 30.0 + dy, pressure, 0.0}};
          const double t0 = visit.now_s();
          visit.Advance(kDurationS + 0.8, sas::kiosk::GesturePenScript(gesture, engine, t0, style));
          const auto at = [&](double t) {
            return static_cast<std::size_t>(std::llround((t0 + delay_s + t) * fs));
          };
          const auto peak = [&](std::size_t from, std::size_t to) {
            double p = 0.0;
            for (std::size_t i = from; i < to && 2 * i < visit.output().size(); ++i)
              p = std::max(p, std::abs(static_cast<double>(visit.output()[2 * i])));
            return p;
          };
          // The stroke from the landing to the last report before the lift; the lift from the
          // pen-up report on (reports come every few ms, so allow one report's slack).
          const double stroke = peak(at(0.0), at(kDurationS - 0.01));
          const double lift = peak(at(kDurationS - 0.01), at(kDurationS + 0.7));
          char figures[48];
          std::snprintf(figures, sizeof figures, "/%.0fmm/s/p%.1f", speed_mm_s, pressure);
          const std::string key =
              std::string(texture) + "/" + std::string(sas::synth::ProbeStyleName(style)) + figures;
          INFO(key << ": stroke peak " << 20.0 * std::log10(std::max(stroke, 1e-12))
                   << " dBFS, lift " << 20.0 * std::log10(std::max(lift, 1e-12)) << " dBFS");
          CHECK(stroke > 1e-5);
          if (lift > stroke) {
            loud.insert(key);
            CHECK(KnownLoudLifts().count(key) == 1);
          }
        }
      }
    }
  }
  for (const std::string& key : KnownLoudLifts()) {
    INFO("listed as a loud lift but quiet: " << key);
    CHECK(loud.count(key) == 1);
  }
}
