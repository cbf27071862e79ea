// Image loading through OpenCV imgcodecs behind a header check of our own (see image_loader.h).
// Header layouts: PNG (ISO/IEC 15948, §5.3 chunk layout, §11.2.2 IHDR), JPEG (ITU-T T.81, B.1.1
// marker segments, B.2.2 frame header), BMP (Microsoft BITMAPFILEHEADER/BITMAPINFOHEADER).
#include "surface/image_loader.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace sas::surface {
namespace {

std::uint32_t Be32(const std::vector<std::uint8_t>& b, std::size_t at) {
  return (std::uint32_t{b[at]} << 24) | (std::uint32_t{b[at + 1]} << 16) |
         (std::uint32_t{b[at + 2]} << 8) | std::uint32_t{b[at + 3]};
}
std::uint32_t Be16(const std::vector<std::uint8_t>& b, std::size_t at) {
  return (std::uint32_t{b[at]} << 8) | std::uint32_t{b[at + 1]};
}
std::uint32_t Le32(const std::vector<std::uint8_t>& b, std::size_t at) {
  return std::uint32_t{b[at]} | (std::uint32_t{b[at + 1]} << 8) | (std::uint32_t{b[at + 2]} << 16) |
         (std::uint32_t{b[at + 3]} << 24);
}
std::uint32_t Le16(const std::vector<std::uint8_t>& b, std::size_t at) {
  return std::uint32_t{b[at]} | (std::uint32_t{b[at + 1]} << 8);
}

[[noreturn]] void Fail(const std::string& name, const std::string& why) {
  throw LoadError("image '" + name + "': " + why);
}

// Walks every chunk: each must fit in the file, and the stream must end with IEND. A PNG cut off
// anywhere fails here instead of decoding into a partly grey picture.
ImageHeader ParsePng(const std::vector<std::uint8_t>& b, const std::string& name) {
  if (b.size() < 8 + 8 + 13 + 4) Fail(name, "truncated PNG (no complete IHDR chunk)");
  if (Be32(b, 8) != 13 || b[12] != 'I' || b[13] != 'H' || b[14] != 'D' || b[15] != 'R') {
    Fail(name, "malformed PNG (first chunk is not a 13-byte IHDR)");
  }
  const std::uint32_t width = Be32(b, 16);
  const std::uint32_t height = Be32(b, 20);
  std::size_t at = 8;
  bool saw_end = false;
  while (at + 12 <= b.size()) {
    const std::uint64_t length = Be32(b, at);
    const bool is_end =
        b[at + 4] == 'I' && b[at + 5] == 'E' && b[at + 6] == 'N' && b[at + 7] == 'D';
    if (length > b.size() - at - 12)
      Fail(name, "truncated PNG (a chunk runs past the end of file)");
    at += 12 + static_cast<std::size_t>(length);
    if (is_end) {
      saw_end = true;
      break;
    }
  }
  if (!saw_end) Fail(name, "truncated PNG (no IEND chunk)");
  if (width > 0x7fffffffU || height > 0x7fffffffU) Fail(name, "PNG size out of range");
  return {ImageFormat::kPng, static_cast<int>(width), static_cast<int>(height)};
}

// Walks marker segments up to the first start-of-scan, taking the size from the SOFn frame header;
// the entropy-coded data must then be followed by an EOI marker.
ImageHeader ParseJpeg(const std::vector<std::uint8_t>& b, const std::string& name) {
  std::size_t at = 2;
  int width = -1, height = -1;
  bool saw_scan = false;
  while (at + 4 <= b.size()) {
    if (b[at] != 0xFF) Fail(name, "malformed JPEG (expected a marker)");
    const std::uint8_t marker = b[at + 1];
    if (marker == 0xFF) {  // fill byte
      ++at;
      continue;
    }
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) {  // stand-alone markers
      at += 2;
      continue;
    }
    if (marker == 0xD9) break;
    const std::size_t length = Be16(b, at + 2);
    if (length < 2 || at + 2 + length > b.size()) Fail(name, "truncated JPEG (segment past end)");
    const bool is_sof =
        marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (is_sof) {
      if (length < 8) Fail(name, "malformed JPEG frame header");
      height = static_cast<int>(Be16(b, at + 5));
      width = static_cast<int>(Be16(b, at + 7));
    }
    if (marker == 0xDA) {
      saw_scan = true;
      break;
    }
    at += 2 + length;
  }
  if (width < 0) Fail(name, "truncated or malformed JPEG (no frame header before the scan)");
  if (!saw_scan) Fail(name, "truncated JPEG (no image data)");
  // Encoders may pad after EOI; look for it near the end only.
  const std::size_t tail_start = b.size() > 4096 ? b.size() - 4096 : at;
  bool saw_eoi = false;
  for (std::size_t i = std::max(tail_start, at); i + 1 < b.size(); ++i) {
    if (b[i] == 0xFF && b[i + 1] == 0xD9) saw_eoi = true;
  }
  if (!saw_eoi) Fail(name, "truncated JPEG (no end-of-image marker)");
  return {ImageFormat::kJpeg, width, height};
}

