#pragma once
// What the screen shows while exploring, as a pure state machine: the current picture (and the
// previous one while they cross-fade after a token switch), the tip deformation, and the
// overlays. It decides when a frame is due — only while something changes: the tip moves or
// presses, the dent relaxes, a fade runs, the overlays change, or the window asked for one — and
// builds that frame as a description (`Frame`) that the SDL window draws on the GPU and
// ComposeFrame draws in software (snapshots, headless demo, tests).
//
// Chain: stylus samples -> DeformationField -> patch around the tip (CPU) -> Frame
//        -> KioskWindow::Present (SDL, vsync paces it to the display's refresh) or ComposeFrame.

#include <cstdint>
#include <memory>

#include "platform/pen/pen_reading.h"
#include "ui/deformation_field.h"
#include "ui/image_rgba.h"
#include "ui/overlay.h"

namespace sas::ui {

struct TextureViewConfig {
  DeformationConfig deformation{};
  double cross_fade_s = 0.45;  // picture cross-fade on a texture switch (sound fades alongside)
};

// One frame: draw `fade_from` (if any) fully, then `picture` with weight `fade_weight` on top
// (out = from·(1-w) + picture·w), then the deformed `patch` at `patch_rect`, then the overlays.
struct Frame {
  int width = 0;
  int height = 0;
  std::shared_ptr<const ImageRgba> picture;
  std::shared_ptr<const ImageRgba> fade_from;  // null when no cross-fade runs
  float fade_weight = 1.0f;
  PixelRect patch_rect{};
  ImageRgba patch;
  Overlays overlays;
  std::uint64_t number = 0;  // counts frames built
};

class TextureView {
 public:
  TextureView(int width, int height, const TextureViewConfig& config = {});

  int width() const { return width_; }
  int height() const { return height_; }

  // Shows `picture` (must be width x height: see ResizeToCover), cross-fading from the current
  // one when `cross_fade` and there is one. Throws std::invalid_argument on a size mismatch.
  void ShowPicture(std::shared_ptr<const ImageRgba> picture, double now_s, bool cross_fade = true);
  void OnStylus(const platform::PenReading& sample);
  void SetOverlays(Overlays overlays);
  void ResetDeformation();  // idle reset: flat skin at once
  void Invalidate();        // the window lost its contents: draw again

  // Moves time to `now_s`; returns NeedsRedraw().
  bool Advance(double now_s);
  bool NeedsRedraw() const { return dirty_; }
  // Builds the frame for the state at the last Advance and clears NeedsRedraw. The returned
  // reference stays valid until the next call (its patch buffer is reused: no per-frame heap
  // growth once the largest patch has been seen).
  const Frame& TakeFrame();

  const DeformationField& deformation() const { return field_; }
  bool fading() const { return frame_.fade_from != nullptr; }

 private:
  int width_;
  int height_;
  TextureViewConfig config_;
  DeformationField field_;
  double now_s_ = 0.0;
  double fade_start_s_ = 0.0;
  bool dirty_ = true;
  Frame frame_;
};

// Draws `frame` into `out` (reshaped to the frame's size) exactly as the window would.
void ComposeFrame(const Frame& frame, ImageRgba& out);

// Monotonic nanoseconds (platform::PenReading::time_ns) to the seconds TextureView::Advance takes.
inline double SecondsFromNs(std::int64_t time_ns) {
  return static_cast<double>(time_ns) * 1e-9;
}

}  // namespace sas::ui
