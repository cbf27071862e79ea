// The six profile slots: store, recall, replace while a reader still holds the old surface, and
// save to disk only on request, in a form the loaders read back.
#include <catch2/catch.hpp>
#include <filesystem>

#include "support/temp_dir.h"
#include "surface/image_surface.h"
#include "surface/profile_slots.h"
#include "surface/sound_image.h"

using namespace sas::surface;

namespace {
HeightField Ramp(int w, int h, double top_m) {
  std::pmr::vector<float> v(static_cast<std::size_t>(w * h));
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = static_cast<float>(top_m * static_cast<double>(i) / static_cast<double>(v.size() - 1));
  return HeightField(w, h, 0.1e-3, std::move(v));
}
}  // namespace

TEST_CASE("six slots store and recall surfaces and a replaced surface lives on for its reader",
          "[surface]") {
  ProfileSlots slots;
  for (int i = 0; i < ProfileSlots::kSlotCount; ++i) CHECK_FALSE(slots.occupied(i));
  CHECK(slots.Recall(3) == nullptr);
  slots.Store(0, "voice", Ramp(100, 1, 1e-3));
  const auto held = slots.Recall(0);
  slots.Store(0, "voice again", Ramp(50, 1, 2e-3));
  CHECK(held->width() == 100);  // the audio side's surface is not pulled from under it
  CHECK(slots.Recall(0)->width() == 50);
  CHECK(slots.label(0) == "voice again");
  slots.Clear(0);
  CHECK_FALSE(slots.occupied(0));
  CHECK_THROWS_AS(slots.Store(6, "x", Ramp(10, 1, 1e-3)), std::out_of_range);
  CHECK_THROWS_AS(slots.Recall(-1), std::out_of_range);
  CHECK_THROWS_AS(slots.Store(1, "empty", HeightField{}), std::invalid_argument);
}

TEST_CASE("saving writes a file only when asked, and it reads back as the same surface",
          "[surface]") {
  sas::test::TempDir dir;
  ProfileSlots slots;
  slots.Store(1, "profile", Ramp(200, 1, 0.8e-3));
  slots.Store(2, "image", Ramp(64, 32, 1.5e-3));
  CHECK(std::filesystem::is_empty(dir.path()));  // storing never touches the disk
  CHECK_THROWS_AS(slots.SaveToDisk(0, dir.file("empty.csv")), LoadError);

  slots.SaveToDisk(1, dir.file("profile.csv"));
  VibrationOptions options;
  options.csv_pitch_mm = 0.1;
  const auto back = VibrationProfileFromFile(dir.file("profile.csv"), options);
  REQUIRE(back.width() == 200);
  for (int x = 0; x < 200; ++x)
    REQUIRE(back.at(x, 0) == Approx(slots.Recall(1)->at(x, 0)).margin(1e-9));

  const double full_scale_mm = slots.SaveToDisk(2, dir.file("image.png"));
  CHECK(full_scale_mm == Approx(1.5));
  const auto image = LoadHeightMapPng(dir.file("image.png"), full_scale_mm, 0.1);
  REQUIRE(image.width() == 64);
  REQUIRE(image.height() == 32);
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 64; ++x) {
      // 16-bit quantisation of 1.5 mm: 23 nm steps.
      REQUIRE(image.at(x, y) == Approx(slots.Recall(2)->at(x, y)).margin(1.5e-3 / 65535.0));
    }
  }
}
