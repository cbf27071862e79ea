#pragma once
// Loading pictures for the surface pipeline: PNG, JPEG and BMP files decoded by OpenCV's
// imgcodecs, converted to linear luminance in [0, 1]. Loading happens at start-up or on a staff
// action, never per frame. Errors are exceptions (set-up only, never in the audio path) carrying
// the file name and why.
//
// Hardening: the file's own header (PNG IHDR, JPEG SOFn, BMP info header) is parsed here before any
// decoder runs, so a 40000 x 40000 "bomb" is refused by the pixel limit without allocating it, a
// file whose signature is not one of the three formats never reaches a decoder, a PNG without its
// IEND chunk or a JPEG without its EOI marker is reported as truncated (libpng/libjpeg would
// otherwise hand back a half-grey picture), and the decoded size must equal the header's.

#include <cstddef>
#include <cstdint>
#include <memory_resource>
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
  // Row-major, width * height values in [0, 1]. Allocator-aware (std::pmr) so that a sound image
  // of the visitor's voice can be made in memory kept out of core dumps (sound_image.h).
  std::pmr::vector<float> luminance;

  float at(int x, int y) const {
    return luminance[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                     static_cast<std::size_t>(x)];
  }
};

struct ImageLoadLimits {
  std::int64_t max_pixels = 4096LL * 4096LL;     // refused from the header if larger
  int min_side_px = 8;                           // 1 x 1 and slivers carry no surface
  std::uintmax_t max_file_bytes = 256ULL << 20;  // refuse before reading into memory
};

enum class ImageFormat : std::uint8_t { kPng, kJpeg, kBmp };

// What the header says, read without decoding any pixel data.
struct ImageHeader {
  ImageFormat format = ImageFormat::kPng;
  int width = 0;
  int height = 0;
};

// Parses the header of an in-memory file. Throws LoadError (prefixed with `name`) when the bytes
// are not PNG/JPEG/BMP, the header is malformed or truncated, or the size is outside `limits`.
ImageHeader ParseImageHeader(const std::vector<std::uint8_t>& bytes, const std::string& name,
                             const ImageLoadLimits& limits = {});

// Reads `path` as a grayscale picture. Throws LoadError naming the file when it is missing,
// unreadable, truncated, not an image, or outside `limits`.
GrayImage LoadGrayImage(const std::string& path, const ImageLoadLimits& limits = {});

// Same, from bytes already in memory (`name` is used in error messages).
GrayImage DecodeGrayImage(const std::vector<std::uint8_t>& bytes, const std::string& name,
                          const ImageLoadLimits& limits = {});

// Reads a whole file with a size cap; throws LoadError naming the file.
std::vector<std::uint8_t> ReadFileBytes(const std::string& path, std::uintmax_t max_bytes);

}  // namespace sas::surface
