// Checks a screenshot (PNG) of the live kiosk's staff panel (staff_panel_xvfb_e2e.sh):
//   staff_panel_check <shot.png> <picture shown under the panel> <config path given to the kiosk>
// Read from the pixels, with the panel where ui::StaffPanelRect puts it:
//  - outside the panel the screen is the picture fitted to the screen under the attract screen's
//    uniform veil, so the pixels under the translucent panel are known. The panel's plate is
//    measured where no text can be (above its first line, left of its lines) as a colour laid
//    over the picture (screen = k + s * picture per channel), which must fit those pixels;
//  - the panel's two text colours, measured on the fully covered glyph pixels of two lines found
//    in the shot (the title, amber; "Configuration: <path> (accepted)", white), reach 7:1 against
//    the plate laid over the brightest picture pixel anywhere under the panel's lines without the
//    veil (the visitor screens' rule, tests/ui/test_visitor_screens.cpp) and against every
//    text-free pixel around them;
//  - each button's label (its brightest pixels) reaches 7:1 against the button (its commonest
//    colour);
//  - those two lines are drawn as written, in normal case: the shot matches them rendered in the
//    panel's font and size, and not their upper-case rendering (the bitmap fallback's capitals),
//    so the configuration path reads as given and can be typed.
// Exit 0 when all hold, 1 otherwise; each check prints its figures.
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "sas/version.h"
#include "tools/command_line.h"
#include "ui/overlay.h"
#include "ui/picture_io.h"
#include "ui/ttf_text.h"

namespace {

using sas::ui::ImageRgba;
using sas::ui::PixelRect;
using sas::ui::Rgba;
using sas::ui::TextMask;

constexpr double kMinContrast = 7.0;

// WCAG 2 relative luminance of an sRGB colour (0..255 per channel).
double Luminance(double r, double g, double b) {
  const auto lin = [](double c) {
    c /= 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  };
  return 0.2126 * lin(r) + 0.7152 * lin(g) + 0.0722 * lin(b);
}
double Luminance(Rgba c) {
  return Luminance(c.r, c.g, c.b);
}
double Contrast(double l1, double l2) {
  return (std::max(l1, l2) + 0.05) / (std::min(l1, l2) + 0.05);
}

bool failed = false;
void Expect(bool ok, const std::string& what) {
  std::printf("%s: %s\n", ok ? "ok" : "FAIL", what.c_str());
  if (!ok) failed = true;
}
std::string Num(double v, int decimals = 2) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, v);
  return text;
}
std::string Hex(Rgba c) {
  char text[16];
  std::snprintf(text, sizeof text, "#%02x%02x%02x", c.r, c.g, c.b);
  return text;
}

// Pearson correlation of the mask's coverage with the shot's luminance where the mask would be
// drawn at (x, y): near 1 where exactly that text is drawn, whatever the colours.
double Match(const ImageRgba& shot, const TextMask& mask, int x, int y) {
  if (x < 0 || y < 0 || x + mask.w > shot.width() || y + mask.h > shot.height()) return -1.0;
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  const double n = static_cast<double>(mask.w) * mask.h;
  for (int j = 0; j < mask.h; ++j) {
    for (int i = 0; i < mask.w; ++i) {
      const double a = mask.alpha[static_cast<std::size_t>(j * mask.w + i)];
      const Rgba p = shot.at(x + i, y + j);
      const double b = 0.2126 * p.r + 0.7152 * p.g + 0.0722 * p.b;
      sa += a;
      sb += b;
      saa += a * a;
      sbb += b * b;
      sab += a * b;
    }
  }
  const double va = saa - sa * sa / n, vb = sbb - sb * sb / n;
  return va <= 0 || vb <= 0 ? 0.0 : (sab - sa * sb / n) / std::sqrt(va * vb);
}

// The best row for `mask` at column x between rows y0 and y1, and its match.
std::pair<int, double> Find(const ImageRgba& shot, const TextMask& mask, int x, int y0, int y1) {
  std::pair<int, double> best{-1, -2.0};
  for (int y = y0; y <= y1; ++y) {
    const double m = Match(shot, mask, x, y);
    if (m > best.second) best = {y, m};
  }
  return best;
}

