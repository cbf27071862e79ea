// gesture_response: how each kiosk texture and the voice surface answer the hand
// (calibration/gesture_response.h): level and sharpness against speed, pressure and style, and
// through one accelerating stroke per style and pressure.
//
//   gesture_response --textures DIR [--docs DIR] [--places N]
//
// Prints the grid and the relations that fail; with --docs writes DIR/gesture-response.md (the
// table, every relation checked and which fail) and DIR/gesture-response.png (the plot). Exit 0
// when written (or printed), 1 on an error, 2 on a usage error; failing relations are reported,
// not an error (the test tests/kiosk/test_gesture_response.cpp holds the line).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "calibration/gesture_response.h"
#include "tools/command_line.h"

namespace {

using sas::kiosk::ResponseCell;

const cv::Scalar kStyleColour[3] = {{40, 90, 220}, {60, 160, 40}, {200, 110, 30}};  // BGR
constexpr int kPanelW = 440, kPanelH = 250, kLeft = 60, kRight = 14, kTop = 30, kBottom = 40;

// One panel: y against speed (log axis), one line per style and pressure (firm solid, light thin).
enum class Plotted { kSound, kSharpness, kVibration, kDetail };

void Panel(cv::Mat& image, int x0, int y0, const std::string& title,
           const std::vector<ResponseCell>& grid, Plotted what) {
  const cv::Rect area(x0 + kLeft, y0 + kTop, kPanelW - kLeft - kRight, kPanelH - kTop - kBottom);
  double lo = 1e300, hi = -1e300;
  const bool sharpness = what == Plotted::kSharpness;
  const auto value = [&](const ResponseCell& c) {
    switch (what) {
      case Plotted::kSharpness:
        return c.response.sharpness_acum;
      case Plotted::kVibration:
        return c.response.haptic_db;
      case Plotted::kDetail:
        return c.response.haptic_detail_db;
      case Plotted::kSound:
        break;
    }
    return c.response.sound_db;
  };
  for (const auto& c : grid) {
    lo = std::min(lo, value(c));
    hi = std::max(hi, value(c));
  }
  if (sharpness) {
    lo = std::floor(lo * 4.0) / 4.0;
    hi = std::ceil(hi * 4.0) / 4.0;
  } else {
    lo = std::floor(lo / 10.0) * 10.0;
    hi = std::ceil(hi / 10.0) * 10.0;
  }
  if (hi <= lo) hi = lo + 1.0;
  const double s_lo = std::log10(25.0), s_hi = std::log10(360.0);
  const auto px = [&](double speed) {
    return area.x + static_cast<int>((std::log10(speed) - s_lo) / (s_hi - s_lo) * area.width);
  };
  const auto py = [&](double v) {
    return area.y + area.height - static_cast<int>((v - lo) / (hi - lo) * area.height);
  };
  cv::rectangle(image, area, {0, 0, 0}, 1);
  cv::putText(image, title, {x0 + kLeft, y0 + 20}, cv::FONT_HERSHEY_SIMPLEX, 0.5, {0, 0, 0}, 1,
              cv::LINE_AA);
  for (const double speed : sas::kiosk::kResponseSpeedsMmS) {
    const int x = px(speed);
    cv::line(image, {x, area.y + area.height}, {x, area.y + area.height + 4}, {0, 0, 0});
    cv::putText(image, std::to_string(static_cast<int>(speed)), {x - 10, area.y + area.height + 18},
                cv::FONT_HERSHEY_SIMPLEX, 0.4, {0, 0, 0}, 1, cv::LINE_AA);
  }
  cv::putText(image, "speed, mm/s", {area.x + area.width / 2 - 40, area.y + area.height + 34},
              cv::FONT_HERSHEY_SIMPLEX, 0.4, {0, 0, 0}, 1, cv::LINE_AA);
  const int ticks = 4;
  for (int t = 0; t <= ticks; ++t) {
    const double v = lo + (hi - lo) * t / ticks;
    char label[32];
    if (sharpness) {
      std::snprintf(label, sizeof label, "%.2f", v);
    } else {
      std::snprintf(label, sizeof label, "%.0f", v);
    }
    cv::putText(image, label, {x0 + 8, py(v) + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.4, {0, 0, 0}, 1,
                cv::LINE_AA);
    cv::line(image, {area.x, py(v)}, {area.x + area.width, py(v)}, {225, 225, 225});
  }
  for (std::size_t s = 0; s < sas::kiosk::kResponseStyles.size(); ++s) {
    for (const double pressure : sas::kiosk::kResponsePressures) {
      std::vector<cv::Point> points;
      for (const auto& c : grid) {
        if (c.stroke.style == sas::kiosk::kResponseStyles[s] && c.stroke.pressure == pressure) {
          points.emplace_back(px(c.stroke.speed_mm_s), py(value(c)));
        }
      }
      const int thickness = pressure > 0.5 ? 2 : 1;
      cv::polylines(image, points, false, kStyleColour[s], thickness, cv::LINE_AA);
      for (const auto& p : points) cv::circle(image, p, 3, kStyleColour[s], -1, cv::LINE_AA);
    }
  }
}

void WritePlot(const std::string& path, const std::vector<std::string>& names,
               const std::vector<std::vector<ResponseCell>>& grids) {
  const int legend = 40;
  cv::Mat image(legend + kPanelH * static_cast<int>(names.size()), 4 * kPanelW, CV_8UC3,
                cv::Scalar(255, 255, 255));
  int x = 10;
  for (std::size_t s = 0; s < sas::kiosk::kResponseStyles.size(); ++s) {
    cv::line(image, {x, 20}, {x + 30, 20}, kStyleColour[s], 2, cv::LINE_AA);
    cv::putText(image, sas::synth::ProbeStyleName(sas::kiosk::kResponseStyles[s]).data(),
                {x + 36, 25}, cv::FONT_HERSHEY_SIMPLEX, 0.5, {0, 0, 0}, 1, cv::LINE_AA);
    x += 120;
  }
  cv::putText(image, "thick: pressure 0.8, thin: 0.2", {x + 20, 25}, cv::FONT_HERSHEY_SIMPLEX, 0.5,
              {0, 0, 0}, 1, cv::LINE_AA);
  for (std::size_t i = 0; i < names.size(); ++i) {
    const int y0 = legend + kPanelH * static_cast<int>(i);
    Panel(image, 0, y0, names[i] + ": sound level, dB", grids[i], Plotted::kSound);
    Panel(image, kPanelW, y0, names[i] + ": sharpness, acum", grids[i], Plotted::kSharpness);
    Panel(image, 2 * kPanelW, y0, names[i] + ": vibration, dB (skin-weighted)", grids[i],
          Plotted::kVibration);
    Panel(image, 3 * kPanelW, y0, names[i] + ": vibration detail, dB", grids[i],
          Plotted::kDetail);
  }
  if (!cv::imwrite(path, image)) throw std::runtime_error("cannot write " + path);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Level and sharpness of each kiosk texture and the voice surface against speed, "
      "pressure and style, and through accelerating strokes.",
      "gesture_response"};
  std::string textures = "textures";
  std::string docs;
  int places = sas::kiosk::kResponsePlaces;
  app.add_option("--textures", textures, "the kiosk textures' folder (default textures)");
  app.add_option("--docs", docs, "write gesture-response.md and gesture-response.png here");
  app.add_option("--places", places, "places per stroke, the median taken (default 8)")
      ->check(CLI::Range(1, 50));
  if (const int code = sas::kiosk::ParseProgramCommandLine(app, argc, argv); code >= 0) return code;
  try {
    const auto surfaces = sas::kiosk::LoadResponseSurfaces(textures);
    std::vector<std::string> names;
    std::vector<std::vector<ResponseCell>> grids;
    std::vector<std::vector<sas::kiosk::RampResponse>> ramps;
    std::vector<sas::kiosk::ResponseFailure> failures, exemptions;
    for (const auto& s : surfaces) {
      names.push_back(s.name);
      grids.push_back(sas::kiosk::MeasureResponseGrid(s, places));
      sas::kiosk::ResponseCheck check = sas::kiosk::CheckResponseGrid(s.name, grids.back());
      for (auto& f : check.failures) {
        std::printf("FAIL [%s] %s\n", f.key.c_str(), f.text.c_str());
        failures.push_back(std::move(f));
      }
      for (auto& f : check.exemptions) {
        std::printf("EXEMPT [%s] %s\n", f.key.c_str(), f.text.c_str());
        exemptions.push_back(std::move(f));
      }
      ramps.push_back(sas::kiosk::MeasureRamps(s, places));
      for (auto& f : sas::kiosk::CheckRamps(s.name, ramps.back())) {
        std::printf("FAIL [%s] %s\n", f.key.c_str(), f.text.c_str());
        failures.push_back(std::move(f));
      }
    }
    for (auto& f : sas::kiosk::CheckSharpestTexture(names, grids)) {
      std::printf("FAIL [%s] %s\n", f.key.c_str(), f.text.c_str());
      failures.push_back(std::move(f));
    }
    const int relations = (sas::kiosk::ResponseRelationCount() + sas::kiosk::RampRelationCount()) *
                              static_cast<int>(surfaces.size()) +
                          sas::kiosk::kSharpestRelationCount;
    const int holding =
        relations - static_cast<int>(failures.size()) - static_cast<int>(exemptions.size());
    std::printf("%d of %d relations hold, %zu exempt (sliding noise), %zu fail\n", holding,
                relations, exemptions.size(), failures.size());
    if (docs.empty()) return 0;
    std::filesystem::create_directories(docs);
    WritePlot((std::filesystem::path(docs) / "gesture-response.png").string(), names, grids);
    std::ofstream md(std::filesystem::path(docs) / "gesture-response.md");
    md << "# How the sound answers the hand\n\n"
          "Written by `gesture_response --docs docs` (textures/gesture_response.cpp); do not "
          "edit.\n"
          "Each texture and the voice surface, stroked along the same straight "
       << sas::kiosk::kPathMm
       << " mm path at 3 speeds, 2 pen pressures and in 3 styles (scrape: upright pen; rub: pen "
          "tilted 40°, a 4 mm probe; roll: a ball following the relief), through the kiosk's "
          "synth at gain 0 dB, "
       << places
       << " seeded places each, every figure the median over the places (calibration/"
          "gesture_response.h). Sound and vibration are RMS levels of the moving stroke in dB re "
          "full scale, the vibration skin-weighted (calibration/felt.h: the hand's threshold "
          "curve, Verrillo 1963); its detail is the range its 10 ms envelope spans (90th minus "
          "10th percentile, dB: bumps, cracks and grain lines move it, a smooth slide or a "
          "limiter's buzz does not); sharpness is DIN 45692's (acum, Zwicker loudness of ISO 532-1) with every "
          "stroke heard at "
       << sas::kiosk::kListeningDbSpl
       << " dB SPL, the level the kiosk plays a typical stroke at; the centroid is channel 1's "
          "power-weighted mean frequency.\n\n"
          "![level, sharpness, vibration and its detail against speed]"
          "(gesture-response.png)\n\n";
    md << "## Relations\n\nWanted on every surface: speed 30 → 300 mm/s raises the sound by ≥ 6 "
          "dB, "
          "the sharpness by ≥ 1.15× and the vibration; pressure 0.2 → 0.8 raises the sound by ≥ 3 "
          "dB; any two styles' level-normalised third-octave spectra (100 Hz–10 kHz) differ by ≥ 3 "
          "dB on average; through a stroke speeding up from 20 to 400 mm/s, level and sharpness "
          "follow the speed (Spearman's ρ ≥ 0.6 over its 12 windows); and broken glass is the "
          "sharpest texture at every speed (Character, below). **"
       << holding << " of " << relations << " hold, " << exemptions.size() << " are exempt and "
       << failures.size()
       << " fail.**\n\n"
          "Exempt: a pressure relation where the relief alone (the same stroke without friction "
          "and micro-roughness) plays at least 20 dB under the stroke at both pressures, and the "
          "firm stroke is at most 1 dB quieter. What sounds there is the sliding contact's own "
          "noise (the probe bridges the relief or stays above it), and the level of roughness "
          "noise follows the surfaces' roughness, the sliding speed and the bodies' dynamics, "
          "not a light load (Ben Abdelounis et al., Wear 268, 2010; Le Bot & Bou Chakra, "
          "Tribology Letters 37, 2010):\n\n";
    for (const auto& f : exemptions) md << "- " << f.text << "\n";
    if (exemptions.empty()) md << "- none\n";
    md << "\nFailing:\n\n";
    for (const auto& f : failures) md << "- " << f.text << "\n";
    if (failures.empty()) md << "- none\n";
    char line[256];
    md << "\n## Character\n\nWhat makes a texture gritty, tonal or clicky, on a 100 mm/s "
          "scrape (calibration/character.h): spectral flatness of the sound between 100 Hz and "
          "10 kHz (Welch PSD, geometric over arithmetic mean: 1 for white noise, near 0 for a "
          "few tones), its crest factor and its onsets per second (5 ms frames rising 6 dB over "
          "the 30 ms before).\n\n| surface | pressure | flatness | crest, dB | onsets/s |\n"
          "|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < names.size(); ++i) {
      for (const auto& c : grids[i]) {
        if (c.stroke.style != sas::synth::ProbeStyle::kScrape || c.stroke.speed_mm_s != 100.0) {
          continue;
        }
        std::snprintf(line, sizeof line, "| %s | %.1f | %.3f | %.1f | %.0f |\n", names[i].c_str(),
                      c.stroke.pressure, c.response.flatness, c.response.crest_db,
                      c.response.onsets_per_s);
        md << line;
      }
    }
    md << "\nHow sharp each surface sounds at each speed: the median sharpness (acum) of its "
          "styles and pressures. Broken glass should be the sharpest texture at every speed.\n\n"
          "| surface |";
    for (const double speed : sas::kiosk::kResponseSpeedsMmS) md << " " << speed << " mm/s |";
    md << "\n|---|";
    for (std::size_t k = 0; k < sas::kiosk::kResponseSpeedsMmS.size(); ++k) md << "---|";
    md << "\n";
    for (std::size_t i = 0; i < names.size(); ++i) {
      md << "| " << names[i] << " |";
      for (const double speed : sas::kiosk::kResponseSpeedsMmS) {
        std::snprintf(line, sizeof line, " %.2f |", sas::kiosk::SharpnessAtSpeed(grids[i], speed));
        md << line;
      }
      md << "\n";
    }
    md << "\n## Speeding up\n\nOne stroke per style and pressure whose speed rises steadily "
          "from "
       << sas::kiosk::kRampFromMmS << " to " << sas::kiosk::kRampToMmS << " mm/s in "
       << sas::kiosk::kRampS
       << " s across the middle of the picture, the pen at rest on the surface before it; level "
          "(dB) and sharpness (acum) of each of its "
       << sas::kiosk::kRampWindows
       << " equal windows, the median over the places, and Spearman's ρ of each against the "
          "window's speed.\n\n| surface | style | pressure | ρ level | ρ sharpness | level, slow "
          "→ fast | sharpness, slow → fast |\n|---|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < names.size(); ++i) {
      for (const auto& r : ramps[i]) {
        std::string levels, sharps;
        for (int w = 0; w < sas::kiosk::kRampWindows; ++w) {
          char one[24];
          std::snprintf(one, sizeof one, "%.0f", r.sound_db[static_cast<std::size_t>(w)]);
          levels += (w ? " " : "") + std::string(one);
          std::snprintf(one, sizeof one, "%.2f", r.sharpness_acum[static_cast<std::size_t>(w)]);
          sharps += (w ? " " : "") + std::string(one);
        }
        std::snprintf(line, sizeof line, "| %s | %s | %.1f | %.2f | %.2f | ", names[i].c_str(),
                      sas::synth::ProbeStyleName(r.style).data(), r.pressure, r.sound_rho,
                      r.sharpness_rho);
        md << line << levels << " | " << sharps << " |\n";
      }
    }
    md << "\n## The grid\n\n";
    for (std::size_t i = 0; i < names.size(); ++i) {
      md << "### " << names[i]
         << "\n\n| style | speed, mm/s | pressure | sound, dB | vibration, dB (skin) "
            "| vibration detail, dB | sharpness, acum | centroid, Hz | relief alone, dB "
            "| relief alone's centroid, Hz | flatness | crest, dB | onsets/s |\n"
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
      for (const auto& c : grids[i]) {
        const bool relief_heard = c.response.relief_db >= sas::kiosk::kPrintFloorDb;
        std::snprintf(
            line, sizeof line,
            "| %s | %.0f | %.1f | %.1f | %.1f | %.1f | %.2f | %.0f | %s | %s | %.3f | %.1f | "
            "%.0f |\n",
            sas::synth::ProbeStyleName(c.stroke.style).data(), c.stroke.speed_mm_s,
            c.stroke.pressure, c.response.sound_db, c.response.haptic_db,
            c.response.haptic_detail_db, c.response.sharpness_acum,
            c.response.centroid_hz, sas::kiosk::LevelText(c.response.relief_db).c_str(),
            relief_heard ? std::to_string(std::lround(c.response.relief_centroid_hz)).c_str() : "-",
            c.response.flatness, c.response.crest_db, c.response.onsets_per_s);
        md << line;
      }
      md << "\n";
    }
    if (!md) throw std::runtime_error("cannot write " + docs + "/gesture-response.md");
    std::printf("wrote %s/gesture-response.md and gesture-response.png\n", docs.c_str());
  } catch (const std::exception& error) {
    std::fprintf(stderr, "gesture_response: %s\n", error.what());
    return 1;
  }
  return 0;
}
