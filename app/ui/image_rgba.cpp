// Pixel operations on ImageRgba (see image_rgba.h). Straightforward loops: these run on
// sub-rectangles (the deformation patch, overlays) or once per snapshot, never on a hot path big
// enough to need SIMD.
#include "ui/image_rgba.h"

#include <algorithm>
#include <cmath>

namespace sas::ui {

PixelRect PixelRect::Intersect(const PixelRect& o) const {
  const int x0 = std::max(x, o.x);
  const int y0 = std::max(y, o.y);
  const int x1 = std::min(x + w, o.x + o.w);
  const int y1 = std::min(y + h, o.y + o.h);
  if (x1 <= x0 || y1 <= y0) return {};
  return {x0, y0, x1 - x0, y1 - y0};
}

ImageRgba::ImageRgba(int width, int height, Rgba fill) {
  Reshape(width, height);
  Fill(fill);
}

void ImageRgba::Reshape(int width, int height) {
  width_ = std::max(width, 0);
  height_ = std::max(height, 0);
  pixels_.resize(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * 4U);
}

void ImageRgba::Fill(Rgba c) {
  for (std::size_t i = 0; i < pixels_.size(); i += 4) {
    pixels_[i] = c.r;
    pixels_[i + 1] = c.g;
    pixels_[i + 2] = c.b;
    pixels_[i + 3] = c.a;
  }
}

void Blit(const ImageRgba& src, ImageRgba& dst, int x, int y) {
  const PixelRect target = PixelRect{x, y, src.width(), src.height()}.Intersect(dst.bounds());
  for (int row = target.y; row < target.y + target.h; ++row) {
    const std::uint8_t* from = src.row(row - y) + (target.x - x) * 4;
    std::copy(from, from + target.w * 4, dst.row(row) + target.x * 4);
  }
}

void CrossFade(const ImageRgba& from, const ImageRgba& to, float weight, ImageRgba& dst) {
  const float w = std::clamp(weight, 0.0f, 1.0f);
  dst.Reshape(to.width(), to.height());
  const std::size_t n =
      static_cast<std::size_t>(to.pitch_bytes()) * static_cast<std::size_t>(to.height());
  const std::uint8_t* a = from.data();
  const std::uint8_t* b = to.data();
  std::uint8_t* out = dst.data();
  for (std::size_t i = 0; i < n; ++i) {
    const float v =
        static_cast<float>(a[i]) + (static_cast<float>(b[i]) - static_cast<float>(a[i])) * w;
    out[i] = static_cast<std::uint8_t>(std::lround(v));
  }
}

void FillRectBlend(ImageRgba& dst, PixelRect rect, Rgba color) {
  const PixelRect r = rect.Intersect(dst.bounds());
  const float a = static_cast<float>(color.a) / 255.0f;
  const float src[3] = {static_cast<float>(color.r), static_cast<float>(color.g),
                        static_cast<float>(color.b)};
  for (int y = r.y; y < r.y + r.h; ++y) {
    std::uint8_t* p = dst.row(y) + r.x * 4;
    for (int x = 0; x < r.w; ++x, p += 4) {
      for (int c = 0; c < 3; ++c) {
        const float v = static_cast<float>(p[c]) * (1.0f - a) + src[c] * a;
        p[c] = static_cast<std::uint8_t>(std::lround(v));
      }
      p[3] = 255;
    }
  }
}

}  // namespace sas::ui
