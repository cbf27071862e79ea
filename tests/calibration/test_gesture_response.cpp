// How the sound answers the hand (calibration/gesture_response.h): the grid of 4 kiosk textures and
// the voice surface × 3 styles × 3 speeds × 2 pressures, through the kiosk's synth, and the
// relations a blind visitor relies on (faster = louder and brighter, firmer = louder, styles
// distinct).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "calibration/gesture_response.h"
#include "sas/version.h"

namespace {

using sas::kiosk::CheckResponseGrid;
using sas::kiosk::ResponseCell;
using sas::synth::ProbeStyle;

#if !defined(__SANITIZE_ADDRESS__)
// The relations today's materials do not meet, measured by `gesture_response` and listed with
// their figures in docs/gesture-response.md. The models and materials are to be changed until
// this list is empty; a change that breaks a relation not listed here fails the test, and one
// that meets a listed relation should delete its line.
const std::set<std::string>& KnownOpen() {
  static const std::set<std::string> keys = {
      "bubble wrap/speed-sharpness/scrape/p0.8",
      "bubble wrap/style-spectra/rub-roll/30mm/s,p0.2",
      "bubble wrap/style-spectra/rub-roll/100mm/s,p0.2",
      "bubble wrap/style-spectra/rub-roll/300mm/s,p0.2",
      "bubble wrap/ramp-sharpness/scrape/p0.8",
      "broken glass/speed-sound/rub/p0.8",
      "broken glass/speed-sharpness/scrape/p0.8",
      "broken glass/ramp-sharpness/scrape/p0.2",
      "broken glass/ramp-sharpness/scrape/p0.8",
      "broken glass/ramp-sharpness/rub/p0.2",
      "broken glass/ramp-sound/rub/p0.8",
      "broken glass/ramp-sharpness/roll/p0.2",
      // The felt channel is the contact force: a light roll over the pane feels its cracks, and
      // at 300 mm/s it feels them 4 dB less than at 30 (not yet explained).
      "broken glass/speed-haptic/roll/p0.2",
      "wooden board/speed-sharpness/scrape/p0.8",
      "wooden board/pressure-sound/scrape/100mm/s",
      "wooden board/ramp-sharpness/scrape/p0.8",
      "wooden board/ramp-sharpness/roll/p0.8",
      "cracked ground/speed-sharpness/rub/p0.2",
      "cracked ground/speed-sharpness/rub/p0.8",
      "cracked ground/speed-sharpness/roll/p0.8",
      "cracked ground/style-spectra/scrape-roll/100mm/s,p0.2",
      "cracked ground/style-spectra/scrape-roll/300mm/s,p0.8",
      "cracked ground/ramp-sharpness/rub/p0.8",
      "cracked ground/ramp-sharpness/roll/p0.2",
      "cracked ground/ramp-sharpness/roll/p0.8",
      "voice/ramp-sharpness/scrape/p0.8",
      "voice/ramp-sharpness/roll/p0.8",
      "voice/style-spectra/rub-roll/30mm/s,p0.2",
      "voice/ramp-sound/roll/p0.2",
      "character/glass-sharpest/30mm/s",
      "character/glass-sharpest/100mm/s",
      "character/glass-sharpest/300mm/s",
  };
  return keys;
}

// The pressure relations exempt as sliding noise (CheckResponseGrid: the relief alone >= 20 dB
// under the stroke at both pressures, the firm stroke not quieter by more than 1 dB), with their
// figures in docs/gesture-response.md. Listed so that a change which turns more relations into
// sliding noise is looked at, not silently accepted.
const std::set<std::string>& KnownExempt() {
  static const std::set<std::string> keys = {
      "bubble wrap/pressure-sound/rub/30mm/s",  "bubble wrap/pressure-sound/rub/100mm/s",
      "bubble wrap/pressure-sound/rub/300mm/s", "cracked ground/pressure-sound/rub/300mm/s",
      "voice/pressure-sound/rub/30mm/s",
  };
  return keys;
}
#endif

// A grid whose every relation holds by construction: level +8 dB and sharpness x1.5 from the slow
// to the fast speed, +4 dB from light to firm, and three styles with clearly different spectra.
std::vector<ResponseCell> GoodGrid() {
  std::vector<ResponseCell> grid;
  int style_index = 0;
  for (const ProbeStyle style : sas::kiosk::kResponseStyles) {
    for (std::size_t s = 0; s < sas::kiosk::kResponseSpeedsMmS.size(); ++s) {
      for (std::size_t p = 0; p < sas::kiosk::kResponsePressures.size(); ++p) {
        ResponseCell cell;
        cell.stroke = {style, sas::kiosk::kResponseSpeedsMmS[s], sas::kiosk::kResponsePressures[p]};
        cell.response.sound_db =
            -60.0 + 4.0 * static_cast<double>(s) + 4.0 * static_cast<double>(p);
        cell.response.haptic_db = cell.response.sound_db;
        cell.response.relief_db = cell.response.sound_db;  // the relief is what is heard
        cell.response.sharpness_acum = 1.0 + 0.25 * static_cast<double>(s);
        for (std::size_t b = 0; b < cell.response.band_db.size(); ++b) {
          // Each style tilts its spectrum its own way: 0, +0.6, -0.6 dB per band.
          const double tilt = style_index == 0 ? 0.0 : (style_index == 1 ? 0.6 : -0.6);
          cell.response.band_db[b] = tilt * (static_cast<double>(b) - 10.0);
        }
        grid.push_back(cell);
      }
    }
    ++style_index;
  }
  return grid;
}

}  // namespace

