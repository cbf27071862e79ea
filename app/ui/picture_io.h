#pragma once
// Pictures in and out of the ui layer: texture pictures loaded for display (colour, with the
// surface layer's hardened header checks), fitted to the screen, grey sound-images shown as
// pictures, and PNG snapshots of composed frames (headless demo, tests). OpenCV stays in the .cpp.
// Set-up / staff-action paths only: errors are PictureErrors naming the file.

#include <stdexcept>
#include <string>

#include "surface/image_loader.h"
#include "ui/image_rgba.h"

namespace sas::ui {

class PictureError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Decodes a PNG/JPEG/BMP file to RGBA (opaque). The header is checked first by the surface
// layer's ParseImageHeader (size limits, truncation), then OpenCV decodes it in colour.
ImageRgba LoadPicture(const std::string& path, const surface::ImageLoadLimits& limits = {});

// Scales `src` uniformly so it covers width x height and crops the overflow evenly (no bars, no
// distortion): the texture always fills the screen.
ImageRgba ResizeToCover(const ImageRgba& src, int width, int height);

// Grey image (luminance 0..1, as the sound -> image transform makes it, 0.5 = silence) to an
// opaque picture, value v shown as grey level round(255 v).
ImageRgba FromGrayImage(const surface::GrayImage& gray);

// Writes `image` as an 8-bit RGB PNG. Throws PictureError naming the file on failure.
void SavePng(const ImageRgba& image, const std::string& path);
// JPEG at `quality` (0-100): screenshots for the documentation, a tenth of the PNG's size.
void SaveJpeg(const ImageRgba& image, const std::string& path, int quality = 85);

}  // namespace sas::ui
