// Image loading through OpenCV imgcodecs (see image_loader.h).
#include "surface/image_loader.h"

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace sas::surface {

GrayImage LoadGrayImage(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw LoadError("image '" + path + "': no such file");
  }
  cv::Mat decoded;
  try {
    decoded = cv::imread(path, cv::IMREAD_GRAYSCALE | cv::IMREAD_ANYDEPTH);
  } catch (const cv::Exception& e) {
    throw LoadError("image '" + path + "': decoder failed: " + e.what());
  }
  if (decoded.empty()) {
    throw LoadError("image '" + path + "': not a readable image (corrupt or unknown format)");
  }
  // Scale 8- and 16-bit pictures alike to [0, 1].
  const double scale = decoded.depth() == CV_16U ? 1.0 / 65535.0 : 1.0 / 255.0;
  cv::Mat as_float;
  decoded.convertTo(as_float, CV_32F, scale);
  GrayImage image;
  image.width = as_float.cols;
  image.height = as_float.rows;
  image.luminance.resize(static_cast<std::size_t>(image.width) *
                         static_cast<std::size_t>(image.height));
  for (int y = 0; y < image.height; ++y) {
    const float* row = as_float.ptr<float>(y);
    std::copy(row, row + image.width,
              image.luminance.begin() + static_cast<std::ptrdiff_t>(y) * image.width);
  }
  return image;
}

}  // namespace sas::surface
