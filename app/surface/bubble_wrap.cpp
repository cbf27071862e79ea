// Bubble wrap state (see bubble_wrap.h).
#include "surface/bubble_wrap.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace sas::surface {

std::vector<std::pair<double, double>> BubbleLayout::Centres(int width_px, int height_px) const {
  std::vector<std::pair<double, double>> out;
  if (!(pitch_px > 0.0)) return out;
  const double row_step = pitch_px * std::sqrt(3.0) / 2.0;
  for (int row = 0;; ++row) {
    const double y = origin_y_px + row * row_step;
    if (y >= height_px) break;
    if (y < 0.0) continue;
    const double shift = (row % 2 == 1) ? pitch_px / 2.0 : 0.0;
    for (int col = 0;; ++col) {
      const double x = origin_x_px + shift + col * pitch_px;
      if (x >= width_px) break;
      if (x >= 0.0) out.emplace_back(x, y);
    }
  }
  return out;
}

BubbleWrapState::BubbleWrapState(BubbleLayout layout, double pop_force_n, HeightField intact,
                                 double flatten_radius_scale)
    : BubbleWrapState(layout, pop_force_n, std::make_shared<const HeightField>(std::move(intact)),
                      flatten_radius_scale) {}

BubbleWrapState::BubbleWrapState(BubbleLayout layout, double pop_force_n,
                                 std::shared_ptr<const HeightField> intact,
                                 double flatten_radius_scale)
    : layout_(layout), pop_force_n_(pop_force_n), intact_(std::move(intact)) {
  if (!(pop_force_n > 0.0) || !(layout.radius_px > 0.0) || !(flatten_radius_scale >= 1.0) ||
      !intact_ || intact_->empty()) {
    throw std::invalid_argument("BubbleWrapState: bad threshold, radius or field");
  }
  flatten_radius_px_ = layout.radius_px * flatten_radius_scale;
  centres_ = layout_.Centres(intact_->width(), intact_->height());
  popped_.assign(centres_.size(), false);
  current_ = intact_;
}

int BubbleWrapState::BubbleAt(double x_px, double y_px) const {
  for (std::size_t i = 0; i < centres_.size(); ++i) {
    if (std::hypot(x_px - centres_[i].first, y_px - centres_[i].second) <= layout_.radius_px) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

std::optional<PopEvent> BubbleWrapState::Press(double x_px, double y_px, double force_n) {
  const int bubble = BubbleAt(x_px, y_px);
  if (bubble < 0 || popped_[static_cast<std::size_t>(bubble)] || !(force_n >= pop_force_n_)) {
    return std::nullopt;
  }
  popped_[static_cast<std::size_t>(bubble)] = true;
  // Plain variables, not a structured binding: clang 14 (Debian's, used for the fuzz build) cannot
  // capture bindings in the lambda below (C++20 P1091 arrived in clang 16).
  const double cx = centres_[static_cast<std::size_t>(bubble)].first;
  const double cy = centres_[static_cast<std::size_t>(bubble)].second;
  // Flatten: every sample within the flatten radius drops to the lowest level found there (the
  // film between bubbles), the rim included.
  const HeightField& old = *current_;
  std::pmr::vector<float> heights = old.heights_m();
  const int x0 = std::max(0, static_cast<int>(std::floor(cx - flatten_radius_px_)));
  const int x1 = std::min(old.width() - 1, static_cast<int>(std::ceil(cx + flatten_radius_px_)));
  const int y0 = std::max(0, static_cast<int>(std::floor(cy - flatten_radius_px_)));
  const int y1 = std::min(old.height() - 1, static_cast<int>(std::ceil(cy + flatten_radius_px_)));
  const auto inside = [&](int x, int y) {
    return std::hypot(x - cx, y - cy) <= flatten_radius_px_;
  };
  float level = std::numeric_limits<float>::max();
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      if (inside(x, y)) level = std::min(level, old.at(x, y));
    }
  }
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      if (inside(x, y)) {
        heights[static_cast<std::size_t>(y) * static_cast<std::size_t>(old.width()) +
                static_cast<std::size_t>(x)] = level;
      }
    }
  }
  current_ = std::make_shared<const HeightField>(old.width(), old.height(), old.pitch_m(),
                                                 std::move(heights));
  PopEvent event;
  event.bubble = bubble;
  event.x_px = cx;
  event.y_px = cy;
  event.force_n = force_n;
  event.strength = std::min(4.0, force_n / pop_force_n_);
  return event;
}

void BubbleWrapState::Reset() {
  std::fill(popped_.begin(), popped_.end(), false);
  current_ = intact_;
}

int BubbleWrapState::popped_count() const {
  return static_cast<int>(std::count(popped_.begin(), popped_.end(), true));
}

}  // namespace sas::surface
