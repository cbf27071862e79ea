// The tip deformation: lagged dent depth and elastic drag (Advance), backward map with Lambert
// shading (At), rendered over the dent's footprint only (RenderPatch). See deformation_field.h.
#include "ui/deformation_field.h"

#include <algorithm>
#include <cmath>

namespace sas::ui {
namespace {

// Unit vector towards the light: upper left (screen y points down) and well above the screen,
// so a flat skin gets n·L = L.z and is drawn unchanged.
constexpr float kLightX = -0.5f;
constexpr float kLightY = -0.5f;
constexpr float kLightZ = 0.7071068f;

// Bilinear sample with edge clamping; pixel centres at integer coordinates.
void SampleBilinear(const ImageRgba& img, float x, float y, float out[3]) {
  const float cx = std::clamp(x, 0.0f, static_cast<float>(img.width() - 1));
  const float cy = std::clamp(y, 0.0f, static_cast<float>(img.height() - 1));
  const int x0 = static_cast<int>(cx);
  const int y0 = static_cast<int>(cy);
  const int x1 = std::min(x0 + 1, img.width() - 1);
  const int y1 = std::min(y0 + 1, img.height() - 1);
  const float fx = cx - static_cast<float>(x0);
  const float fy = cy - static_cast<float>(y0);
  const std::uint8_t* p00 = img.row(y0) + x0 * 4;
  const std::uint8_t* p10 = img.row(y0) + x1 * 4;
  const std::uint8_t* p01 = img.row(y1) + x0 * 4;
  const std::uint8_t* p11 = img.row(y1) + x1 * 4;
  for (int c = 0; c < 3; ++c) {
    const float top =
        static_cast<float>(p00[c]) + (static_cast<float>(p10[c]) - static_cast<float>(p00[c])) * fx;
    const float bottom =
        static_cast<float>(p01[c]) + (static_cast<float>(p11[c]) - static_cast<float>(p01[c])) * fx;
    out[c] = top + (bottom - top) * fy;
  }
}

void SampleSource(const PictureSource& src, float x, float y, float out[3]) {
  SampleBilinear(*src.picture, x, y, out);
  if (src.fade_from == nullptr) return;
  float from[3];
  SampleBilinear(*src.fade_from, x, y, from);
  const float w = std::clamp(src.weight, 0.0f, 1.0f);
  for (int c = 0; c < 3; ++c) out[c] = from[c] + (out[c] - from[c]) * w;
}

std::uint8_t ToByte(float v) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 255.0f)));
}

// First-order lag towards `target`: exact for a constant target over dt.
float Lag(float value, float target, float dt_s, float tau_s) {
  if (tau_s <= 0.0f) return target;
  return target + (value - target) * std::exp(-dt_s / tau_s);
}

}  // namespace

DeformationField::DeformationField(const DeformationConfig& config) : config_(config) {}

void DeformationField::SetTip(const platform::PenReading& sample) {
  tip_ = sample;
}

void DeformationField::Reset() {
  depth_px_ = 0.0f;
  drag_x_px_ = 0.0f;
  drag_y_px_ = 0.0f;
  was_down_ = false;
  tip_.tip_down = false;
}

