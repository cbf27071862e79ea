// Profile under the probe: width window, roll envelope, penetration threshold (surface_reader.h).
#include "synth/surface_reader.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sas::synth {

void SurfaceReader::Prepare(const HeightFieldView& field) {
  field_ = field;
  max_height_m_ = 0.0;
  height_range_m_ = 0.0;
  roll_.valid = false;
  inv_pitch_ = field_.pitch_m > 0.0 ? 1.0 / field_.pitch_m : 0.0;
  if (field_.empty() || field_.summed_area == nullptr) {
    field_ = HeightFieldView{};
    return;
  }
  const std::size_t n = field_.size();
  float highest = field_.height_m[0], lowest = field_.height_m[0];
  for (std::size_t i = 1; i < n; ++i) {
    highest = std::max(highest, field_.height_m[i]);
    lowest = std::min(lowest, field_.height_m[i]);
  }
  max_height_m_ = static_cast<double>(highest);
  height_range_m_ = static_cast<double>(highest) - static_cast<double>(lowest);
  roll_ = RollTrack{};
  tiles_x_ = (field_.width + kTile - 1) / kTile;
  tiles_y_ = (field_.height + kTile - 1) / kTile;
  tile_max_.assign(static_cast<std::size_t>(tiles_x_) * static_cast<std::size_t>(tiles_y_),
                   -std::numeric_limits<float>::infinity());
  for (int y = 0; y < field_.height; ++y) {
    for (int x = 0; x < field_.width; ++x) {
      float& tile =
          tile_max_[static_cast<std::size_t>(y / kTile) * static_cast<std::size_t>(tiles_x_) +
                    static_cast<std::size_t>(x / kTile)];
      tile = std::max(
          tile,
          field_.height_m[static_cast<std::size_t>(y) * static_cast<std::size_t>(field_.width) +
                          static_cast<std::size_t>(x)]);
    }
  }
}

double SurfaceReader::CeilingOver(double x_lo, double x_hi, double y_lo, double y_hi,
                                  double half_px, CeilingMemo* memo) const {
  // The pixels a window of half-width half_px centred in the range can touch, with BoxMean's
  // clamping of the centre and shifting of the window at the edges, and one pixel to spare.
  const auto pixel_range = [&](double lo_m, double hi_m, int size, int* first, int* last) {
    const double n = static_cast<double>(size);
    const double c_lo = std::clamp(lo_m * inv_pitch_, 0.0, n);
    const double c_hi = std::clamp(hi_m * inv_pitch_, 0.0, n);
    const double from = std::max(0.0, std::min(c_lo - half_px, n - 2.0 * half_px)) - 1.0;
    const double to = std::min(n, std::max(c_hi + half_px, 2.0 * half_px)) + 1.0;
    *first = static_cast<int>(std::clamp(from, 0.0, n - 1.0));
    *last = static_cast<int>(std::clamp(to, 0.0, n - 1.0));
  };
  int x0 = 0, x1 = 0, y0 = 0, y1 = field_.height - 1;
  pixel_range(x_lo, x_hi, field_.width, &x0, &x1);
  if (field_.height > 1) pixel_range(y_lo, y_hi, field_.height, &y0, &y1);
  const int tx0 = x0 / kTile, tx1 = x1 / kTile, ty0 = y0 / kTile, ty1 = y1 / kTile;
  if (memo != nullptr && memo->tx0 == tx0 && memo->tx1 == tx1 && memo->ty0 == ty0 &&
      memo->ty1 == ty1) {
    return static_cast<double>(memo->highest);
  }
  float highest = -std::numeric_limits<float>::infinity();
  for (int ty = ty0; ty <= ty1; ++ty) {
    for (int tx = tx0; tx <= tx1; ++tx) {
      highest = std::max(
          highest, tile_max_[static_cast<std::size_t>(ty) * static_cast<std::size_t>(tiles_x_) +
                             static_cast<std::size_t>(tx)]);
    }
  }
  if (memo != nullptr) *memo = {tx0, tx1, ty0, ty1, highest};
  return static_cast<double>(highest);
}

// Inlined into BoxMean (four calls per sample): as a call it was a tenth of the kiosk scene's time.
[[gnu::always_inline]] inline double SurfaceReader::Integral(double px, double py) const {
  // Bilinear interpolation of the summed-area table is the exact integral of the
  // piecewise-constant field up to (px, py).
  const int w = field_.width, hgt = field_.height;
  const int ix = std::min(static_cast<int>(px), w - 1);
  const int iy = std::min(static_cast<int>(py), hgt - 1);
  const double fx = px - ix, fy = py - iy;
  const auto stride = static_cast<std::size_t>(w) + 1;
  const double* s = field_.summed_area;
  const auto at = [&](int x, int y) {
    return s[static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x)];
  };
  const double s00 = at(ix, iy), s10 = at(ix + 1, iy), s01 = at(ix, iy + 1),
               s11 = at(ix + 1, iy + 1);
  return s00 * (1.0 - fx) * (1.0 - fy) + s10 * fx * (1.0 - fy) + s01 * (1.0 - fx) * fy +
         s11 * fx * fy;
}

