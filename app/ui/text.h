#pragma once
// Plain text as overlay rectangles, for the staff panel and the visitor's friendly messages: a
// built-in 5x7 pixel font (capitals, digits and common punctuation; lower case is drawn as upper
// case, unknown characters as a blank), each lit pixel run one OverlayShape scaled by `scale`. No
// font files, no SDL_ttf: the same rectangles are drawn by the window and by the software
// compositor, so screenshots and headless snapshots agree.

#include <string_view>

#include "ui/overlay.h"

namespace sas::ui {

inline constexpr int kGlyphWidth = 5;
inline constexpr int kGlyphHeight = 7;
inline constexpr int kGlyphAdvance = 6;  // one column of spacing

// Adds `text` with its top-left corner at (x, y); each font pixel is `scale` x `scale` screen
// pixels. Returns the x just after the last character.
int AddText(Overlays& out, int x, int y, int scale, std::string_view text, Rgba color);

// Width in screen pixels AddText would use.
int TextWidth(std::string_view text, int scale);

}  // namespace sas::ui