ImageHeader ParseBmp(const std::vector<std::uint8_t>& b, const std::string& name) {
  if (b.size() < 26) Fail(name, "truncated BMP header");
  const std::uint32_t pixel_offset = Le32(b, 10);
  const std::uint32_t info_size = Le32(b, 14);
  std::int64_t width = 0, height = 0;
  std::uint32_t bits = 0, compression = 0;
  if (info_size == 12) {
    width = Le16(b, 18);
    height = Le16(b, 20);
    bits = Le16(b, 24);
  } else if (info_size >= 40 && b.size() >= 34) {
    width = static_cast<std::int32_t>(Le32(b, 18));
    height = static_cast<std::int32_t>(Le32(b, 22));
    bits = Le16(b, 28);
    compression = Le32(b, 30);
  } else {
    Fail(name, "malformed or truncated BMP info header");
  }
  height = height < 0 ? -height : height;
  if (width <= 0 || width > 0x7fffffff || height > 0x7fffffff) Fail(name, "BMP size out of range");
  if (bits != 1 && bits != 4 && bits != 8 && bits != 16 && bits != 24 && bits != 32) {
    Fail(name, "unsupported BMP bit depth");
  }
  if (compression == 0) {  // uncompressed: the pixel array's size is known exactly
    const std::uint64_t stride = ((static_cast<std::uint64_t>(width) * bits + 31) / 32) * 4;
    if (pixel_offset > b.size() ||
        stride * static_cast<std::uint64_t>(height) > b.size() - pixel_offset) {
      Fail(name, "truncated BMP (pixel data shorter than the header says)");
    }
  }
  return {ImageFormat::kBmp, static_cast<int>(width), static_cast<int>(height)};
}

}  // namespace

ImageHeader ParseImageHeader(const std::vector<std::uint8_t>& bytes, const std::string& name,
                             const ImageLoadLimits& limits) {
  if (bytes.empty()) Fail(name, "empty file (zero bytes)");
  static constexpr std::uint8_t kPngMagic[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  ImageHeader header;
  if (bytes.size() >= 8 && std::equal(kPngMagic, kPngMagic + 8, bytes.begin())) {
    header = ParsePng(bytes, name);
  } else if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) {
    header = ParseJpeg(bytes, name);
  } else if (bytes.size() >= 2 && bytes[0] == 'B' && bytes[1] == 'M') {
    header = ParseBmp(bytes, name);
  } else {
    Fail(name, "not a PNG, JPEG or BMP image (unrecognised file signature)");
  }
  if (header.width < limits.min_side_px || header.height < limits.min_side_px) {
    Fail(name, "image is " + std::to_string(header.width) + " x " + std::to_string(header.height) +
                   " px, smaller than the minimum side of " + std::to_string(limits.min_side_px) +
                   " px");
  }
  const std::int64_t pixels = std::int64_t{header.width} * std::int64_t{header.height};
  if (pixels > limits.max_pixels) {
    Fail(name, "image is " + std::to_string(header.width) + " x " + std::to_string(header.height) +
                   " px, over the limit of " + std::to_string(limits.max_pixels) +
                   " pixels (refused before decoding)");
  }
  return header;
}

std::vector<std::uint8_t> ReadFileBytes(const std::string& path, std::uintmax_t max_bytes) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw LoadError("'" + path + "': no such file");
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw LoadError("'" + path + "': cannot read its size: " + ec.message());
  if (size > max_bytes) {
    throw LoadError("'" + path + "': file is " + std::to_string(size) +
                    " bytes, over the limit of " + std::to_string(max_bytes));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw LoadError("'" + path + "': cannot be opened for reading");
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size));
  if (static_cast<std::uintmax_t>(in.gcount()) != size) {
    throw LoadError("'" + path + "': read failed");
  }
  return bytes;
}

GrayImage DecodeGrayImage(const std::vector<std::uint8_t>& bytes, const std::string& name,
                          const ImageLoadLimits& limits) {
  const ImageHeader header = ParseImageHeader(bytes, name, limits);
  cv::Mat decoded;
  try {
    const cv::Mat buffer(1, static_cast<int>(bytes.size()), CV_8UC1,
                         const_cast<std::uint8_t*>(bytes.data()));
    decoded = cv::imdecode(buffer, cv::IMREAD_GRAYSCALE | cv::IMREAD_ANYDEPTH);
  } catch (const cv::Exception& e) {
    Fail(name, std::string("decoder failed: ") + e.what());
  }
  if (decoded.empty()) Fail(name, "not a readable image (corrupt data)");
  if (decoded.cols != header.width || decoded.rows != header.height) {
    Fail(name, "decoded size differs from the header's (corrupt file)");
  }
  // Scale 8- and 16-bit pictures alike to [0, 1].
  const double scale = decoded.depth() == CV_16U ? 1.0 / 65535.0 : 1.0 / 255.0;
  GrayImage image;
  image.width = decoded.cols;
  image.height = decoded.rows;
  image.luminance.resize(static_cast<std::size_t>(image.width) *
                         static_cast<std::size_t>(image.height));
  // Convert straight into the result's buffer: no intermediate full-size copy.
  cv::Mat target(image.height, image.width, CV_32F, image.luminance.data());
  decoded.convertTo(target, CV_32F, scale);
  return image;
}

GrayImage LoadGrayImage(const std::string& path, const ImageLoadLimits& limits) {
  std::vector<std::uint8_t> bytes;
  try {
    bytes = ReadFileBytes(path, limits.max_file_bytes);
  } catch (const LoadError& e) {
    throw LoadError(std::string("image ") + e.what());
  }
  return DecodeGrayImage(bytes, path, limits);
}

}  // namespace sas::surface