// A layer over the picture, per channel: screen = k + s * picture (a colour laid over it at
// some opacity), fitted by least squares on the given pixels; residual is the largest deviation.
struct Layer {
  std::array<double, 3> k{}, s{};
  double residual = 0;
};
Layer Fit(const ImageRgba& shot, const ImageRgba& under,
          const std::vector<std::pair<int, int>>& pixels) {
  Layer layer;
  const double n = static_cast<double>(pixels.size());
  for (std::size_t c = 0; c < 3; ++c) {
    const auto channel = [c](Rgba p) { return c == 0 ? p.r : c == 1 ? p.g : p.b; };
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (const auto& [x, y] : pixels) {
      const double u = channel(under.at(x, y)), v = channel(shot.at(x, y));
      sx += u;
      sy += v;
      sxx += u * u;
      sxy += u * v;
    }
    const double var = sxx - sx * sx / n;
    layer.s[c] = var > 0 ? (sxy - sx * sy / n) / var : 0.0;
    layer.k[c] = (sy - layer.s[c] * sx) / n;
    for (const auto& [x, y] : pixels) {
      layer.residual = std::max(
          layer.residual,
          std::abs(layer.k[c] + layer.s[c] * channel(under.at(x, y)) - channel(shot.at(x, y))));
    }
  }
  return layer;
}

std::string Upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

// Outside the panel: the picture under the attract screen's veil (a uniform dark layer that
// breathes), measured as screen = k + s * picture per channel away from the pulsing frame
// along the screen's edges.
Layer CheckVeil(const ImageRgba& shot, const ImageRgba& under, const PixelRect& panel) {
  const int width = shot.width(), height = shot.height();
  const int edge = 24;
  std::vector<std::pair<int, int>> outside;
  for (int y = edge; y < height - edge; y += 2) {
    for (int x = edge; x < width - edge; x += 2) {
      if (!PixelRect{panel.x - 2, panel.y - 2, panel.w + 4, panel.h + 4}.Contains(x, y)) {
        outside.push_back({x, y});
      }
    }
  }
  const Layer veil = Fit(shot, under, outside);
  std::printf("outside: screen = (%.1f, %.1f, %.1f) + (%.3f, %.3f, %.3f) * picture\n", veil.k[0],
              veil.k[1], veil.k[2], veil.s[0], veil.s[1], veil.s[2]);
  Expect(veil.residual <= 4.0 && veil.s[0] > 0.2 && veil.s[1] > 0.2 && veil.s[2] > 0.2,
         "outside the panel the screen shows the picture, at most veiled (largest deviation " +
             Num(veil.residual, 1) + " levels)");
  return veil;
}

