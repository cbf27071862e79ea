// Built-in profiles are deterministic, have the relief and structure they document, and a picture
// becomes a height field with white high and black low.
#include <catch2/catch.hpp>

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>

#include "sas/version.h"
#include "support/temp_dir.h"
#include "surface/image_surface.h"
#include "tools/builtin_profiles.h"

using sas::kiosk::BuiltinProfileNames;
using sas::kiosk::LoadProfile;
using sas::kiosk::MakeBuiltinProfile;
using sas::kiosk::ProfileError;
using sas::surface::ReliefM;

TEST_CASE("built-in profiles are identical every time they are made and never negative",
          "[kiosk]") {
  for (const auto& name : BuiltinProfileNames()) {
    INFO(name);
    const auto a = MakeBuiltinProfile(name);
    const auto b = MakeBuiltinProfile(name);
    REQUIRE(a);
    REQUIRE(b);
    CHECK(a->width() == sas::kiosk::kBuiltinProfileWidth);
    CHECK(a->height() == sas::kiosk::kBuiltinProfileHeight);
    CHECK(a->pitch_m() == sas::kiosk::kProfilePitchM);
    CHECK(a->heights_m() == b->heights_m());
    CHECK(*std::min_element(a->heights_m().begin(), a->heights_m().end()) >= 0.0f);
  }
  CHECK_FALSE(MakeBuiltinProfile("velvet"));
}

TEST_CASE("built-in profiles have the relief they document", "[kiosk]") {
  CHECK(ReliefM(*MakeBuiltinProfile("grating")) == Approx(0.1e-3).epsilon(0.01));
  CHECK(ReliefM(*MakeBuiltinProfile("rough")) == Approx(0.1e-3).epsilon(1e-6));
  CHECK(ReliefM(*MakeBuiltinProfile("bumps")) == Approx(0.15e-3).epsilon(0.05));
  CHECK(ReliefM(*MakeBuiltinProfile("cracks")) == Approx(0.2e-3).epsilon(0.01));
  CHECK(ReliefM(*MakeBuiltinProfile("flat")) == 0.0);
}

TEST_CASE("the grating has one ridge every 2 mm along x and none along y", "[kiosk]") {
  const auto field = *MakeBuiltinProfile("grating");
  int ridges = 0;
  for (int x = 1; x < field.width(); ++x) {
    if (field.at(x - 1, 10) < 0.05e-3f && field.at(x, 10) >= 0.05e-3f) ++ridges;
  }
  const double length_mm = field.width() * field.pitch_m() * 1e3;
  CHECK(std::abs(ridges - length_mm / 2.0) <= 1.0);
  for (int y = 1; y < field.height(); ++y) CHECK(field.at(7, y) == field.at(7, 0));
}

TEST_CASE("the rough profile varies everywhere while the cracks profile is mostly flat plates",
          "[kiosk]") {
  const auto rough = *MakeBuiltinProfile("rough");
  const auto cracks = *MakeBuiltinProfile("cracks");
  int rough_flat = 0;
  int plate = 0;
  const auto count = static_cast<int>(rough.heights_m().size());
  for (int i = 1; i < count; ++i) {
    const auto index = static_cast<std::size_t>(i);
    if (rough.heights_m()[index] == rough.heights_m()[index - 1]) ++rough_flat;
    if (cracks.heights_m()[index] >= 0.199e-3f) ++plate;
  }
  CHECK(rough_flat < count / 100);
  CHECK(plate > count / 2);
  CHECK(plate < count);  // and there are cracks
}

TEST_CASE("a picture's gray-level edge becomes a ridge and its even halves stay flat", "[kiosk]") {
  sas::test::TempDir dir;
  cv::Mat image(40, 60, CV_8UC1, cv::Scalar(0));
  image(cv::Rect(30, 0, 30, 40)).setTo(cv::Scalar(255));
  const std::string path = dir.file("half.png");
  REQUIRE(cv::imwrite(path, image));
  const auto field = LoadProfile(path);
  REQUIRE(field.width() == 60);
  REQUIRE(field.height() == 40);
  CHECK(field.pitch_m() == Approx(sas::surface::DisplayGeometry{}.pixel_pitch_mm() * 1e-3));
  // Paper §2: even regions are flat, the change of gray level is the ridge.
  CHECK(field.at(8, 20) == 0.0f);
  CHECK(field.at(52, 20) == 0.0f);
  const double relief_m = sas::surface::ReliefOptions{}.relief_mm * 1e-3;
  CHECK(std::max(field.at(29, 20), field.at(30, 20)) == Approx(relief_m).epsilon(0.05));
  CHECK(sas::kiosk::ProfileMaterial(path).empty());
}

TEST_CASE("a kiosk texture file gives its true height map and names its material", "[kiosk]") {
  const std::string path = std::string(sas::kSourceDir) + "/textures/wooden_board/texture.toml";
  const auto field = LoadProfile(path);
  CHECK(field.width() == 1920);
  CHECK(field.height() == 1080);
  CHECK(ReliefM(field) > 0.0);
  CHECK(sas::kiosk::ProfileMaterial(path) == "wood");
}

TEST_CASE("a profile that is neither built-in nor a picture names the file and the built-ins",
          "[kiosk]") {
  CHECK_THROWS_AS(LoadProfile("/nonexistent/surface.png"), ProfileError);
  CHECK_THROWS_WITH(LoadProfile("/nonexistent/surface.png"),
                    Catch::Contains("/nonexistent/surface.png") && Catch::Contains("grating"));
}
