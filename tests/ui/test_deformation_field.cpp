// The tip deformation (paper §4): properties of the dent model, checked on the map itself and on
// rendered pixels.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <vector>

#include "ui/deformation_field.h"
#include "ui/image_rgba.h"
#include "ui/texture_view.h"

using sas::platform::PenReading;
using sas::ui::DeformationConfig;
using sas::ui::DeformationField;
using sas::ui::ImageRgba;
using sas::ui::PixelRect;
using sas::ui::Rgba;

namespace {

constexpr int kW = 400;
constexpr int kH = 300;
constexpr double kFrame = 1.0 / 60.0;

PenReading Tip(float x, float y, float pressure, bool down = true) {
  PenReading s;
  s.x_px = x;
  s.y_px = y;
  s.pressure = pressure;
  s.tip_down = down;
  return s;
}

// Holds the tip still at (x, y) for `seconds`, advancing at 60 Hz from `t`; returns the new time.
double Hold(DeformationField& f, float x, float y, float pressure, double t, double seconds) {
  f.SetTip(Tip(x, y, pressure, pressure > 0.0f));
  const int n = static_cast<int>(std::lround(seconds / kFrame));
  for (int i = 0; i < n; ++i) f.Advance(t += kFrame);
  return t;
}

// A textured picture (checker + gradients) on which any displacement or shading shows.
ImageRgba Textured() {
  ImageRgba img(kW, kH);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      const bool dark = ((x / 10) + (y / 10)) % 2 == 0;
      const auto v = static_cast<std::uint8_t>((dark ? 60 : 180) + (x % 10) * 3);
      img.set(x, y,
              {v, static_cast<std::uint8_t>(255 - v), static_cast<std::uint8_t>(y % 256), 255});
    }
  }
  return img;
}

// Picture with the deformation drawn over it (patch only, as the renderer does).
ImageRgba Render(const DeformationField& f, const ImageRgba& picture) {
  ImageRgba out = picture;
  const PixelRect rect = f.AffectedRect(picture.width(), picture.height());
  if (rect.empty()) return out;
  ImageRgba patch;
  f.RenderPatch({&picture, nullptr, 1.0f}, rect, patch);
  sas::ui::Blit(patch, out, rect.x, rect.y);
  return out;
}

double MeanAbsDifference(const ImageRgba& a, const ImageRgba& b) {
  double sum = 0.0;
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      const Rgba p = a.at(x, y), q = b.at(x, y);
      sum += std::abs(p.r - q.r) + std::abs(p.g - q.g) + std::abs(p.b - q.b);
    }
  }
  return sum / (3.0 * a.width() * a.height());
}

}  // namespace

TEST_CASE("zero pressure leaves every pixel of the picture unchanged, even while moving",
          "[render]") {
  const ImageRgba picture = Textured();
  DeformationField f;
  double t = 0.0;
  for (int i = 0; i < 30; ++i) {
    f.SetTip(Tip(100.0f + 5.0f * static_cast<float>(i), 150.0f, 0.0f, true));
    f.Advance(t += kFrame);
  }
  CHECK_FALSE(f.active());
  CHECK(f.AffectedRect(kW, kH).empty());
  CHECK(Render(f, picture) == picture);
  // Hovering with the tip up is no touch either.
  t = Hold(f, 200.0f, 150.0f, 0.0f, t, 0.2);
  CHECK(Render(f, picture) == picture);
}

TEST_CASE(
    "the dent deepens with pressure: steady depth follows max_depth * p^gamma, and "
    "displacement and shading grow with it",
    "[render]") {
  const ImageRgba picture(kW, kH, {128, 128, 128, 255});
  const DeformationConfig cfg;
  double previous_displacement = 0.0, previous_difference = 0.0;
  int previous_darkest = 255;
  for (const float p : {0.15f, 0.4f, 0.7f, 1.0f}) {
    DeformationField f(cfg);
    Hold(f, 200.0f, 150.0f, p, 0.0, 1.0);
    CHECK(f.depth_px() ==
          Approx(cfg.max_depth_px * std::pow(p, cfg.pressure_exponent)).margin(0.05));
    // Largest distance any pixel samples from (the pinch), over the footprint.
    double displacement = 0.0;
    for (int y = 90; y <= 210; ++y) {
      for (int x = 140; x <= 260; ++x) {
        const auto s = f.At(static_cast<float>(x), static_cast<float>(y));
        displacement = std::max(displacement, std::hypot(double{s.src_x} - x, double{s.src_y} - y));
      }
    }
    const ImageRgba shown = Render(f, picture);
    int darkest = 255;
    for (int y = 0; y < kH; ++y) {
      for (int x = 0; x < kW; ++x) darkest = std::min<int>(darkest, shown.at(x, y).r);
    }
    const double difference = MeanAbsDifference(shown, picture);
    INFO("pressure " << p << ": displacement " << displacement << " px, darkest " << darkest
                     << ", mean difference " << difference);
    CHECK(displacement > previous_displacement);
    CHECK(difference > previous_difference);
    CHECK(darkest < previous_darkest);
    previous_displacement = displacement;
    previous_difference = difference;
    previous_darkest = darkest;
  }
  // At full pressure the dent is plainly visible on a flat grey: its floor is well below grey.
  CHECK(previous_darkest < 128 - 40);
}

