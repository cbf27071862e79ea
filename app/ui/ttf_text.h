#pragma once
// Visitor and staff text rendered with SDL2_ttf in B612 (Debian's fonts-b612), the typeface
// Airbus and ENAC designed for cockpit screens read at a glance under poor conditions: a large
// x-height, open counters and shapes that cannot be confused (l, I and 1; O and 0; rn and m),
// with the Latin accents the five languages need. Each line is rendered once into a TextMask
// (coverage per pixel) and drawn as an overlay shape, so the window and the software compositor
// (headless frames, screenshots) draw the same pixels. Set-up and control thread only.
//
// Without the font (or SDL2_ttf failing to start) Available() is false and the callers keep the
// built-in 5x7 bitmap font (text.h), so a box missing fonts-b612 still says something.

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "ui/overlay.h"

namespace sas::ui {

// The font files looked for, in order: B612, then DejaVu Sans (always on a Debian desktop).
std::string FindFontFile(bool bold);

class TextRenderer {
 public:
  TextRenderer();
  ~TextRenderer();
  TextRenderer(const TextRenderer&) = delete;
  TextRenderer& operator=(const TextRenderer&) = delete;

  bool Available() const { return available_; }
  const std::string& font_file() const { return regular_file_; }
  // One line of `utf8` at `size_px` (the font's em size in pixels); cached, so the same text at
  // the same size is the same mask (and the view sees an unchanged frame). Null when !Available().
  std::shared_ptr<const TextMask> Render(std::string_view utf8, int size_px, bool bold = false);
  // `utf8` broken at spaces into lines no wider than `max_width_px` (a word longer than that
  // stands on its own line).
  std::vector<std::string> Wrap(std::string_view utf8, int size_px, int max_width_px,
                                bool bold = false);
  int Width(std::string_view utf8, int size_px, bool bold = false);
  // The distance between baselines for `size_px`.
  int LineHeight(int size_px, bool bold = false);

 private:
  struct Font;
  Font* FontAt(int size_px, bool bold);

  bool available_ = false;
  bool ttf_started_ = false;
  std::string regular_file_, bold_file_;
  std::map<std::pair<int, bool>, Font*> fonts_;
  std::map<std::tuple<std::string, int, bool>, std::shared_ptr<const TextMask>> cache_;
};

}  // namespace sas::ui