double SurfaceReader::BoxMean(double x_m, double y_m, double width_m) const {
  if (field_.empty() || !std::isfinite(x_m) || !std::isfinite(y_m)) return 0.0;
  const double inv_pitch = inv_pitch_;
  const double w = static_cast<double>(field_.width), hgt = static_cast<double>(field_.height);
  // Window at least one pixel wide: a point probe reads the pixel it is on.
  const double half = 0.5 * std::max(width_m * inv_pitch, 1.0);
  double cx = std::clamp(x_m * inv_pitch, 0.0, w);
  double x0 = cx - half, x1 = cx + half;
  // Shift (not shrink) the window at the edges so its width, hence its smoothing, stays the same.
  if (x0 < 0.0) {
    x1 = std::min(x1 - x0, w);
    x0 = 0.0;
  }
  if (x1 > w) {
    x0 = std::max(x0 - (x1 - w), 0.0);
    x1 = w;
  }
  double y0 = 0.0, y1 = hgt;
  if (field_.height > 1) {
    const double cy = std::clamp(y_m * inv_pitch, 0.0, hgt);
    y0 = cy - half;
    y1 = cy + half;
    if (y0 < 0.0) {
      y1 = std::min(y1 - y0, hgt);
      y0 = 0.0;
    }
    if (y1 > hgt) {
      y0 = std::max(y0 - (y1 - hgt), 0.0);
      y1 = hgt;
    }
  }
  const double area = (x1 - x0) * (y1 - y0);
  if (!(area > 0.0)) return 0.0;
  const double sum = Integral(x1, y1) - Integral(x0, y1) - Integral(x1, y0) + Integral(x0, y0);
  return sum / area;
}

// Margin of the roll's bounds for BoxMean's rounding (~1e-13 m).
constexpr double kBoxMeanSlack = 1e-9;  // m

SurfaceReader::RollGeometry SurfaceReader::Roll(double width_m, double ball_radius_m,
                                                double direction_x, double direction_y) const {
  RollGeometry g;
  g.r = std::max(ball_radius_m, 0.5 * width_m);
  g.half_count = static_cast<int>(std::clamp(g.r / field_.pitch_m, 1.0, 64.0));
  g.ds = g.r / g.half_count;
  const double norm = std::hypot(direction_x, direction_y);
  g.dx = norm > 0.0 ? direction_x / norm : 1.0;
  g.dy = norm > 0.0 ? direction_y / norm : 0.0;
  return g;
}

double SurfaceReader::RollCeiling(double x_m, double y_m, double width_m, const RollGeometry& g,
                                  CeilingMemo* memo) const {
  // The ceiling is the highest point under the ball's track (its tiles), not the field's: on a
  // low or flat part of the field the scan stops after a point or two. (At least 0: BoxMean
  // reads 0 where it cannot average.)
  const double half_px = 0.5 * std::max(width_m * inv_pitch_, 1.0);
  const double local =
      std::isfinite(x_m) && std::isfinite(y_m) && std::isfinite(g.r) && std::isfinite(half_px)
          ? CeilingOver(x_m - g.r * std::fabs(g.dx), x_m + g.r * std::fabs(g.dx),
                        y_m - g.r * std::fabs(g.dy), y_m + g.r * std::fabs(g.dy), half_px, memo)
          : max_height_m_;
  return std::max(local, 0.0) + kBoxMeanSlack;
}

double SurfaceReader::Felt(double x_m, double y_m, double width_m, double penetration_m,
                           ProbeStyle style, double ball_radius_m, double direction_x,
                           double direction_y) const {
  if (field_.empty()) return 0.0;
  double h = 0.0;
  const double threshold = max_height_m_ - std::max(penetration_m, 0.0);
  if (style == ProbeStyle::kRoll) {
    // Bottom of a ball of radius r rolling along the stroke: max over |s| <= r of
    // profile(p + s·dir) + sqrt(r² - s²) - r, sampled at the field pitch (at most 129 points).
    // A point can only matter if its highest possible value (ceiling + lift) exceeds both the
    // threshold and the best found so far; the lift falls with |s|, so the points are taken from
    // the centre outwards and the scan stops at the first that cannot matter. Skipping them leaves
    // the maximum, hence the result, bit-identical (kBoxMeanSlack covers BoxMean's rounding, which
    // is ~1e-13 m), while a ball under a light touch reads a few points instead of up to 129.
    const RollGeometry g = Roll(width_m, ball_radius_m, direction_x, direction_y);
    const double ceiling = RollCeiling(x_m, y_m, width_m, g);
    h = -1e300;
    for (int k = 0; k <= g.half_count; ++k) {
      const double s = k * g.ds;
      const double lift = std::sqrt(std::max(g.r * g.r - s * s, 0.0)) - g.r;
      if (ceiling + lift <= std::max(h, threshold)) break;
      h = std::max(h, BoxMean(x_m + s * g.dx, y_m + s * g.dy, width_m) + lift);
      if (k > 0) h = std::max(h, BoxMean(x_m - s * g.dx, y_m - s * g.dy, width_m) + lift);
    }
  } else {
    h = BoxMean(x_m, y_m, width_m);
  }
  return std::max(h - threshold, 0.0);
}

