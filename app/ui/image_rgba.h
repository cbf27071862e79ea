#pragma once
// A plain 8-bit RGBA picture in memory (bytes R, G, B, A per pixel, rows top to bottom, no
// padding) and the few pixel operations the renderer needs. It is the common currency of the ui
// layer: textures are uploaded from it, the deformation patch is computed into it on the CPU, the
// software compositor (snapshots, headless demo, tests) draws into it and window read-backs land in
// it. Byte order matches SDL_PIXELFORMAT_RGBA32 so uploads need no conversion.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace sas::ui {

struct Rgba {
  std::uint8_t r = 0, g = 0, b = 0, a = 255;
  bool operator==(const Rgba&) const = default;
};

// Pixel rectangle, x/y of the top-left corner. Empty when w or h <= 0.
struct PixelRect {
  int x = 0, y = 0, w = 0, h = 0;
  bool empty() const { return w <= 0 || h <= 0; }
  bool Contains(int px, int py) const { return px >= x && py >= y && px < x + w && py < y + h; }
  PixelRect Intersect(const PixelRect& o) const;
  bool operator==(const PixelRect&) const = default;
};

class ImageRgba {
 public:
  ImageRgba() = default;
  ImageRgba(int width, int height, Rgba fill = {});

  int width() const { return width_; }
  int height() const { return height_; }
  bool empty() const { return width_ <= 0 || height_ <= 0; }
  int pitch_bytes() const { return width_ * 4; }
  std::uint8_t* data() { return pixels_.data(); }
  const std::uint8_t* data() const { return pixels_.data(); }
  std::uint8_t* row(int y) { return pixels_.data() + Offset(0, y); }
  const std::uint8_t* row(int y) const { return pixels_.data() + Offset(0, y); }

  Rgba at(int x, int y) const {
    const std::uint8_t* p = pixels_.data() + Offset(x, y);
    return {p[0], p[1], p[2], p[3]};
  }
  void set(int x, int y, Rgba c) {
    std::uint8_t* p = pixels_.data() + Offset(x, y);
    p[0] = c.r;
    p[1] = c.g;
    p[2] = c.b;
    p[3] = c.a;
  }
  PixelRect bounds() const { return {0, 0, width_, height_}; }

  // Resizes (contents undefined afterwards unless `fill` is used) without shrinking capacity,
  // so a per-frame patch buffer stops allocating once it has reached its largest size.
  void Reshape(int width, int height);
  void Fill(Rgba c);

  bool operator==(const ImageRgba&) const = default;

 private:
  std::size_t Offset(int x, int y) const {
    return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
            static_cast<std::size_t>(x)) *
           4U;
  }
  int width_ = 0;
  int height_ = 0;
  std::vector<std::uint8_t> pixels_;
};

// Copies `src` into `dst` with its top-left corner at (x, y), clipped to `dst`.
void Blit(const ImageRgba& src, ImageRgba& dst, int x, int y);

// dst = from * (1 - weight) + to * weight, per channel, rounded; all three the same size.
// This is the cross-fade formula the SDL renderer reproduces with alpha blending.
void CrossFade(const ImageRgba& from, const ImageRgba& to, float weight, ImageRgba& dst);

// Source-over blend of a solid colour (its alpha used as coverage) into `dst` within `rect`.
void FillRectBlend(ImageRgba& dst, PixelRect rect, Rgba color);

}  // namespace sas::ui