TEST_CASE(
    "gesture response: the checker passes a grid that meets every relation and names each "
    "one that a grid breaks",
    "[kiosk][gesture]") {
  std::vector<ResponseCell> grid = GoodGrid();
  CHECK(CheckResponseGrid("test", grid).failures.empty());
  CHECK(CheckResponseGrid("test", grid).exemptions.empty());
  // Break one relation of each kind.
  for (auto& c : grid) {
    if (c.stroke.style == ProbeStyle::kRub && c.stroke.speed_mm_s == 300.0 &&
        c.stroke.pressure == 0.2) {
      c.response.sharpness_acum = 1.12;  // x1.12 only
    }
    if (c.stroke.style == ProbeStyle::kRoll && c.stroke.speed_mm_s == 100.0 &&
        c.stroke.pressure == 0.8) {
      c.response.sound_db -= 3.0;  // firm only +1 dB above light
    }
    if (c.stroke.style == ProbeStyle::kScrape && c.stroke.speed_mm_s == 30.0 &&
        c.stroke.pressure == 0.8) {
      c.response.haptic_db = 0.0;  // the vibration falls with speed
    }
  }
  std::set<std::string> keys;
  for (const auto& f : CheckResponseGrid("test", grid).failures) keys.insert(f.key);
  CHECK(keys == std::set<std::string>{"test/speed-sharpness/rub/p0.2",
                                      "test/pressure-sound/roll/100mm/s",
                                      "test/speed-haptic/scrape/p0.8"});
  // Two styles with the same spectrum shape are not distinct.
  for (auto& c : grid) {
    if (c.stroke.style == ProbeStyle::kRoll) {
      for (std::size_t b = 0; b < c.response.band_db.size(); ++b) {
        c.response.band_db[b] = 0.1 * (static_cast<double>(b) - 10.0);
      }
    }
  }
  int style_failures = 0;
  for (const auto& f : CheckResponseGrid("test", grid).failures) {
    if (f.key.find("style-spectra/scrape-roll/") != std::string::npos) ++style_failures;
  }
  CHECK(style_failures == 6);  // every speed and pressure
}

TEST_CASE(
    "gesture response: broken glass must be the sharpest texture at every speed, the voice "
    "surface left out",
    "[kiosk][gesture]") {
  // Two cells per speed for each surface, sharpness rising with speed; glass the sharpest.
  const auto grid = [](double base) {
    std::vector<ResponseCell> g;
    for (const double speed : sas::kiosk::kResponseSpeedsMmS) {
      for (const double pressure : sas::kiosk::kResponsePressures) {
        ResponseCell c;
        c.stroke = {ProbeStyle::kScrape, speed, pressure};
        c.response.sharpness_acum = base + speed / 1000.0;
        g.push_back(c);
      }
    }
    return g;
  };
  const std::vector<std::string> names = {"bubble wrap", "broken glass", "wooden board", "voice"};
  std::vector<std::vector<ResponseCell>> grids = {grid(1.0), grid(2.0), grid(1.5), grid(3.0)};
  CHECK(sas::kiosk::SharpnessAtSpeed(grids[1], 100.0) == Approx(2.1));
  CHECK(sas::kiosk::CheckSharpestTexture(names, grids).empty());  // the voice does not count
  // The wooden board sharper than the glass at 300 mm/s only.
  for (auto& c : grids[2]) {
    if (c.stroke.speed_mm_s == 300.0) c.response.sharpness_acum = 2.5;
  }
  const auto failures = sas::kiosk::CheckSharpestTexture(names, grids);
  REQUIRE(failures.size() == 1);
  CHECK(failures[0].key == "character/glass-sharpest/300mm/s");
  CHECK(failures[0].text.find("wooden board 2.50") != std::string::npos);
}

