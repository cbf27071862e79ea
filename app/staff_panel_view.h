#pragma once
// The staff panel as drawn over the picture: its text (kiosk/staff_panel.h says what) in lines
// that wrap inside the panel, the journal's newest lines in the room left, and one row of buttons
// along its bottom edge under captions with their state, as overlays for the visit view. Normal
// case, so paths read as they are and can be typed from the journal line they repeat; the size
// follows the screen (16 px at 720p, 24 px at 1080p). Without a TrueType font the bitmap fallback
// draws capitals cut at the panel's edge.

#include <array>
#include <cstddef>
#include <vector>

#include "kiosk/staff_panel.h"
#include "ui/overlay.h"
#include "ui/ttf_text.h"

namespace sas::app {

// Where the buttons are on a width x height screen.
struct StaffButtons {
  std::array<ui::PixelRect, static_cast<std::size_t>(kiosk::kStaffButtonCount)> rects;
  const ui::PixelRect& operator[](kiosk::StaffButton b) const {
    return rects[static_cast<std::size_t>(b)];
  }
  // The button under (x, y), or kCount.
  kiosk::StaffButton At(int x, int y) const;
};
StaffButtons StaffButtonRects(int width, int height);

class StaffPanelView {
 public:
  // The text is rebuilt at most 4 times a second (a frame is drawn only when it changed).
  bool Due(double now_s) const { return overlays_.empty() || now_s - built_s_ >= 0.25; }
  // The panel's overlays for `lines` (of the journal's lines, the newest that fit), the buttons
  // and their `captions` above them; the low-vibration button's label follows `low_vibration`.
  const ui::Overlays& Build(const std::vector<kiosk::StaffPanelLine>& lines,
                            const std::vector<kiosk::StaffButtonCaption>& captions,
                            bool low_vibration, ui::TextRenderer& text, int width, int height,
                            double now_s);
  const ui::Overlays& overlays() const { return overlays_; }

 private:
  void AddButtons(const std::vector<kiosk::StaffButtonCaption>& captions, bool low_vibration,
                  ui::TextRenderer& text, int width, int height, int size_px, int caption_y);

  double built_s_ = -1.0;
  ui::Overlays overlays_;
};

}  // namespace sas::app