double SurfaceReader::FeltTracked(double x_m, double y_m, double width_m, double penetration_m,
                                  ProbeStyle style, double ball_radius_m, double direction_x,
                                  double direction_y) {
  if (style != ProbeStyle::kRoll || field_.empty() || !std::isfinite(x_m) || !std::isfinite(y_m) ||
      !std::isfinite(width_m) || !std::isfinite(ball_radius_m)) {
    roll_.valid = false;
    return Felt(x_m, y_m, width_m, penetration_m, style, ball_radius_m, direction_x, direction_y);
  }
  // Felt's scan, with one more reason to skip a point: a box mean over a window of width W moves
  // by at most (highest - lowest) · travel / W when the window travels, so a point read at an
  // earlier position (a few um back: far less than a pixel) is bounded by what it read plus the
  // drift since. Only points that cannot reach the maximum are skipped, and the one that gave it
  // last time is read first, so the result is Felt's, bit for bit, from about one box mean a
  // sample instead of three or four.
  const double threshold = max_height_m_ - std::max(penetration_m, 0.0);
  RollTrack& t = roll_;
  if (!t.valid || t.width_m != width_m || t.radius_m != ball_radius_m ||
      t.direction_x != direction_x || t.direction_y != direction_y) {
    t = RollTrack{};
    t.valid = true;
    t.width_m = width_m;
    t.radius_m = ball_radius_m;
    t.direction_x = direction_x;
    t.direction_y = direction_y;
    t.geometry = Roll(width_m, ball_radius_m, direction_x, direction_y);
    for (int k = 0; k <= t.geometry.half_count; ++k) {
      const double s = k * t.geometry.ds;
      t.lift[k] = std::sqrt(std::max(t.geometry.r * t.geometry.r - s * s, 0.0)) - t.geometry.r;
    }
    for (double& v : t.value) v = std::numeric_limits<double>::infinity();
  } else {
    // The window's width in pixels along each axis (BoxMean: at least one, at most the field).
    const double side = std::max(width_m * inv_pitch_, 1.0);
    const double wx = std::min(side, static_cast<double>(field_.width));
    const double wy = std::min(side, static_cast<double>(field_.height));
    const double travel = std::fabs(x_m - t.x_m) * inv_pitch_ / wx +
                          (field_.height > 1 ? std::fabs(y_m - t.y_m) * inv_pitch_ / wy : 0.0);
    // (1 + 1e-9): the bound's own rounding.
    t.drift += height_range_m_ * travel * (1.0 + 1e-9);
    if (!std::isfinite(t.drift)) {
      t.drift = 0.0;
      for (double& v : t.value) v = std::numeric_limits<double>::infinity();
    }
  }
  t.x_m = x_m;
  t.y_m = y_m;
  const RollGeometry& g = t.geometry;
  const double ceiling = RollCeiling(x_m, y_m, width_m, g, &t.ceiling);
  // Point index: 0 the centre, 2k - 1 at +k·ds, 2k at -k·ds.
  const auto read = [&](int k, int index, double s) {
    const double v = index > 0 && index == 2 * k ? BoxMean(x_m - s * g.dx, y_m - s * g.dy, width_m)
                                                 : BoxMean(x_m + s * g.dx, y_m + s * g.dy, width_m);
    t.value[index] = v;
    t.drift_at[index] = t.drift;
    return v;
  };
  double h = -1e300;
  int best = -1;
  const int first = t.best <= 2 * g.half_count ? t.best : -1;
  if (first >= 0) {
    const int k = (first + 1) / 2;
    const double s = k * g.ds;
    h = read(k, first, s) + t.lift[k];
    best = first;
  }
  for (int k = 0; k <= g.half_count; ++k) {
    const double s = k * g.ds;
    const double lift = t.lift[k];
    if (ceiling + lift <= std::max(h, threshold)) break;
    for (int index = k == 0 ? 0 : 2 * k - 1; index <= 2 * k; ++index) {
      if (index == first) continue;
      const double bound = t.value[index] + (t.drift - t.drift_at[index]) + kBoxMeanSlack;
      if (bound + lift <= std::max(h, threshold)) continue;
      const double v = read(k, index, s) + lift;
      if (v > h) {
        h = v;
        best = index;
      }
    }
  }
  t.best = best;
  return std::max(h - threshold, 0.0);
}

double SurfaceReader::FrictionShare(ProbeStyle style, double width_mm) {
  switch (style) {
    case ProbeStyle::kRoll:
      return 0.0;
    case ProbeStyle::kRub:
      return 1.0;
    case ProbeStyle::kScrape:
    default:
      return 0.3 + 0.7 * std::clamp((width_mm - 0.5) / 7.5, 0.0, 1.0);
  }
}

}  // namespace sas::synth