TEST_CASE(
    "gesture response: Spearman's rho is 1 for any rising series, -1 for a falling one and takes "
    "ties at their mean rank",
    "[kiosk][gesture]") {
  using sas::kiosk::SpearmanRho;
  const std::vector<double> speed = {20, 50, 90, 150, 260, 400};
  CHECK(SpearmanRho(speed, std::vector<double>{-60, -55, -54, -40, -39, -20}) ==
        Approx(1.0).margin(1e-12));
  CHECK(SpearmanRho(speed, std::vector<double>{3, 2, 1, 0, -1, -2}) == Approx(-1.0).margin(1e-12));
  // Ranks 1 2 3 4 5 6 against 2 1 4 3 6 5: 1 - 6 * 6 / (6 * 35) = 0.82857.
  CHECK(SpearmanRho(speed, std::vector<double>{2, 1, 4, 3, 6, 5}) ==
        Approx(0.828571).epsilon(1e-5));
  // Ties: ranks of {1, 1, 2, 3} are 1.5 1.5 3 4; Pearson of those with 1 2 3 4 is 0.948683.
  CHECK(SpearmanRho(std::vector<double>{1, 2, 3, 4}, std::vector<double>{1, 1, 2, 3}) ==
        Approx(0.948683).epsilon(1e-5));
  CHECK(SpearmanRho(speed, std::vector<double>(6, 1.0)) == 0.0);
}

TEST_CASE(
    "gesture response: an accelerating stroke passes when level and sharpness rise with its "
    "speed and is named when either does not",
    "[kiosk][gesture]") {
  sas::kiosk::RampResponse rising;
  rising.style = ProbeStyle::kRoll;
  rising.pressure = 0.8;
  rising.sound_rho = 0.9;
  rising.sharpness_rho = 0.7;
  CHECK(sas::kiosk::CheckRamps("test", {rising}).empty());
  sas::kiosk::RampResponse darker = rising;
  darker.sharpness_rho = -0.7;
  for (int w = 0; w < sas::kiosk::kRampWindows; ++w)
    darker.sharpness_acum[static_cast<std::size_t>(w)] = 2.0 - 0.05 * w;
  const auto failures = sas::kiosk::CheckRamps("test", {rising, darker});
  REQUIRE(failures.size() == 1);
  CHECK(failures[0].key == "test/ramp-sharpness/roll/p0.8");
  CHECK(failures[0].text.find("rho -0.70") != std::string::npos);
  CHECK(failures[0].text.find("2.00 1.95 1.90") != std::string::npos);
  darker.sound_rho = 0.59;
  CHECK(sas::kiosk::CheckRamps("test", {darker}).size() == 2);
}

TEST_CASE(
    "gesture response: the measured places are the same on every run, distinct, and inside "
    "the middle of the picture",
    "[kiosk][gesture]") {
  std::set<std::pair<long, long>> seen;
  for (int p = 0; p < sas::kiosk::kResponsePlaces; ++p) {
    const auto a = sas::kiosk::ResponsePlace(p, 294.0, 166.0);
    const auto b = sas::kiosk::ResponsePlace(p, 294.0, 166.0);
    CHECK(a.cx_mm == b.cx_mm);
    CHECK(a.dy == b.dy);
    CHECK(a.cx_mm >= 0.2 * 294.0);
    CHECK(a.cx_mm <= 0.8 * 294.0);
    CHECK(a.cy_mm >= 0.2 * 166.0);
    CHECK(a.cy_mm <= 0.8 * 166.0);
    CHECK(std::hypot(a.dx, a.dy) == Approx(1.0));
    seen.insert({std::lround(a.cx_mm), std::lround(a.cy_mm)});
  }
  CHECK(seen.size() == static_cast<std::size_t>(sas::kiosk::kResponsePlaces));
}

