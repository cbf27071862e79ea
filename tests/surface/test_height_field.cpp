// The summed-area table must give the same box means as summing the pixels directly.
#include <catch2/catch.hpp>
#include <memory_resource>
#include <random>

#include "surface/height_field.h"

TEST_CASE("box means from the summed-area table equal brute-force sums over random boxes",
          "[surface]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> height(-1e-3f, 1e-3f);
  const int width = 37, rows = 11;
  std::pmr::vector<float> heights(static_cast<std::size_t>(width * rows));
  for (auto& h : heights) h = height(rng);
  const sas::surface::HeightField field(width, rows, 1e-4, heights);
  std::uniform_int_distribution<int> px(0, width - 1), py(0, rows - 1);
  for (int trial = 0; trial < 200; ++trial) {
    int x0 = px(rng), x1 = px(rng), y0 = py(rng), y1 = py(rng);
    if (x1 < x0) std::swap(x0, x1);
    if (y1 < y0) std::swap(y0, y1);
    double sum = 0.0;
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) sum += heights[static_cast<std::size_t>(y * width + x)];
    }
    const double expected = sum / ((x1 - x0 + 1) * (y1 - y0 + 1));
    REQUIRE(field.BoxMean(x0, y0, x1, y1) == Approx(expected).margin(1e-12));
  }
  const auto view = field.View();
  CHECK(view.width == width);
  CHECK(view.height == rows);
  CHECK(view.height_m[5] == heights[5]);
}

TEST_CASE(
    "the summed-area table of a field of ones holds x * y exactly, with a zero first row and "
    "column",
    "[surface]") {
  const int width = 1920, rows = 5;  // a picture's width, a few rows: small integers sum exactly
  const sas::surface::HeightField field(width, rows, 1e-4,
                                        std::pmr::vector<float>(std::size_t{width} * rows, 1.0f));
  const double* table = field.View().summed_area;
  for (int y = 0; y <= rows; ++y) {
    for (int x = 0; x <= width; ++x) {
      REQUIRE(table[static_cast<std::size_t>(y) * (width + 1) + static_cast<std::size_t>(x)] ==
              static_cast<double>(x) * y);
    }
  }
}

TEST_CASE("a height field whose size does not match its data is refused", "[surface]") {
  CHECK_THROWS_AS(sas::surface::HeightField(4, 4, 1e-4, std::pmr::vector<float>(15)),
                  std::invalid_argument);
}
