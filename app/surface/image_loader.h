#pragma once
// Loading pictures for the surface pipeline: any format OpenCV's imgcodecs reads, converted to
// linear luminance in [0, 1]. Loading happens at start-up or on a staff action, never per frame.
// Errors are exceptions (set-up only, never in the audio path) carrying the file name and why.

#include <stdexcept>
#include <string>
#include <vector>

namespace sas::surface {

class LoadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct GrayImage {
  int width = 0;
  int height = 0;
  std::vector<float> luminance;  // row-major, width * height values in [0, 1]

  float at(int x, int y) const {
    return luminance[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                     static_cast<std::size_t>(x)];
  }
};

// Reads `path` as a grayscale picture. Throws LoadError naming the file when it is missing,
// unreadable, or not an image.
GrayImage LoadGrayImage(const std::string& path);

}  // namespace sas::surface
