#pragma once
// Flat overlay shapes drawn over the texture: the recording countdown bar, the live level meter,
// the discs and rings of the recording sign and the staff panel's frame. A shape is a rectangle
// filled with a colour whose alpha is its coverage, or a coverage mask (text, a disc) tinted by
// it; the window draws them with SDL's blended fill and textures and the software compositor
// with FillRectBlend, so both give the same pixels. Colours come from ui/palette.h.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "ui/image_rgba.h"

namespace sas::ui {

// A line of text rendered once (ui/ttf_text.h): its coverage per pixel, and the text it shows
// (tests read what a screen says from it; a shape's mask, CircleMask, has none).
struct TextMask {
  int w = 0, h = 0;
  std::vector<std::uint8_t> alpha;  // w * h, row by row
  std::string text;
};

// A filled rectangle, or with `mask` the text whose coverage scales `color`'s alpha (the rect is
// the mask's size where it is drawn).
struct OverlayShape {
  PixelRect rect;
  Rgba color;
  std::shared_ptr<const TextMask> mask{};
  bool operator==(const OverlayShape&) const = default;
};

using Overlays = std::vector<OverlayShape>;

// A rectangle outline `thickness_px` wide inside `rect`.
void AddFrame(Overlays& out, PixelRect rect, int thickness_px, Rgba color);

// Countdown: a bar across the top of a width x height screen, filled in proportion to
// `fraction_left` (1 at the start of the countdown, 0 when recording starts).
void AddCountdownBar(Overlays& out, int width, int height, float fraction_left);

// Live microphone level: a segmented vertical meter at the right edge; `level` 0..1 of full
// scale (linear in dB in the caller's choice of range); segments above 0.9 are red (clipping).
void AddLevelMeter(Overlays& out, int width, int height, float level);

// A disc `diameter_px` across (ring_px 0), or a ring `ring_px` wide, as a coverage mask with
// smooth edges (no text): drawn like text, in an OverlayShape's colour.
std::shared_ptr<const TextMask> CircleMask(int diameter_px, int ring_px = 0);

// The staff panel's backdrop: a translucent dark panel with a light frame over the middle of the
// screen (contents come with the staff panel's wiring).
void AddStaffPanelFrame(Overlays& out, int width, int height);
// Where AddStaffPanelFrame puts the panel (for its contents).
PixelRect StaffPanelRect(int width, int height);

void DrawOverlays(const Overlays& overlays, ImageRgba& target);

}  // namespace sas::ui
