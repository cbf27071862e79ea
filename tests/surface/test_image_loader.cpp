// Image loading: real files written with OpenCV, read back through the product's loader.
#include <catch2/catch.hpp>
#include <opencv2/imgcodecs.hpp>

#include "support/temp_dir.h"
#include "surface/image_loader.h"

using sas::surface::LoadError;
using sas::surface::LoadGrayImage;

TEST_CASE("a 16-bit gradient PNG loads as luminance scaled to [0, 1] pixel for pixel",
          "[surface]") {
  sas::test::TempDir dir;
  cv::Mat gradient(9, 16, CV_16UC1);
  for (int y = 0; y < gradient.rows; ++y) {
    for (int x = 0; x < gradient.cols; ++x) {
      gradient.at<uint16_t>(y, x) = static_cast<uint16_t>(x * 4000 + y);
    }
  }
  const std::string path = dir.file("gradient.png");
  REQUIRE(cv::imwrite(path, gradient));
  const auto image = LoadGrayImage(path);
  REQUIRE(image.width == 16);
  REQUIRE(image.height == 9);
  for (int y = 0; y < 9; ++y) {
    for (int x = 0; x < 16; ++x) {
      CHECK(image.at(x, y) == Approx((x * 4000 + y) / 65535.0).margin(1e-6));
    }
  }
}

TEST_CASE("a missing file and a non-image with a .png name give errors naming the file",
          "[surface]") {
  sas::test::TempDir dir;
  CHECK_THROWS_WITH(LoadGrayImage(dir.file("absent.png")), Catch::Contains("absent.png"));
  const auto fake = dir.Write("fake.png", "this is plain text, not a PNG");
  CHECK_THROWS_AS(LoadGrayImage(fake), LoadError);
  CHECK_THROWS_WITH(LoadGrayImage(fake), Catch::Contains("fake.png"));
}
