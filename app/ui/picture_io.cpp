// Picture loading, fitting and PNG snapshots through OpenCV imgcodecs/imgproc (see picture_io.h).
#include "ui/picture_io.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace sas::ui {
namespace {

cv::Mat WrapRgba(const ImageRgba& image) {
  // OpenCV only reads through this header; the const_cast never leads to a write.
  return cv::Mat(image.height(), image.width(), CV_8UC4, const_cast<std::uint8_t*>(image.data()),
                 static_cast<std::size_t>(image.pitch_bytes()));
}

ImageRgba FromMat(const cv::Mat& rgba) {
  ImageRgba out;
  out.Reshape(rgba.cols, rgba.rows);
  for (int y = 0; y < rgba.rows; ++y) {
    const auto* src = rgba.ptr<std::uint8_t>(y);
    std::copy(src, src + rgba.cols * 4, out.row(y));
  }
  return out;
}

}  // namespace

ImageRgba LoadPicture(const std::string& path, const surface::ImageLoadLimits& limits) {
  std::vector<std::uint8_t> bytes;
  try {
    bytes = surface::ReadFileBytes(path, limits.max_file_bytes);
    surface::ParseImageHeader(bytes, path, limits);
  } catch (const surface::LoadError& e) {
    throw PictureError(e.what());
  }
  cv::Mat bgr;
  try {
    bgr = cv::imdecode(bytes, cv::IMREAD_COLOR);
  } catch (const cv::Exception& e) {
    throw PictureError(path + ": cannot decode picture (" + e.what() + ")");
  }
  if (bgr.empty()) throw PictureError(path + ": cannot decode picture");
  cv::Mat rgba;
  cv::cvtColor(bgr, rgba, cv::COLOR_BGR2RGBA);
  return FromMat(rgba);
}

ImageRgba ResizeToCover(const ImageRgba& src, int width, int height) {
  if (src.empty() || width <= 0 || height <= 0) {
    throw PictureError("ResizeToCover: empty picture or screen size");
  }
  if (src.width() == width && src.height() == height) return src;
  const double scale = std::max(static_cast<double>(width) / src.width(),
                                static_cast<double>(height) / src.height());
  const int scaled_w = std::max(width, static_cast<int>(std::ceil(src.width() * scale)));
  const int scaled_h = std::max(height, static_cast<int>(std::ceil(src.height() * scale)));
  cv::Mat scaled;
  // INTER_AREA when shrinking avoids aliasing on fine textures; linear when enlarging.
  cv::resize(WrapRgba(src), scaled, cv::Size(scaled_w, scaled_h), 0, 0,
             scale < 1.0 ? cv::INTER_AREA : cv::INTER_LINEAR);
  const cv::Rect crop((scaled_w - width) / 2, (scaled_h - height) / 2, width, height);
  return FromMat(scaled(crop));
}

ImageRgba FromGrayImage(const surface::GrayImage& gray) {
  ImageRgba out;
  out.Reshape(gray.width, gray.height);
  for (int y = 0; y < gray.height; ++y) {
    for (int x = 0; x < gray.width; ++x) {
      const auto v =
          static_cast<std::uint8_t>(std::lround(std::clamp(gray.at(x, y), 0.0f, 1.0f) * 255.0f));
      out.set(x, y, {v, v, v, 255});
    }
  }
  return out;
}

void SavePng(const ImageRgba& image, const std::string& path) {
  if (image.empty()) throw PictureError(path + ": nothing to save (empty image)");
  cv::Mat bgr;
  cv::cvtColor(WrapRgba(image), bgr, cv::COLOR_RGBA2BGR);
  bool ok = false;
  try {
    ok = cv::imwrite(path, bgr);
  } catch (const cv::Exception& e) {
    throw PictureError(path + ": cannot write PNG (" + e.what() + ")");
  }
  if (!ok) throw PictureError(path + ": cannot write PNG");
}

void SaveJpeg(const ImageRgba& image, const std::string& path, int quality) {
  if (image.empty()) throw PictureError(path + ": nothing to save (empty image)");
  cv::Mat bgr;
  cv::cvtColor(WrapRgba(image), bgr, cv::COLOR_RGBA2BGR);
  bool ok = false;
  try {
    ok = cv::imwrite(path, bgr, {cv::IMWRITE_JPEG_QUALITY, quality});
  } catch (const cv::Exception& e) {
    throw PictureError(path + ": cannot write JPEG (" + e.what() + ")");
  }
  if (!ok) throw PictureError(path + ": cannot write JPEG");
}

}  // namespace sas::ui
