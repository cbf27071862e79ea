#pragma once
// The dent check shared by the end-to-end tools: mean absolute RGB difference between a screen
// (or snapshot) and the plain picture near the tip (within 0.8 R of it) and far from it (beyond
// 3 R), R = the deformation's radius. A dent shows as a clear near difference and none far away.

#include <algorithm>
#include <cmath>

#include "ui/deformation_field.h"
#include "ui/image_rgba.h"

namespace sas::test {

struct DentDifference {
  double near_mean = 0.0;
  double far_mean = 0.0;
};

// Rows from `rows` down are left out (a banner the screen may show across its bottom).
inline DentDifference MeasureDent(const ui::ImageRgba& shot, const ui::ImageRgba& plain, int cx,
                                  int cy, double radius = ui::DeformationConfig{}.radius_px,
                                  int rows = -1) {
  double near_sum = 0, far_sum = 0, near_n = 0, far_n = 0;
  const int last_row = rows < 0 ? shot.height() : std::min(rows, shot.height());
  for (int y = 0; y < last_row; ++y) {
    for (int x = 0; x < shot.width(); ++x) {
      const auto p = shot.at(x, y), q = plain.at(x, y);
      const double d = (std::abs(p.r - q.r) + std::abs(p.g - q.g) + std::abs(p.b - q.b)) / 3.0;
      const double r = std::hypot(x - cx, y - cy);
      if (r < 0.8 * radius) {
        near_sum += d;
        ++near_n;
      } else if (r > 3.0 * radius) {
        far_sum += d;
        ++far_n;
      }
    }
  }
  DentDifference out;
  out.near_mean = near_n > 0 ? near_sum / near_n : 0.0;
  out.far_mean = far_n > 0 ? far_sum / far_n : 0.0;
  return out;
}

}  // namespace sas::test
