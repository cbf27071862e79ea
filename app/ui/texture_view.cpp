// Frame scheduling and composition for the exploring screen (see texture_view.h).
#include "ui/texture_view.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace sas::ui {
namespace {

// Smoothstep: the cross-fade starts and ends without a visible kink in brightness.
float Ease(double t) {
  const float x = static_cast<float>(std::clamp(t, 0.0, 1.0));
  return x * x * (3.0f - 2.0f * x);
}

}  // namespace

TextureView::TextureView(int width, int height, const TextureViewConfig& config)
    : width_(width), height_(height), config_(config), field_(config.deformation) {
  frame_.width = width;
  frame_.height = height;
}

void TextureView::ShowPicture(std::shared_ptr<const ImageRgba> picture, double now_s,
                              bool cross_fade) {
  if (!picture || picture->width() != width_ || picture->height() != height_) {
    throw std::invalid_argument("TextureView::ShowPicture: picture must be " +
                                std::to_string(width_) + "x" + std::to_string(height_));
  }
  if (cross_fade && frame_.picture && config_.cross_fade_s > 0.0) {
    // A switch during a fade starts from what is on screen's dominant picture; good enough for a
    // 0.45 s fade and avoids keeping three pictures.
    frame_.fade_from =
        frame_.fade_weight >= 0.5f || !frame_.fade_from ? frame_.picture : frame_.fade_from;
    frame_.fade_weight = 0.0f;
    fade_start_s_ = now_s;
  } else {
    frame_.fade_from.reset();
    frame_.fade_weight = 1.0f;
  }
  frame_.picture = std::move(picture);
  dirty_ = true;
}

void TextureView::OnStylus(const platform::PenReading& sample) {
  field_.SetTip(sample);
}

void TextureView::SetOverlays(Overlays overlays) {
  if (overlays == frame_.overlays) return;
  frame_.overlays = std::move(overlays);
  dirty_ = true;
}

void TextureView::ResetDeformation() {
  if (field_.active()) dirty_ = true;
  field_.Reset();
}

void TextureView::Invalidate() {
  dirty_ = true;
}

bool TextureView::Advance(double now_s) {
  now_s_ = now_s;
  if (field_.Advance(now_s)) dirty_ = true;
  if (frame_.fade_from) {
    const double t =
        config_.cross_fade_s > 0.0 ? (now_s - fade_start_s_) / config_.cross_fade_s : 1.0;
    frame_.fade_weight = Ease(t);
    if (t >= 1.0) {
      frame_.fade_from.reset();
      frame_.fade_weight = 1.0f;
    }
    dirty_ = true;
  }
  return dirty_;
}

const Frame& TextureView::TakeFrame() {
  frame_.patch_rect = frame_.picture ? field_.AffectedRect(width_, height_) : PixelRect{};
  if (!frame_.patch_rect.empty()) {
    field_.RenderPatch({frame_.picture.get(), frame_.fade_from.get(), frame_.fade_weight},
                       frame_.patch_rect, frame_.patch);
  } else {
    frame_.patch.Reshape(0, 0);
  }
  ++frame_.number;
  dirty_ = false;
  return frame_;
}

void ComposeFrame(const Frame& frame, ImageRgba& out) {
  out.Reshape(frame.width, frame.height);
  if (!frame.picture) {
    out.Fill({0, 0, 0, 255});
  } else if (frame.fade_from) {
    CrossFade(*frame.fade_from, *frame.picture, frame.fade_weight, out);
  } else {
    out = *frame.picture;
  }
  if (!frame.patch_rect.empty()) Blit(frame.patch, out, frame.patch_rect.x, frame.patch_rect.y);
  DrawOverlays(frame.overlays, out);
}

}  // namespace sas::ui