// The plate, measured the same way where no text can be: between the frame and the first
// line's top (panel.y + 16) and left of the lines (panel.x + 16). The frame is at most 1% of
// the shorter side thick (ui::AddStaffPanelFrame's 0.6%). Returns the brightest the plate gets
// over the picture anywhere under the panel's lines, with the veil taken away: the veil only
// darkens, so this bounds every moment of its breath. With the veil (k_v, s_v) under a plate of
// colour C and opacity a, the panel's fit is k = a C + (1 - a) k_v, s = (1 - a) s_v; the plate
// alone over the picture is a C + (1 - a) picture.
double BrightestPlate(const ImageRgba& shot, const ImageRgba& under, const PixelRect& panel,
                      const Layer& veil, int text_bottom) {
  const int width = shot.width(), height = shot.height();
  const int frame = std::max(2, std::min(width, height) / 100);
  std::vector<std::pair<int, int>> clear;  // x, y of plate-only pixels
  for (int y = panel.y + frame; y < panel.y + 15; ++y) {
    for (int x = panel.x + frame; x < panel.x + panel.w - frame; ++x) clear.push_back({x, y});
  }
  for (int y = panel.y + 15; y < text_bottom; ++y) {
    for (int x = panel.x + frame; x < panel.x + 15; ++x) clear.push_back({x, y});
  }
  const Layer plate = Fit(shot, under, clear);
  std::printf("panel: screen = (%.1f, %.1f, %.1f) + (%.3f, %.3f, %.3f) * picture\n", plate.k[0],
              plate.k[1], plate.k[2], plate.s[0], plate.s[1], plate.s[2]);
  Expect(clear.size() > 1000 && plate.residual <= 4.0,
         "the panel's plate is a colour laid over the picture (" + std::to_string(clear.size()) +
             " text-free pixels, largest deviation " + Num(plate.residual, 1) + " levels)");
  double plate_max_l = 0;
  for (int y = panel.y; y < text_bottom; ++y) {
    for (int x = panel.x; x < panel.x + panel.w; ++x) {
      const Rgba p = under.at(x, y);
      std::array<double, 3> bare{};
      for (std::size_t c = 0; c < 3; ++c) {
        const double clear_part = plate.s[c] / veil.s[c];  // 1 - a
        bare[c] = plate.k[c] - clear_part * veil.k[c] +
                  clear_part * (c == 0   ? p.r
                                : c == 1 ? p.g
                                         : p.b);
      }
      plate_max_l = std::max(plate_max_l, Luminance(bare[0], bare[1], bare[2]));
    }
  }
  return plate_max_l;
}

struct Line {
  std::string what, content;
  bool at_top;  // the first line, at the panel's top margin; else anywhere below it
};

// One line of the panel's text: drawn where the panel draws it, not in capitals, and at least
// kMinContrast over the plate at its brightest and over the pixels around its glyphs.
void CheckLine(const ImageRgba& shot, sas::ui::TextRenderer& text, const Line& line, int size_px,
               int left, const PixelRect& panel, int text_bottom, double plate_max_l) {
  const auto mask = text.Render(line.content, size_px);
  const auto upper = text.Render(Upper(line.content), size_px);
  if (!mask || !upper) {
    Expect(false, "render \"" + line.content + "\"");
    return;
  }
  const int y0 = panel.y + 16;
  const int y1 = line.at_top ? panel.y + 16 : text_bottom - mask->h;
  const auto [y, match] = Find(shot, *mask, left, y0, y1);
  const double upper_match = Find(shot, *upper, left, y0, y1).second;
  Expect(match >= 0.95, line.what + " \"" + line.content + "\" drawn at " + std::to_string(left) +
                            "," + std::to_string(y) + " (match " + Num(match, 3) + ")");
  Expect(upper_match < 0.8 && upper_match < match - 0.15,
         line.what + " not in capitals (best match of \"" + Upper(line.content) + "\" " +
             Num(upper_match, 3) + ")");
  if (match < 0.95) return;
  // Text colour: the commonest colour of the glyphs' fully covered pixels.
  std::map<std::array<int, 3>, int> counts;
  double around_max_l = 0;
  for (int j = 0; j < mask->h; ++j) {
    for (int i = 0; i < mask->w; ++i) {
      const int a = mask->alpha[static_cast<std::size_t>(j * mask->w + i)];
      const Rgba p = shot.at(left + i, y + j);
      if (a == 255) ++counts[{p.r, p.g, p.b}];
      if (a == 0) around_max_l = std::max(around_max_l, Luminance(p));
    }
  }
  if (counts.empty()) {
    Expect(false, line.what + ": fully covered glyph pixels");
    return;
  }
  const auto colour =
      std::max_element(counts.begin(), counts.end(), [](const auto& a, const auto& b) {
        return a.second < b.second;
      })->first;
  const Rgba ink{static_cast<std::uint8_t>(colour[0]), static_cast<std::uint8_t>(colour[1]),
                 static_cast<std::uint8_t>(colour[2]), 255};
  const double worst = Contrast(Luminance(ink), plate_max_l);
  const double local = Contrast(Luminance(ink), around_max_l);
  Expect(worst >= kMinContrast, line.what + " text " + Hex(ink) +
                                    " against the plate over the brightest picture pixel "
                                    "under the panel: " +
                                    Num(worst) + ":1");
  Expect(local >= kMinContrast,
         line.what + " text against the brightest text-free pixel around it: " + Num(local) + ":1");
}