TEST_CASE("lateral drag shifts content along the motion direction, for every direction",
          "[render]") {
  const DeformationConfig cfg;
  const float dirs[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0.6f, -0.8f}};
  for (const auto& d : dirs) {
    DeformationField f(cfg);
    double t = Hold(f, 200.0f, 150.0f, 1.0f, 0.0, 0.2);
    // Stroke at 300 px/s for 0.2 s.
    float x = 200.0f, y = 150.0f;
    for (int i = 0; i < 12; ++i) {
      x += d[0] * 5.0f;
      y += d[1] * 5.0f;
      f.SetTip(Tip(x, y, 1.0f));
      f.Advance(t += kFrame);
    }
    INFO("direction " << d[0] << "," << d[1]);
    const float q = std::hypot(f.drag_x_px(), f.drag_y_px());
    REQUIRE(q > 3.0f);
    // The stretch points along the motion...
    CHECK((f.drag_x_px() * d[0] + f.drag_y_px() * d[1]) / q == Approx(1.0).margin(1e-3));
    // ...and the material under the tip came from behind it: content moved forward.
    const auto s = f.At(x, y);
    const float moved_x = x - s.src_x, moved_y = y - s.src_y;
    CHECK(moved_x * d[0] + moved_y * d[1] == Approx(q).margin(1e-3));
  }
}

TEST_CASE("a dragged dent moves a vertical line forward near the tip and leaves it far away",
          "[render]") {
  // Red line on green: shading scales both channels, so line pixels stay identifiable.
  ImageRgba picture(kW, kH, {0, 200, 0, 255});
  for (int y = 0; y < kH; ++y) picture.set(200, y, {220, 0, 0, 255});
  DeformationField f;
  double t = Hold(f, 190.0f, 150.0f, 1.0f, 0.0, 0.2);
  for (int i = 1; i <= 10; ++i) {
    f.SetTip(Tip(190.0f + static_cast<float>(i), 150.0f, 1.0f));  // 60 px/s to the right
    f.Advance(t += kFrame);
  }
  REQUIRE(f.drag_x_px() > 1.5f);
  const ImageRgba shown = Render(f, picture);
  auto line_centroid = [&](int row) {
    double sum = 0.0, weight = 0.0;
    for (int x = 0; x < kW; ++x) {
      const Rgba c = shown.at(x, row);
      const double red = std::max(0, c.r - c.g);
      sum += red * x;
      weight += red;
    }
    return sum / weight;
  };
  CHECK(line_centroid(150) > 200.5);               // through the tip: pushed right
  CHECK(line_centroid(10) == Approx(200.0));       // far above: untouched
  CHECK(line_centroid(kH - 10) == Approx(200.0));  // far below: untouched
}

TEST_CASE("the stretch of a steady stroke settles at follow * speed * relaxation time",
          "[render]") {
  DeformationConfig cfg;
  cfg.max_drag_fraction = 10.0f;  // no slip: check the elastic law alone
  DeformationField f(cfg);
  double t = Hold(f, 50.0f, 150.0f, 1.0f, 0.0, 0.3);
  const float speed_px_s = 60.0f;
  float x = 50.0f;
  for (int i = 0; i < 120; ++i) {  // 1 s >> relaxation time
    x += speed_px_s * static_cast<float>(kFrame);
    f.SetTip(Tip(x, 150.0f, 1.0f));
    f.Advance(t += kFrame);
  }
  // Discrete steady state of q <- q e^(-dt/tau) + follow * v dt, independently: v dt / (1 - e^..).
  const double expected =
      cfg.drag_follow * speed_px_s * kFrame / (1.0 - std::exp(-kFrame / cfg.drag_relax_s));
  CHECK(f.drag_x_px() == Approx(expected).epsilon(1e-3));
  // ...which is close to the continuous follow * v * tau.
  CHECK(f.drag_x_px() == Approx(cfg.drag_follow * speed_px_s * cfg.drag_relax_s).epsilon(0.15));
}

