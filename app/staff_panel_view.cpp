// The staff panel's drawing (see staff_panel_view.h).
#include "staff_panel_view.h"

#include <algorithm>
#include <string>

#include "ui/text.h"

namespace sas::app {

kiosk::StaffButton StaffButtons::At(int x, int y) const {
  for (std::size_t i = 0; i < rects.size(); ++i) {
    if (rects[i].Contains(x, y)) return static_cast<kiosk::StaffButton>(i);
  }
  return kiosk::StaffButton::kCount;
}

StaffButtons StaffButtonRects(int width, int height) {
  const ui::PixelRect panel = ui::StaffPanelRect(width, height);
  constexpr int kCount = kiosk::kStaffButtonCount;
  const int h = 44, gap = 12;
  const int w = std::min(200, (panel.w - (kCount + 1) * gap) / kCount);
  const int y = panel.y + panel.h - h - gap;
  StaffButtons buttons;
  for (int i = 0; i < kCount; ++i) {
    buttons.rects[static_cast<std::size_t>(i)] = {panel.x + gap + i * (gap + w), y, w, h};
  }
  return buttons;
}

const ui::Overlays& StaffPanelView::Build(const std::vector<kiosk::StaffPanelLine>& lines,
                                          bool low_vibration, ui::TextRenderer& text, int width,
                                          int height, double now_s) {
  built_s_ = now_s;
  overlays_.clear();
  const ui::PixelRect panel = ui::StaffPanelRect(width, height);
  const bool ttf = text.Available();
  const int size_px = std::max(16, height / 45);
  const int scale = panel.w >= 1100 ? 2 : 1;
  const int line_h = ttf ? text.LineHeight(size_px) : (ui::kGlyphHeight + 4) * scale;
  const int bottom = panel.y + panel.h - 80;
  int y = panel.y + 16;
  const ui::Rgba white{235, 235, 235, 255};
  const ui::Rgba amber{250, 190, 60, 255};
  for (const auto& line : lines) {
    const ui::Rgba color = line.warning ? amber : white;
    if (!ttf) {
      // The bitmap fallback: capitals, cut at the panel's edge.
      const int max_chars = (panel.w - 32) / (ui::kGlyphAdvance * scale);
      if (y + line_h > bottom) break;
      ui::AddText(overlays_, panel.x + 16, y, scale,
                  line.text.substr(0, static_cast<std::size_t>(std::max(0, max_chars))), color);
      y += line_h;
      continue;
    }
    // A long status (a rejected configuration's file:line: key: what) wraps rather than losing
    // its end, where the reason is; continuation lines are indented, so every row is wrapped to
    // the indented width (none runs past the panel's edge).
    bool first = true;
    for (const auto& row : text.Wrap(line.text, size_px, panel.w - 32 - 24)) {
      if (y + line_h > bottom) break;
      if (auto mask = text.Render(row, size_px)) {
        overlays_.push_back(
            {{panel.x + 16 + (first ? 0 : 24), y, mask->w, mask->h}, color, std::move(mask)});
      }
      first = false;
      y += line_h;
    }
  }
  AddButtons(low_vibration, text, width, height, size_px);
  return overlays_;
}

void StaffPanelView::AddButtons(bool low_vibration, ui::TextRenderer& text, int width, int height,
                                int size_px) {
  const ui::Rgba white{235, 235, 235, 255};
  const StaffButtons buttons = StaffButtonRects(width, height);
  for (int i = 0; i < kiosk::kStaffButtonCount; ++i) {
    const auto button = static_cast<kiosk::StaffButton>(i);
    const char* label = kiosk::StaffButtonLabel(button, low_vibration);
    const ui::PixelRect& rect = buttons[button];
    // A dark blue: the white label keeps 7:1 on it (8.9:1), and the button still stands out from
    // the panel's near-black plate.
    overlays_.push_back({rect, {40, 62, 100, 255}});
    if (text.Available()) {
      if (auto mask = text.Render(label, std::min(size_px, rect.h * 6 / 10), true)) {
        overlays_.push_back(
            {{rect.x + (rect.w - mask->w) / 2, rect.y + (rect.h - mask->h) / 2, mask->w, mask->h},
             white,
             std::move(mask)});
      }
      continue;
    }
    // Seven buttons share a 720p panel's width: a label that does not fit goes down a size.
    const int label_scale = ui::TextWidth(label, 2) <= rect.w - 8 ? 2 : 1;
    ui::AddText(overlays_, rect.x + (rect.w - ui::TextWidth(label, label_scale)) / 2,
                rect.y + (rect.h - ui::kGlyphHeight * label_scale) / 2, label_scale, label, white);
  }
}

}  // namespace sas::app