bool DeformationField::Advance(double now_s) {
  const float dt = have_time_ ? static_cast<float>(std::max(0.0, now_s - last_s_)) : 0.0f;
  last_s_ = now_s;
  have_time_ = true;
  const float old_depth = depth_px_;
  const float old_qx = drag_x_px_, old_qy = drag_y_px_;
  const float old_cx = centre_x_, old_cy = centre_y_;

  // The dent is drawn in single precision: the screen's pixels need no more.
  const float tip_x = static_cast<float>(tip_.x_px), tip_y = static_cast<float>(tip_.y_px);
  float travel_x = 0.0f, travel_y = 0.0f;
  if (tip_.tip_down) {
    if (was_down_) {
      travel_x = tip_x - centre_x_;
      travel_y = tip_y - centre_y_;
    } else {
      // A new touch: the dent starts under the tip with no stretch (a previous, still relaxing
      // dent elsewhere is dropped: the visitor's attention is at the new point).
      drag_x_px_ = drag_y_px_ = 0.0f;
    }
    centre_x_ = tip_x;
    centre_y_ = tip_y;
  }
  was_down_ = tip_.tip_down;

  const float pressure =
      tip_.tip_down ? std::clamp(static_cast<float>(tip_.pressure), 0.0f, 1.0f) : 0.0f;
  const float target = std::pow(pressure, config_.pressure_exponent) * config_.max_depth_px;
  const float tau = target > depth_px_ ? config_.press_time_s : config_.release_time_s;
  depth_px_ = Lag(depth_px_, target, dt, tau);
  if (std::fabs(depth_px_ - target) < 0.5f * config_.rest_px) depth_px_ = target;
  if (depth_px_ < config_.rest_px && target == 0.0f) depth_px_ = 0.0f;

  // Stretch: elastic relaxation, plus stick in proportion to the normal force (depth).
  const float keep = config_.drag_relax_s > 0.0f ? std::exp(-dt / config_.drag_relax_s) : 0.0f;
  const float stick =
      config_.max_depth_px > 0.0f ? config_.drag_follow * depth_px_ / config_.max_depth_px : 0.0f;
  drag_x_px_ = drag_x_px_ * keep + stick * travel_x;
  drag_y_px_ = drag_y_px_ * keep + stick * travel_y;
  const float q = std::hypot(drag_x_px_, drag_y_px_);
  const float q_max = config_.max_drag_fraction * config_.radius_px;
  if (q > q_max) {
    drag_x_px_ *= q_max / q;
    drag_y_px_ *= q_max / q;
  } else if (q < config_.rest_px) {
    drag_x_px_ = drag_y_px_ = 0.0f;
  }

  const bool shape_changed = depth_px_ != old_depth || drag_x_px_ != old_qx || drag_y_px_ != old_qy;
  const bool moved = (centre_x_ != old_cx || centre_y_ != old_cy) && (active() || old_depth > 0.0f);
  return shape_changed || moved;
}

DeformSample DeformationField::At(float x, float y) const {
  const float r_px = config_.radius_px;
  const float dx = x - centre_x_;
  const float dy = y - centre_y_;
  const float inv_r2 = 1.0f / (r_px * r_px);
  const float u = (dx * dx + dy * dy) * inv_r2;
  if (!active() || u >= 1.0f) return {x, y, 1.0f};

  const float w = 1.0f - u;
  const float g = w * w * w;
  const float gx = -6.0f * w * w * dx * inv_r2;
  const float gy = -6.0f * w * w * dy * inv_r2;
  const float d = depth_px_;
  const float qx = drag_x_px_, qy = drag_y_px_;

  DeformSample s;
  const float pull = config_.pinch * (d / r_px) * g;
  s.src_x = x + pull * dx - qx * g;
  s.src_y = y + pull * dy - qy * g;

  // Relief h = -D g + ridge (q·d)/R g and its gradient, for Lambert shading.
  const float along = (qx * dx + qy * dy) / r_px;
  const float k = config_.ridge;
  const float hx = -d * gx + k * (qx / r_px * g + along * gx);
  const float hy = -d * gy + k * (qy / r_px * g + along * gy);
  const float sx = -config_.relief_gain * hx;
  const float sy = -config_.relief_gain * hy;
  const float n_dot_l =
      (sx * kLightX + sy * kLightY + kLightZ) / std::sqrt(sx * sx + sy * sy + 1.0f);
  const float occlusion = config_.max_depth_px > 0.0f
                              ? 1.0f - config_.occlusion * (d / config_.max_depth_px) * g
                              : 1.0f;
  s.shade = std::max(0.0f, n_dot_l / kLightZ) * occlusion;
  return s;
}

PixelRect DeformationField::AffectedRect(int width, int height) const {
  if (!active()) return {};
  const int r = static_cast<int>(std::ceil(config_.radius_px)) + 1;
  const int cx = static_cast<int>(std::lround(centre_x_));
  const int cy = static_cast<int>(std::lround(centre_y_));
  return PixelRect{cx - r, cy - r, 2 * r + 1, 2 * r + 1}.Intersect({0, 0, width, height});
}

void DeformationField::RenderPatch(const PictureSource& source, PixelRect rect,
                                   ImageRgba& out) const {
  out.Reshape(rect.w, rect.h);
  if (rect.empty() || source.picture == nullptr) return;
  float rgb[3];
  for (int y = 0; y < rect.h; ++y) {
    std::uint8_t* o = out.row(y);
    for (int x = 0; x < rect.w; ++x, o += 4) {
      const float px = static_cast<float>(rect.x + x);
      const float py = static_cast<float>(rect.y + y);
      const DeformSample s = At(px, py);
      SampleSource(source, s.src_x, s.src_y, rgb);
      o[0] = ToByte(rgb[0] * s.shade);
      o[1] = ToByte(rgb[1] * s.shade);
      o[2] = ToByte(rgb[2] * s.shade);
      o[3] = 255;
    }
  }
}

}  // namespace sas::ui