TEST_CASE(
    "after the tip lifts the field relaxes back to exactly the picture and stops asking "
    "for frames",
    "[render]") {
  const ImageRgba picture = Textured();
  DeformationField f;
  double t = Hold(f, 150.0f, 150.0f, 1.0f, 0.0, 0.2);
  for (int i = 0; i < 10; ++i) {
    f.SetTip(Tip(150.0f + 6.0f * static_cast<float>(i), 150.0f, 1.0f));
    f.Advance(t += kFrame);
  }
  f.SetTip(Tip(204.0f, 150.0f, 0.0f, false));
  int frames_with_change = 0;
  double rest_after_s = -1.0;
  for (int i = 0; i < 120; ++i) {
    if (f.Advance(t += kFrame)) {
      ++frames_with_change;
    } else if (rest_after_s < 0.0) {
      rest_after_s = (i + 1) * kFrame;
    }
  }
  INFO("frames with change " << frames_with_change << ", at rest after " << rest_after_s << " s");
  CHECK_FALSE(f.active());
  CHECK(rest_after_s > 0.0);
  // Release time constant 0.12 s: 12 px -> 0.05 px takes ln(240) tau = 0.66 s.
  CHECK(rest_after_s < 1.0);
  CHECK_FALSE(f.Advance(t += kFrame));
  CHECK(Render(f, picture) == picture);
}

TEST_CASE("the dent depth after a given time does not depend on the frame rate", "[render]") {
  DeformationField at60, at144;
  at60.SetTip(Tip(100, 100, 0.8f));
  at144.SetTip(Tip(100, 100, 0.8f));
  at60.Advance(0.0);
  at144.Advance(0.0);
  for (int i = 1; i <= 6; ++i) at60.Advance(i / 60.0);     // 0.1 s
  for (int i = 1; i <= 15; ++i) at144.Advance(i / 150.0);  // 0.1 s
  CHECK(at60.depth_px() == Approx(at144.depth_px()).epsilon(1e-5));
  CHECK(at60.depth_px() > 0.0f);
}

TEST_CASE("changed pixels are confined to the dent's radius around the tip", "[render]") {
  const ImageRgba picture = Textured();
  const DeformationConfig cfg;
  DeformationField f(cfg);
  double t = Hold(f, 120.0f, 140.0f, 1.0f, 0.0, 0.2);
  for (int i = 0; i < 8; ++i) {
    f.SetTip(
        Tip(120.0f + 8.0f * static_cast<float>(i), 140.0f + 3.0f * static_cast<float>(i), 1.0f));
    f.Advance(t += kFrame);
  }
  const ImageRgba shown = Render(f, picture);
  int changed = 0;
  double farthest = 0.0;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      if (shown.at(x, y) == picture.at(x, y)) continue;
      ++changed;
      farthest =
          std::max(farthest, std::hypot(x - double{f.centre_x_px()}, y - double{f.centre_y_px()}));
    }
  }
  INFO(changed << " pixels changed, farthest " << farthest << " px from the tip");
  CHECK(changed > 1000);
  CHECK(farthest <= cfg.radius_px);
}

TEST_CASE("at maximum pressure and stretch the map stays one-to-one (no folds or tears)",
          "[render]") {
  DeformationField f;
  double t = Hold(f, 200.0f, 150.0f, 1.0f, 0.0, 0.2);
  for (int i = 0; i < 20; ++i) {  // fast stroke: the stretch saturates at its cap
    f.SetTip(Tip(200.0f + 30.0f * static_cast<float>(i), 150.0f, 1.0f));
    f.Advance(t += kFrame);
  }
  const float cx = f.centre_x_px(), cy = f.centre_y_px();
  REQUIRE(std::hypot(f.drag_x_px(), f.drag_y_px()) ==
          Approx(f.config().max_drag_fraction * f.config().radius_px));
  double min_jacobian = 1e9;
  const float h = 0.25f;
  for (float dy = -60.0f; dy <= 60.0f; dy += 2.0f) {
    for (float dx = -60.0f; dx <= 60.0f; dx += 2.0f) {
      const auto xp = f.At(cx + dx + h, cy + dy), xm = f.At(cx + dx - h, cy + dy);
      const auto yp = f.At(cx + dx, cy + dy + h), ym = f.At(cx + dx, cy + dy - h);
      const double a = (xp.src_x - xm.src_x) / (2 * h), b = (yp.src_x - ym.src_x) / (2 * h);
      const double c = (xp.src_y - xm.src_y) / (2 * h), d = (yp.src_y - ym.src_y) / (2 * h);
      min_jacobian = std::min(min_jacobian, a * d - b * c);
    }
  }
  CHECK(min_jacobian > 0.05);
}
