#pragma once
// Accuracy of picture -> height field against a texture's true height map, shared by
// the accuracy test and the surface benchmark. Computed independently of the code under test:
//   true ridges: the maxima across the slope of the true map (smoothed at 1 px, slope in mm/mm,
//     non-maximum suppression along the slope direction) where the slope exceeds ridge_slope:
//     the edges, rims and crack walls a probe would bump into;
//   recovered ridges: the maxima across the derived field's own gradient direction where the
//     derived height is above zero;
//   recall: share of true ridge pixels with a recovered ridge within tolerance_px (Euclidean);
//   precision: share of recovered ridge pixels with a true ridge within tolerance_px;
//   flat: pixels further than flat_margin_px from any true slope above flat_slope; the share of
//     them whose derived height stays below the probe's penetration threshold;
//   correlation: Pearson's r of the derived height with the true slope, and with the true height.

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>

#include "surface/height_field.h"
#include "surface/image_surface.h"

namespace sas::test {

struct RidgeReport {
  double recall = 0.0;
  double precision = 0.0;
  double flat_below_penetration = 0.0;
  double correlation_slope = 0.0;
  double correlation_height = 0.0;
  long true_ridge_px = 0;
  long recovered_ridge_px = 0;
  long flat_px = 0;
};

struct RidgeCriteria {
  double ridge_slope = 0.25;  // mm per mm
  double flat_slope = 0.05;
  int flat_margin_px = 4;
  double tolerance_px = 2.0;
  int border_px = 4;
};

inline cv::Mat1f ToMat(const surface::HeightField& f, double scale) {
  cv::Mat1f m(f.height(), f.width());
  for (int y = 0; y < f.height(); ++y) {
    for (int x = 0; x < f.width(); ++x) m(y, x) = static_cast<float>(f.at(x, y) * scale);
  }
  return m;
}

// Keeps pixels that are at least as large as both neighbours along `angle` (4 directions).
inline cv::Mat1b NonMaxima(const cv::Mat1f& mag, const cv::Mat1f& angle, const cv::Mat1b& keep) {
  cv::Mat1b out(mag.rows, mag.cols, static_cast<uchar>(0));
  for (int y = 1; y + 1 < mag.rows; ++y) {
    for (int x = 1; x + 1 < mag.cols; ++x) {
      if (!keep(y, x)) continue;
      double a = angle(y, x);
      a = std::fmod(a, CV_PI);
      if (a < 0) a += CV_PI;
      int dx = 1, dy = 0;
      if (a >= CV_PI / 8 && a < 3 * CV_PI / 8) {
        dx = 1;
        dy = 1;
      } else if (a >= 3 * CV_PI / 8 && a < 5 * CV_PI / 8) {
        dx = 0;
        dy = 1;
      } else if (a >= 5 * CV_PI / 8 && a < 7 * CV_PI / 8) {
        dx = -1;
        dy = 1;
      }
      const float m = mag(y, x);
      if (m >= mag(y + dy, x + dx) && m >= mag(y - dy, x - dx)) out(y, x) = 255;
    }
  }
  return out;
}

inline double Pearson(const cv::Mat1f& a, const cv::Mat1f& b, const cv::Mat1b& mask) {
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0, n = 0;
  for (int y = 0; y < a.rows; ++y) {
    for (int x = 0; x < a.cols; ++x) {
      if (!mask(y, x)) continue;
      const double u = a(y, x), v = b(y, x);
      sa += u;
      sb += v;
      saa += u * u;
      sbb += v * v;
      sab += u * v;
      n += 1;
    }
  }
  const double cov = sab / n - (sa / n) * (sb / n);
  const double va = saa / n - (sa / n) * (sa / n), vb = sbb / n - (sb / n) * (sb / n);
  return cov / std::sqrt(std::max(va * vb, 1e-30));
}

inline RidgeReport CompareWithTruth(const surface::ImageSurface& derived,
                                    const surface::HeightField& truth, double penetration_mm,
                                    const RidgeCriteria& c = {}) {
  const int w = truth.width(), h = truth.height();
  const double pitch_mm = truth.pitch_m() * 1e3;
  const cv::Mat1f true_mm = ToMat(truth, 1e3);
  cv::Mat1f smooth;
  cv::GaussianBlur(true_mm, smooth, cv::Size(0, 0), 1.0, 1.0, cv::BORDER_REFLECT);
  cv::Mat1f gx, gy, slope, slope_angle;
  cv::Sobel(smooth, gx, CV_32F, 1, 0, 3, 1.0 / (8.0 * pitch_mm), 0.0, cv::BORDER_REFLECT);
  cv::Sobel(smooth, gy, CV_32F, 0, 1, 3, 1.0 / (8.0 * pitch_mm), 0.0, cv::BORDER_REFLECT);
  cv::magnitude(gx, gy, slope);
  cv::phase(gx, gy, slope_angle);  // radians in [0, 2π)

  cv::Mat1b inner(h, w, static_cast<uchar>(0));
  inner(cv::Rect(c.border_px, c.border_px, w - 2 * c.border_px, h - 2 * c.border_px)) = 255;
  cv::Mat1b steep;
  cv::bitwise_and(cv::Mat(slope > c.ridge_slope), inner, steep);
  const cv::Mat1b true_ridge = NonMaxima(slope, slope_angle, steep);

  const cv::Mat1f derived_mm = ToMat(derived.field, 1e3);
  cv::Mat1f mag(h, w), angle(h, w);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const auto i =
          static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
      mag(y, x) = derived.gradient_magnitude[i];
      angle(y, x) = derived.gradient_direction_rad[i];
    }
  }
  cv::Mat1b raised;
  cv::bitwise_and(cv::Mat(derived_mm > static_cast<float>(penetration_mm)), inner, raised);
  const cv::Mat1b recovered = NonMaxima(mag, angle, raised);

  RidgeReport r;
  cv::Mat1f to_recovered, to_true;
  cv::distanceTransform(255 - recovered, to_recovered, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  cv::distanceTransform(255 - true_ridge, to_true, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  long hit = 0, rec_hit = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (true_ridge(y, x)) {
        ++r.true_ridge_px;
        if (to_recovered(y, x) <= c.tolerance_px) ++hit;
      }
      if (recovered(y, x)) {
        ++r.recovered_ridge_px;
        if (to_true(y, x) <= c.tolerance_px) ++rec_hit;
      }
    }
  }
  r.recall =
      r.true_ridge_px > 0 ? static_cast<double>(hit) / static_cast<double>(r.true_ridge_px) : 0.0;
  r.precision = r.recovered_ridge_px > 0
                    ? static_cast<double>(rec_hit) / static_cast<double>(r.recovered_ridge_px)
                    : 0.0;

  cv::Mat1b sloped(cv::Mat(slope >= c.flat_slope));
  cv::Mat1f to_sloped;
  cv::distanceTransform(255 - sloped, to_sloped, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  long flat_ok = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (!inner(y, x) || to_sloped(y, x) <= static_cast<float>(c.flat_margin_px)) continue;
      ++r.flat_px;
      if (derived_mm(y, x) < penetration_mm) ++flat_ok;
    }
  }
  r.flat_below_penetration =
      r.flat_px > 0 ? static_cast<double>(flat_ok) / static_cast<double>(r.flat_px) : 1.0;
  r.correlation_slope = Pearson(derived_mm, slope, inner);
  r.correlation_height = Pearson(derived_mm, true_mm, inner);
  return r;
}

}  // namespace sas::test
