// Picture -> height field: accuracy on the four generated textures against their true height maps,
// and the detector's basic properties on pictures with known answers.
#include <catch2/catch.hpp>
#include <cmath>

#include "ridge_metrics.h"
#include "surface/image_surface.h"
#include "surface/texture_file.h"

using sas::surface::GrayImage;
using sas::surface::ReliefOptions;
using sas::surface::SurfaceFromImage;

namespace {

GrayImage Uniform(int w, int h, float value) {
  GrayImage image;
  image.width = w;
  image.height = h;
  image.luminance.assign(static_cast<std::size_t>(w * h), value);
  return image;
}

}  // namespace

TEST_CASE("default pixel pitch is the 13.3-inch 1920 x 1080 panel's, about 0.153 mm", "[surface]") {
  // 13.3 in diagonal over sqrt(1920^2 + 1080^2) px.
  const double expected = 13.3 * 25.4 / std::sqrt(1920.0 * 1920.0 + 1080.0 * 1080.0);
  CHECK(sas::surface::DisplayGeometry{}.pixel_pitch_mm() == Approx(expected).epsilon(1e-12));
  CHECK(expected == Approx(0.1534).margin(5e-4));
  const sas::surface::DisplayGeometry big{.diagonal_in = 27.0, .width_px = 2560, .height_px = 1440};
  CHECK(big.pixel_pitch_mm() == Approx(27.0 * 25.4 / std::hypot(2560.0, 1440.0)));
  // The derived field carries the pitch, so 100 px span 15.3 mm.
  const auto field = SurfaceFromImage(Uniform(16, 16, 0.5f)).field;
  CHECK(field.pitch_m() * 1e3 == Approx(expected));
}

TEST_CASE("an evenly coloured picture is a flat surface, not noise stretched to full relief",
          "[surface]") {
  auto image = Uniform(64, 48, 0.4f);
  // Faint grain far below the noise floor.
  for (std::size_t i = 0; i < image.luminance.size(); ++i) {
    image.luminance[i] += 0.002f * static_cast<float>((i * 7919) % 13) / 13.0f;
  }
  const auto field = SurfaceFromImage(image).field;
  for (const float h : field.heights_m()) REQUIRE(h == 0.0f);
}

TEST_CASE("a vertical step in gray level becomes one ridge on the step, flat away from it",
          "[surface]") {
  auto image = Uniform(80, 40, 0.2f);
  for (int y = 0; y < 40; ++y) {
    for (int x = 40; x < 80; ++x) image.luminance[static_cast<std::size_t>(y * 80 + x)] = 0.8f;
  }
  ReliefOptions options;
  options.relief_mm = 0.5;
  const auto field = SurfaceFromImage(image, options).field;
  for (int y = 5; y < 35; ++y) {
    // The highest point of each row lies on the step (between pixels 39 and 40).
    int best = 0;
    for (int x = 0; x < 80; ++x) {
      if (field.at(x, y) > field.at(best, y)) best = x;
    }
    CHECK((best == 39 || best == 40));
    CHECK(field.at(best, y) == Approx(0.5e-3).epsilon(1e-5));
    // Six pixels away from the step (6 sigma of the smoothing) the surface is flat.
    for (int x = 0; x < 80; ++x) {
      if (std::abs(x - 39.5) > 6.0) REQUIRE(field.at(x, y) == 0.0f);
    }
  }
}

TEST_CASE("kLuminance relief reads the picture's luminance as height", "[surface]") {
  auto image = Uniform(10, 10, 0.25f);
  image.luminance[55] = 1.0f;
  ReliefOptions options;
  options.source = sas::surface::ReliefSource::kLuminance;
  options.relief_mm = 2.0;
  const auto field = SurfaceFromImage(image, options).field;
  CHECK(field.at(5, 5) == Approx(2.0e-3));
  CHECK(field.at(0, 0) == Approx(0.5e-3));
}

TEST_CASE("ridges of every kiosk picture lie within 2 px of the true map's ridges, flat stays flat",
          "[surface]") {
  const std::string name =
      GENERATE(as<std::string>{}, "bubble_wrap", "broken_glass", "wooden_board", "cracked_ground");
  const std::string folder = std::string(SAS_TEXTURES_DIR) + "/" + name;
  const auto file = sas::surface::LoadTextureFile(folder + "/texture.toml");
  ReliefOptions options;
  options.relief_mm = file.relief_mm;
  options.keep_gradient = true;
  const auto derived = SurfaceFromImage(sas::surface::LoadGrayImage(file.picture_path), options);
  const auto truth = sas::surface::LoadHeightMapPng(file.height_map_path, file.height_scale_mm,
                                                    options.pixel_pitch_mm);
  const auto report = sas::test::CompareWithTruth(derived, truth, file.probe.penetration_mm);
  INFO(name << ": recall " << report.recall << ", precision " << report.precision << ", flat "
            << report.flat_below_penetration << ", r(slope) " << report.correlation_slope);
  // Enough of both kinds of region to make the figures mean something.
  REQUIRE(report.true_ridge_px > 5000);
  REQUIRE(report.flat_px > 50000);
  CHECK(report.recall >= 0.95);
  CHECK(report.flat_below_penetration >= 0.999);
  // The derived relief follows the true slope (what the gray-level detector measures).
  CHECK(report.correlation_slope > 0.3);
}