TEST_CASE("gesture response: levels under -150 dB print as silent", "[kiosk][gesture]") {
  CHECK(sas::kiosk::LevelText(-42.46) == "-42.5");
  CHECK(sas::kiosk::LevelText(-149.96) == "-150.0");
  CHECK(sas::kiosk::LevelText(-150.01) == "< -150");
  CHECK(sas::kiosk::LevelText(-225.9) == "< -150");
}

TEST_CASE(
    "gesture response: a pressure relation is exempt only where the relief alone is far under "
    "the stroke at both pressures and the firm stroke is not quieter",
    "[kiosk][gesture]") {
  std::vector<ResponseCell> grid = GoodGrid();
  // Every stroke's relief alone 30 dB under it: sliding noise everywhere, but the relations hold,
  // so nothing is exempt.
  for (auto& c : grid) c.response.relief_db = c.response.sound_db - 30.0;
  CHECK(CheckResponseGrid("test", grid).exemptions.empty());
  const auto cell = [&](ProbeStyle style, double speed, double pressure) -> ResponseCell& {
    for (auto& c : grid) {
      if (c.stroke.style == style && c.stroke.speed_mm_s == speed && c.stroke.pressure == pressure)
        return c;
    }
    throw std::logic_error("no such cell");
  };
  // The firm rub at 100 mm/s only 0.5 dB over the light one, both sliding noise: exempt.
  ResponseCell& light = cell(ProbeStyle::kRub, 100.0, 0.2);
  ResponseCell& firm = cell(ProbeStyle::kRub, 100.0, 0.8);
  firm.response.sound_db = light.response.sound_db + 0.5;
  firm.response.relief_db = firm.response.sound_db - 30.0;
  auto check = CheckResponseGrid("test", grid);
  CHECK(check.failures.empty());
  REQUIRE(check.exemptions.size() == 1);
  CHECK(check.exemptions[0].key == "test/pressure-sound/rub/100mm/s");
  CHECK(check.exemptions[0].text.find("30 / 30 dB under") != std::string::npos);
  // A silent relief (float residue of a ring) is printed as silent, not as -220 dB.
  firm.response.relief_db = -220.0;
  check = CheckResponseGrid("test", grid);
  REQUIRE(check.exemptions.size() == 1);
  CHECK(check.exemptions[0].text.find("-86.0 / < -150 dB, 30 / over 94 dB under") !=
        std::string::npos);
  CHECK(check.exemptions[0].text.find("-220") == std::string::npos);
  // The relief of the firm stroke within 20 dB of it: the relief is heard, the relation fails.
  firm.response.relief_db = firm.response.sound_db - 15.0;
  check = CheckResponseGrid("test", grid);
  CHECK(check.exemptions.empty());
  REQUIRE(check.failures.size() == 1);
  CHECK(check.failures[0].key == "test/pressure-sound/rub/100mm/s");
  // Sliding noise again, but the firm stroke 2 dB quieter than the light one: a failure.
  firm.response.relief_db = firm.response.sound_db - 30.0;
  firm.response.sound_db = light.response.sound_db - 2.0;
  firm.response.relief_db = firm.response.sound_db - 30.0;
  check = CheckResponseGrid("test", grid);
  CHECK(check.exemptions.empty());
  CHECK(check.failures.size() == 1);
}