// The buttons along the bottom edge (live_kiosk.cpp StaffButtonRects: 7 in a row, 44 px
// high, 12 px apart): their labels against their fill.
void CheckButtons(const ImageRgba& shot, const PixelRect& panel) {
  const int count = 7, bh = 44, gap = 12;
  const int bw = std::min(200, (panel.w - (count + 1) * gap) / count);
  double worst_button = 1e9;
  for (int b = 0; b < count; ++b) {
    const PixelRect r{panel.x + gap + b * (gap + bw), panel.y + panel.h - bh - gap, bw, bh};
    std::map<std::array<int, 3>, int> counts;
    double brightest = 0;
    for (int y = r.y; y < r.y + r.h; ++y) {
      for (int x = r.x; x < r.x + r.w; ++x) {
        const Rgba p = shot.at(x, y);
        ++counts[{p.r, p.g, p.b}];
        brightest = std::max(brightest, Luminance(p));
      }
    }
    const auto fill =
        std::max_element(counts.begin(), counts.end(), [](const auto& a, const auto& c) {
          return a.second < c.second;
        })->first;
    worst_button =
        std::min(worst_button, Contrast(brightest, Luminance(fill[0], fill[1], fill[2])));
    if (b == 0) {
      std::printf("first button's fill #%02x%02x%02x\n", fill[0], fill[1], fill[2]);
    }
  }
  Expect(worst_button >= kMinContrast,
         "button labels against their buttons: " + Num(worst_button) + ":1 at the lowest");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Checks a screenshot of the live kiosk's staff panel: contrast of its text and "
      "buttons, lines in normal case with the configuration path as given.",
      "staff_panel_check"};
  std::string shot_path, picture_path, config_path;
  app.add_option("shot", shot_path, "the screenshot (PNG)")->required();
  app.add_option("picture", picture_path, "the picture shown under the panel")->required();
  app.add_option("config", config_path, "the configuration path given to the kiosk")->required();
  if (const int code = sas::kiosk::ParseProgramCommandLine(app, argc, argv); code >= 0) return code;
  try {
    const ImageRgba shot = sas::ui::LoadPicture(shot_path);
    const int width = shot.width(), height = shot.height();
    const ImageRgba under =
        sas::ui::ResizeToCover(sas::ui::LoadPicture(picture_path), width, height);
    const PixelRect panel = sas::ui::StaffPanelRect(width, height);
    std::printf("shot %dx%d, panel %d,%d %dx%d\n", width, height, panel.x, panel.y, panel.w,
                panel.h);
    const Layer veil = CheckVeil(shot, under, panel);
    const int text_bottom = panel.y + panel.h - 80;  // where StaffPanel stops its lines
    const double plate_max_l = BrightestPlate(shot, under, panel, veil, text_bottom);

    sas::ui::TextRenderer text;
    Expect(text.Available(), "the TTF font is installed (" + text.font_file() + ")");
    if (!text.Available()) return 1;
    // The panel's text size and left edge (app/live_kiosk.cpp StaffPanel).
    const int size_px = std::max(16, height / 45);
    const int left = panel.x + 16;
    const std::vector<Line> lines = {
        {"title",
         std::string("Sketch-a-Scratch ") + sas::kVersion +
             " - staff panel (the staff chord again closes it)",
         true},
        {"configuration line", "Configuration: " + config_path + " (accepted)", false},
    };
    for (const auto& line : lines) {
      CheckLine(shot, text, line, size_px, left, panel, text_bottom, plate_max_l);
    }
    CheckButtons(shot, panel);
  } catch (const std::exception& error) {
    std::printf("FAIL: %s\n", error.what());
    return 1;
  }
  return failed ? 1 : 0;
}
