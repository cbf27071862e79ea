// Owned height field with its summed-area table (see height_field.h). OpenCV's cv::integral builds
// the table (float heights, double sums) straight into the field's own memory: it accumulates each
// row in double and adds the row above, the same order a hand-written loop would, so the sums are
// exact to the last bit of that order.
#include "surface/height_field.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <stdexcept>

namespace sas::surface {

HeightField::HeightField(int width, int height, double pitch_m, std::pmr::vector<float> heights_m)
    : width_(width),
      height_(height),
      pitch_m_(pitch_m),
      heights_(std::move(heights_m)),
      summed_area_(heights_.get_allocator().resource()) {
  if (width <= 0 || height <= 0 ||
      heights_.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {
    throw std::invalid_argument("HeightField: size does not match width * height");
  }
  if (!(pitch_m > 0.0)) throw std::invalid_argument("HeightField: pitch must be positive");
  summed_area_.assign(
      (static_cast<std::size_t>(width) + 1) * (static_cast<std::size_t>(height) + 1), 0.0);
  // Headers over our buffers: a destination of the right size and type is written in place, so the
  // table stays in the heights' memory resource (never in OpenCV's allocator).
  const cv::Mat heights(height, width, CV_32F, heights_.data());
  cv::Mat table(height + 1, width + 1, CV_64F, summed_area_.data());
  cv::integral(heights, table, CV_64F);
  if (table.data != reinterpret_cast<const uchar*>(summed_area_.data())) {
    throw std::logic_error("HeightField: cv::integral reallocated the summed-area table");
  }
}

double HeightField::BoxMean(int x0, int y0, int x1, int y1) const {
  if (empty()) return 0.0;
  x0 = std::clamp(x0, 0, width_ - 1);
  x1 = std::clamp(x1, 0, width_ - 1);
  y0 = std::clamp(y0, 0, height_ - 1);
  y1 = std::clamp(y1, 0, height_ - 1);
  if (x1 < x0) std::swap(x0, x1);
  if (y1 < y0) std::swap(y0, y1);
  const auto stride = static_cast<std::size_t>(width_) + 1;
  const auto sat = [&](int x, int y) {
    return summed_area_[static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x)];
  };
  const double sum = sat(x1 + 1, y1 + 1) - sat(x0, y1 + 1) - sat(x1 + 1, y0) + sat(x0, y0);
  return sum / (static_cast<double>(x1 - x0 + 1) * static_cast<double>(y1 - y0 + 1));
}

synth::HeightFieldView HeightField::View() const {
  synth::HeightFieldView view;
  if (empty()) return view;
  view.height_m = heights_.data();
  view.summed_area = summed_area_.data();
  view.width = width_;
  view.height = height_;
  view.pitch_m = pitch_m_;
  return view;
}

double ReliefM(const HeightField& field) {
  if (field.empty()) return 0.0;
  const auto [lo, hi] = std::minmax_element(field.heights_m().begin(), field.heights_m().end());
  return static_cast<double>(*hi) - static_cast<double>(*lo);
}

}  // namespace sas::surface