#if defined(__SANITIZE_ADDRESS__)
// The sanitizer build (~10x slower: the whole grid took 486 s there) measures one surface at one
// place: the measuring path runs, every stroke and window is heard and the checks run on real
// figures; the relations themselves are the normal build's.
TEST_CASE("gesture response: one surface at one place measures, and is heard", "[kiosk][gesture]") {
  const auto surfaces = sas::kiosk::LoadResponseSurfaces(
      (std::filesystem::path(sas::kSourceDir) / "textures").string());
  REQUIRE(surfaces.size() == 5);
  const auto& glass = surfaces[1];
  const std::vector<ResponseCell> grid = sas::kiosk::MeasureResponseGrid(glass, 1);
  REQUIRE(grid.size() == 18);
  for (const auto& c : grid) {
    CHECK(c.response.sound_db > -140.0);
    CHECK(c.response.sharpness_acum > 0.1);
  }
  const auto ramps = sas::kiosk::MeasureRamps(glass, 1);
  REQUIRE(ramps.size() == 6);
  for (const auto& r : ramps) {
    for (const double db : r.sound_db) CHECK(db > -140.0);
  }
  // The checks run on the measured figures and name what they find on this surface.
  auto found = CheckResponseGrid(glass.name, grid).failures;
  for (auto& f : sas::kiosk::CheckRamps(glass.name, ramps)) found.push_back(f);
  for (const auto& f : found) {
    CHECK(f.key.rfind("broken glass/", 0) == 0);
    CHECK(f.text.rfind("broken glass, ", 0) == 0);
  }
}
#else
TEST_CASE(
    "gesture response: on the four kiosk textures and the voice surface, no relation "
    "beyond the known open ones fails (medians of 8 places: speed 30 -> 300 mm/s gives +6 dB, "
    "x1.15 sharpness and more vibration, pressure 0.2 -> 0.8 gives +3 dB, styles 3 dB apart, and "
    "level and sharpness follow a stroke speeding up from 20 to 400 mm/s)",
    "[kiosk][gesture]") {
  const auto surfaces = sas::kiosk::LoadResponseSurfaces(
      (std::filesystem::path(sas::kSourceDir) / "textures").string());
  REQUIRE(surfaces.size() == 5);
  int holding = 0;
  int exempt = 0;
  std::set<std::string> failing, exempted;
  std::vector<std::string> names;
  std::vector<std::vector<ResponseCell>> grids;
  for (const auto& surface : surfaces) {
    const std::vector<ResponseCell> grid = sas::kiosk::MeasureResponseGrid(surface);
    names.push_back(surface.name);
    grids.push_back(grid);
    REQUIRE(grid.size() == 18);
    // Every stroke was heard: the measurement itself is not silent.
    for (const auto& c : grid) {
      INFO(surface.name << " " << sas::synth::ProbeStyleName(c.stroke.style) << " "
                        << c.stroke.speed_mm_s << " mm/s p " << c.stroke.pressure);
      CHECK(c.response.sound_db > -140.0);
      CHECK(c.response.centroid_hz > 20.0);
      CHECK(c.response.sharpness_acum > 0.1);
      // Cracked ground crumbles: its scrape is gritty (noise-like), not a few damped thuds.
      if (surface.name == "cracked ground" && c.stroke.style == ProbeStyle::kScrape &&
          c.stroke.speed_mm_s == 100.0) {
        CHECK(c.response.flatness >= 0.1);
      }
    }
    auto check = CheckResponseGrid(surface.name, grid);
    const auto ramps = sas::kiosk::MeasureRamps(surface);
    REQUIRE(ramps.size() == 6);
    for (const auto& r : ramps) {
      // Every window of the accelerating stroke was heard.
      for (const double db : r.sound_db) CHECK(db > -140.0);
    }
    for (auto& f : sas::kiosk::CheckRamps(surface.name, ramps)) check.failures.push_back(f);
    holding += sas::kiosk::ResponseRelationCount() + sas::kiosk::RampRelationCount() -
               static_cast<int>(check.failures.size());
    for (const auto& f : check.failures) {
      INFO(f.text);
      CHECK(KnownOpen().count(f.key) == 1);
      failing.insert(f.key);
    }
    for (const auto& f : check.exemptions) {
      WARN("exempt: " << f.text);
      CHECK(KnownExempt().count(f.key) == 1);
      exempted.insert(f.key);
      ++exempt;
    }
  }
  // Character across the textures: broken glass the sharpest at every speed.
  const auto sharpest = sas::kiosk::CheckSharpestTexture(names, grids);
  holding += sas::kiosk::kSharpestRelationCount - static_cast<int>(sharpest.size());
  for (const auto& f : sharpest) {
    INFO(f.text);
    CHECK(KnownOpen().count(f.key) == 1);
    failing.insert(f.key);
  }
  WARN(holding << " of "
               << 5 * (sas::kiosk::ResponseRelationCount() + sas::kiosk::RampRelationCount()) +
                      sas::kiosk::kSharpestRelationCount
               << " relations hold (" << exempt
               << " of them exempt); known open: " << KnownOpen().size());
  // The list stays exact: a relation that now holds must leave it, so it cannot hide a later
  // regression.
  for (const std::string& key : KnownOpen()) {
    INFO("listed as open but holds: " << key);
    CHECK(failing.count(key) == 1);
  }
  for (const std::string& key : KnownExempt()) {
    INFO("listed as exempt but not: " << key);
    CHECK(exempted.count(key) == 1);
  }
}
#endif
