// Picture -> height field (see image_surface.h). OpenCV does the smoothing and the Sobel
// derivatives; the mapping to height is ours.
#include "surface/image_surface.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace sas::surface {

double DisplayGeometry::pixel_pitch_mm() const {
  const double diagonal_px =
      std::hypot(static_cast<double>(width_px), static_cast<double>(height_px));
  return diagonal_in * 25.4 / diagonal_px;
}

ImageSurface SurfaceFromImage(const GrayImage& image, const ReliefOptions& options,
                              std::pmr::memory_resource* memory) {
  if (image.width <= 0 || image.height <= 0 ||
      image.luminance.size() !=
          static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height)) {
    throw std::invalid_argument("SurfaceFromImage: empty or inconsistent image");
  }
  if (!(options.relief_mm >= 0.0) || !(options.pixel_pitch_mm > 0.0) ||
      !(options.smoothing_sigma_px >= 0.0) || !(options.noise_floor_per_px >= 0.0) ||
      !(options.saturation_percentile > 0.0 && options.saturation_percentile <= 1.0)) {
    throw std::invalid_argument("SurfaceFromImage: relief options out of range");
  }
  const std::size_t count = image.luminance.size();
  const double relief_m = options.relief_mm * 1e-3;
  // The field is constructed in the returned value, never assigned into it: an assignment would
  // copy its buffers into the default memory resource (height_field.h).
  std::pmr::vector<float> heights(count, memory);
  if (options.source == ReliefSource::kLuminance) {
    for (std::size_t i = 0; i < count; ++i) {
      heights[i] = static_cast<float>(relief_m * std::clamp(image.luminance[i], 0.0f, 1.0f));
    }
    return ImageSurface{
        HeightField(image.width, image.height, options.pixel_pitch_mm * 1e-3, std::move(heights)),
        {},
        {}};
  }
  std::vector<float> gradient_magnitude, gradient_direction_rad;

  const cv::Mat lum(image.height, image.width, CV_32F, const_cast<float*>(image.luminance.data()));
  cv::Mat smooth;
  if (options.smoothing_sigma_px > 0.0) {
    cv::GaussianBlur(lum, smooth, cv::Size(0, 0), options.smoothing_sigma_px,
                     options.smoothing_sigma_px, cv::BORDER_REFLECT);
  } else {
    smooth = lum;
  }
  // Sobel 3x3 sums 8 times the central difference per pixel: scale to luminance per pixel.
  cv::Mat gx, gy;
  cv::Sobel(smooth, gx, CV_32F, 1, 0, 3, 1.0 / 8.0, 0.0, cv::BORDER_REFLECT);
  cv::Sobel(smooth, gy, CV_32F, 0, 1, 3, 1.0 / 8.0, 0.0, cv::BORDER_REFLECT);
  // The magnitude is computed straight into the height buffer, then mapped in place.
  cv::Mat magnitude(image.height, image.width, CV_32F, heights.data());
  if (options.keep_gradient) {
    gradient_direction_rad.resize(count);
    cv::Mat direction(image.height, image.width, CV_32F, gradient_direction_rad.data());
    // One vectorised pass; the direction is good to ~0.3°, plenty for overlays and tests.
    cv::cartToPolar(gx, gy, magnitude, direction, false);
    gradient_magnitude.assign(heights.begin(), heights.end());
  } else {
    cv::magnitude(gx, gy, magnitude);
  }

  // |grad| at the saturation quantile, from a histogram (no sorted copy of the picture).
  double max_gradient = 0.0;
  cv::minMaxLoc(magnitude, nullptr, &max_gradient);
  constexpr int kBins = 4096;
  std::vector<std::size_t> histogram(kBins, 0);
  const double bin_scale = max_gradient > 0.0 ? (kBins - 1) / max_gradient : 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    ++histogram[static_cast<std::size_t>(heights[i] * bin_scale)];
  }
  const auto wanted =
      static_cast<std::size_t>(options.saturation_percentile * static_cast<double>(count));
  std::size_t seen = 0;
  int bin = 0;
  for (; bin < kBins - 1; ++bin) {
    seen += histogram[static_cast<std::size_t>(bin)];
    if (seen >= wanted) break;
  }
  const double quantile = bin_scale > 0.0 ? std::min(max_gradient, (bin + 1) / bin_scale) : 0.0;
  const double floor = options.noise_floor_per_px;
  // A picture with no change above the floor is a flat surface, not noise stretched to full relief.
  const double saturation = std::max(quantile, 2.0 * floor + 1e-6);
  const double gain = 1.0 / (saturation - floor);
  for (std::size_t i = 0; i < count; ++i) {
    const double t = (static_cast<double>(heights[i]) - floor) * gain;
    heights[i] = static_cast<float>(relief_m * std::clamp(t, 0.0, 1.0));
  }
  return ImageSurface{
      HeightField(image.width, image.height, options.pixel_pitch_mm * 1e-3, std::move(heights)),
      std::move(gradient_magnitude), std::move(gradient_direction_rad)};
}

HeightField HeightFieldFromImageFile(const std::string& path, const ReliefOptions& options,
                                     const ImageLoadLimits& limits) {
  return SurfaceFromImage(LoadGrayImage(path, limits), options).field;
}

HeightField LoadHeightMapPng(const std::string& path, double full_scale_mm, double pixel_pitch_mm,
                             const ImageLoadLimits& limits) {
  if (!(full_scale_mm > 0.0) || !(pixel_pitch_mm > 0.0)) {
    throw std::invalid_argument("LoadHeightMapPng: scale and pitch must be positive");
  }
  GrayImage image = LoadGrayImage(path, limits);
  std::pmr::vector<float> heights(image.luminance.size());
  const double scale_m = full_scale_mm * 1e-3;
  for (std::size_t i = 0; i < heights.size(); ++i) {
    heights[i] = static_cast<float>(image.luminance[i] * scale_m);
  }
  return HeightField(image.width, image.height, pixel_pitch_mm * 1e-3, std::move(heights));
}

HeightField RowProfile(const HeightField& field, int row) {
  if (field.empty() || row < 0 || row >= field.height()) {
    throw std::out_of_range("RowProfile: row outside the field");
  }
  const auto begin = field.heights_m().begin() + static_cast<std::ptrdiff_t>(row) * field.width();
  return HeightField(field.width(), 1, field.pitch_m(),
                     std::pmr::vector<float>(begin, begin + field.width()));
}

}  // namespace sas::surface
