// Overlay shapes (see overlay.h). Sizes scale with the screen's shorter side so a 1080p panel and
// a 768p test display look alike.
#include "ui/overlay.h"

#include <algorithm>
#include <cmath>

#include "ui/palette.h"

namespace sas::ui {
namespace {

int Scaled(int width, int height, float fraction) {
  return std::max(
      1, static_cast<int>(std::lround(static_cast<float>(std::min(width, height)) * fraction)));
}

}  // namespace

void AddFrame(Overlays& out, PixelRect r, int t, Rgba color) {
  t = std::clamp(t, 1, std::max(1, std::min(r.w, r.h) / 2));
  out.push_back({{r.x, r.y, r.w, t}, color});
  out.push_back({{r.x, r.y + r.h - t, r.w, t}, color});
  out.push_back({{r.x, r.y + t, t, r.h - 2 * t}, color});
  out.push_back({{r.x + r.w - t, r.y + t, t, r.h - 2 * t}, color});
}

void AddCountdownBar(Overlays& out, int width, int height, float fraction_left) {
  const int bar_h = Scaled(width, height, 0.03f);
  const int margin = Scaled(width, height, 0.02f);
  const PixelRect track{margin, margin, width - 2 * margin, bar_h};
  out.push_back({track, WithAlpha(kPlate, 140)});
  const float f = std::clamp(fraction_left, 0.0f, 1.0f);
  const int filled = static_cast<int>(std::lround(static_cast<float>(track.w) * f));
  if (filled > 0) out.push_back({{track.x, track.y, filled, track.h}, WithAlpha(kInk, 220)});
}

void AddLevelMeter(Overlays& out, int width, int height, float level) {
  constexpr int kSegments = 20;
  const int seg_w = Scaled(width, height, 0.03f);
  const int margin = Scaled(width, height, 0.02f);
  const int total_h = height - 2 * margin;
  const int seg_h = std::max(1, total_h / kSegments);
  const int x = width - margin - seg_w;
  const int lit = static_cast<int>(std::lround(std::clamp(level, 0.0f, 1.0f) * kSegments));
  out.push_back({{x - 2, height - margin - seg_h * kSegments - 2, seg_w + 4, seg_h * kSegments + 4},
                 WithAlpha(kPlate, 140)});
  for (int i = 0; i < lit; ++i) {
    const float pos = static_cast<float>(i + 1) / kSegments;
    const Rgba c = WithAlpha(pos > 0.9f ? kRed : pos > 0.7f ? kAmber : kGreen, 230);
    // One-pixel gap between segments so the meter reads as a meter.
    out.push_back({{x, height - margin - (i + 1) * seg_h + 1, seg_w, seg_h - 1}, c});
  }
}

std::shared_ptr<const TextMask> CircleMask(int diameter_px, int ring_px) {
  auto mask = std::make_shared<TextMask>();
  mask->w = mask->h = std::max(1, diameter_px);
  mask->alpha.resize(static_cast<std::size_t>(mask->w) * static_cast<std::size_t>(mask->h));
  const double outer = mask->w / 2.0;
  const double inner = ring_px > 0 ? outer - ring_px : -1.0;
  for (int y = 0; y < mask->h; ++y) {
    for (int x = 0; x < mask->w; ++x) {
      // Coverage from the distance to the edges, one pixel wide: a smooth edge at any size.
      const double r = std::hypot(x + 0.5 - outer, y + 0.5 - outer);
      const double in_outer = std::clamp(outer - r + 0.5, 0.0, 1.0);
      const double out_inner = inner < 0.0 ? 1.0 : std::clamp(r - inner + 0.5, 0.0, 1.0);
      mask->alpha[static_cast<std::size_t>(y * mask->w + x)] =
          static_cast<std::uint8_t>(std::lround(255.0 * in_outer * out_inner));
    }
  }
  return mask;
}

PixelRect StaffPanelRect(int width, int height) {
  // Most of the screen: the status lines stay readable at 720p without a small font.
  const int w = width * 4 / 5;
  const int h = height * 21 / 25;
  return {(width - w) / 2, (height - h) / 2, w, h};
}

void AddStaffPanelFrame(Overlays& out, int width, int height) {
  const PixelRect panel = StaffPanelRect(width, height);
  out.push_back({panel, kPanel});
  AddFrame(out, panel, Scaled(width, height, 0.006f), kFrameLine);
}

void DrawOverlays(const Overlays& overlays, ImageRgba& target) {
  for (const auto& s : overlays) {
    if (!s.mask) {
      FillRectBlend(target, s.rect, s.color);
      continue;
    }
    // Text: the colour at its alpha times the glyphs' coverage, blended as SDL's blend mode does.
    const auto& m = *s.mask;
    for (int y = 0; y < m.h; ++y) {
      const int ty = s.rect.y + y;
      if (ty < 0 || ty >= target.height()) continue;
      for (int x = 0; x < m.w; ++x) {
        const int tx = s.rect.x + x;
        if (tx < 0 || tx >= target.width()) continue;
        const int a = m.alpha[static_cast<std::size_t>(y * m.w + x)] * s.color.a / 255;
        if (a == 0) continue;
        FillRectBlend(target, {tx, ty, 1, 1},
                      {s.color.r, s.color.g, s.color.b, static_cast<std::uint8_t>(a)});
      }
    }
  }
}

}  // namespace sas::ui
