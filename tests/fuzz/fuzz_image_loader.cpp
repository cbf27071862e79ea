// libFuzzer target : arbitrary bytes as a picture (PNG, JPEG or BMP)
// through the same header checks and OpenCV decoding the kiosk uses for textures. DecodeGrayImage
// documents LoadError for every bad file; anything else escaping is a bug. The pixel limit is
// lowered from the kiosk's 4096 x 4096 to 512 x 512 so one input decodes in milliseconds: the
// header checks that enforce the limit are the same code either way.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "surface/image_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<std::uint8_t> bytes(data, data + size);
  sas::surface::ImageLoadLimits limits;
  limits.max_pixels = 512 * 512;
  try {
    const sas::surface::GrayImage image = sas::surface::DecodeGrayImage(bytes, "fuzz", limits);
    // A decoded picture is what image_loader.h promises: consistent size, values in [0, 1].
    if (image.width < limits.min_side_px || image.height < limits.min_side_px) __builtin_trap();
    if (image.luminance.size() !=
        static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height)) {
      __builtin_trap();
    }
    for (const float value : image.luminance) {
      if (!(value >= 0.0f && value <= 1.0f)) __builtin_trap();
    }
  } catch (const sas::surface::LoadError&) {
    // documented rejection of a bad file
  }
  return 0;
}
