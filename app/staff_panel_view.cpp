// The staff panel's drawing (see staff_panel_view.h).
#include "staff_panel_view.h"

#include <algorithm>
#include <string>

#include "ui/palette.h"
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
                                          const std::vector<kiosk::StaffButtonCaption>& captions,
                                          bool low_vibration, ui::TextRenderer& text, int width,
                                          int height, double now_s) {
  built_s_ = now_s;
  overlays_.clear();
  const ui::PixelRect panel = ui::StaffPanelRect(width, height);
  const bool ttf = text.Available();
  const int size_px = std::max(16, height / 45);
  const int scale = panel.w >= 1100 ? 2 : 1;
  const int line_h = ttf ? text.LineHeight(size_px) : (ui::kGlyphHeight + 4) * scale;
  const StaffButtons buttons = StaffButtonRects(width, height);
  // The captions' row sits on the buttons; the lines end above it.
  const int caption_y = buttons.rects[0].y - line_h - 4;
  const int bottom = caption_y - 8;
  int y = panel.y + 16;
  // A long status (a rejected configuration's file:line: key: what) wraps rather than losing its
  // end, where the reason is; continuation lines are indented, so every row is wrapped to the
  // indented width (none runs past the panel's edge).
  struct Row {
    std::string text;
    bool first;
    ui::Rgba color;
  };
  const auto rows_of = [&](const kiosk::StaffPanelLine& line) {
    std::vector<Row> rows;
    const ui::Rgba color = line.warning ? ui::kAmber : ui::kPanelInk;
    if (!ttf) {
      // The bitmap fallback: capitals, cut at the panel's edge.
      const int max_chars = (panel.w - 32) / (ui::kGlyphAdvance * scale);
      rows.push_back(
          {line.text.substr(0, static_cast<std::size_t>(std::max(0, max_chars))), true, color});
      return rows;
    }
    bool first = true;
    for (auto& row : text.Wrap(line.text, size_px, panel.w - 32 - 24)) {
      rows.push_back({std::move(row), first, color});
      first = false;
    }
    return rows;
  };
  const auto draw = [&](const Row& row) {
    if (!ttf) {
      ui::AddText(overlays_, panel.x + 16, y, scale, row.text, row.color);
    } else if (auto mask = text.Render(row.text, size_px)) {
      overlays_.push_back(
          {{panel.x + 16 + (row.first ? 0 : 24), y, mask->w, mask->h}, row.color, std::move(mask)});
    }
    y += line_h;
  };
  std::vector<Row> journal;
  for (const auto& line : lines) {
    auto rows = rows_of(line);
    if (line.journal) {
      journal.insert(journal.end(), rows.begin(), rows.end());
      continue;
    }
    for (const auto& row : rows) {
      if (y + line_h > bottom) break;
      draw(row);
    }
  }
  // The journal's newest rows that fit, in order (a line cut at its start keeps its end).
  const auto fit = static_cast<std::size_t>(std::max(0, (bottom - y) / line_h));
  for (std::size_t i = journal.size() > fit ? journal.size() - fit : 0; i < journal.size(); ++i) {
    draw(journal[i]);
  }
  AddButtons(captions, low_vibration, text, width, height, size_px, caption_y);
  return overlays_;
}

void StaffPanelView::AddButtons(const std::vector<kiosk::StaffButtonCaption>& captions,
                                bool low_vibration, ui::TextRenderer& text, int width, int height,
                                int size_px, int caption_y) {
  const StaffButtons buttons = StaffButtonRects(width, height);
  for (const auto& caption : captions) {
    // Centred over the buttons it belongs to: what they work on, and its state now.
    const ui::PixelRect& a = buttons[caption.first];
    const ui::PixelRect& b = buttons[caption.last];
    const int centre = (a.x + b.x + b.w) / 2;
    if (text.Available()) {
      if (auto mask = text.Render(caption.text, size_px)) {
        overlays_.push_back(
            {{centre - mask->w / 2, caption_y, mask->w, mask->h}, ui::kPanelInk, std::move(mask)});
      }
    } else {
      ui::AddText(overlays_, centre - ui::TextWidth(caption.text, 1) / 2, caption_y, 1,
                  caption.text, ui::kPanelInk);
    }
  }
  for (int i = 0; i < kiosk::kStaffButtonCount; ++i) {
    const auto button = static_cast<kiosk::StaffButton>(i);
    const char* label = kiosk::StaffButtonLabel(button, low_vibration);
    const ui::PixelRect& rect = buttons[button];
    // The palette's dark blue: the white label keeps 7:1 on it (8.9:1), and the button still
    // stands out from the panel's near-black plate.
    overlays_.push_back({rect, ui::kButton});
    if (text.Available()) {
      if (auto mask = text.Render(label, std::min(size_px, rect.h * 6 / 10), true)) {
        overlays_.push_back(
            {{rect.x + (rect.w - mask->w) / 2, rect.y + (rect.h - mask->h) / 2, mask->w, mask->h},
             ui::kPanelInk,
             std::move(mask)});
      }
      continue;
    }
    // Seven buttons share a 720p panel's width: a label that does not fit goes down a size.
    const int label_scale = ui::TextWidth(label, 2) <= rect.w - 8 ? 2 : 1;
    ui::AddText(overlays_, rect.x + (rect.w - ui::TextWidth(label, label_scale)) / 2,
                rect.y + (rect.h - ui::kGlyphHeight * label_scale) / 2, label_scale, label,
                ui::kPanelInk);
  }
}

}  // namespace sas::app
