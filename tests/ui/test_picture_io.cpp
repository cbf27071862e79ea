// Pictures in and out of the ui layer: PNG round trip, cover fitting, grey sound-images.
#include <catch2/catch.hpp>

#include "support/temp_dir.h"
#include "ui/picture_io.h"

using sas::ui::ImageRgba;
using sas::ui::Rgba;

TEST_CASE("a snapshot written as PNG reads back pixel for pixel", "[render]") {
  sas::test::TempDir dir;
  ImageRgba img(37, 23);
  for (int y = 0; y < 23; ++y) {
    for (int x = 0; x < 37; ++x) {
      img.set(x, y,
              {static_cast<std::uint8_t>(x * 7), static_cast<std::uint8_t>(y * 11),
               static_cast<std::uint8_t>((x * y) % 256), 255});
    }
  }
  const std::string path = dir.file("snap.png");
  sas::ui::SavePng(img, path);
  CHECK(sas::ui::LoadPicture(path) == img);
}

TEST_CASE("saving into a missing folder or loading garbage names the file", "[render]") {
  sas::test::TempDir dir;
  CHECK_THROWS_WITH(sas::ui::SavePng(ImageRgba(4, 4), dir.file("no/such/dir/x.png")),
                    Catch::Contains("x.png"));
  const std::string junk = dir.Write("junk.png", "this is not a picture at all, honestly");
  CHECK_THROWS_AS(sas::ui::LoadPicture(junk), sas::ui::PictureError);
}

TEST_CASE("fitting to the screen covers it without distortion and crops evenly", "[render]") {
  // 200x100 picture, left half black, right half white; fit to 100x100: scale 1, crop 50 px from
  // each side, so the boundary lands in the middle.
  ImageRgba img(200, 100, {0, 0, 0, 255});
  for (int y = 0; y < 100; ++y) {
    for (int x = 100; x < 200; ++x) img.set(x, y, {255, 255, 255, 255});
  }
  const ImageRgba fit = sas::ui::ResizeToCover(img, 100, 100);
  REQUIRE(fit.width() == 100);
  REQUIRE(fit.height() == 100);
  CHECK(fit.at(40, 50).r == 0);
  CHECK(fit.at(60, 50).r == 255);
  // Enlarging a 40x30 to 1920x1080 (scale 48): still the right size.
  const ImageRgba big = sas::ui::ResizeToCover(ImageRgba(40, 30, {9, 9, 9, 255}), 1920, 1080);
  CHECK(big.width() == 1920);
  CHECK(big.height() == 1080);
  CHECK(big.at(1000, 500).r == 9);
}

TEST_CASE("a grey sound-image is shown with silence as mid grey", "[render]") {
  sas::surface::GrayImage gray;
  gray.width = 3;
  gray.height = 1;
  gray.luminance = {0.0f, 0.5f, 1.0f};
  const ImageRgba img = sas::ui::FromGrayImage(gray);
  CHECK(img.at(0, 0) == Rgba{0, 0, 0, 255});
  CHECK(img.at(1, 0) == Rgba{128, 128, 128, 255});
  CHECK(img.at(2, 0) == Rgba{255, 255, 255, 255});
}
