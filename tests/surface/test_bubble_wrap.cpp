// Bubble wrap: the layout in the texture file matches the bubbles in the true height map; pressing
// past the force threshold pops a bubble once, flattens it until Reset.
#include <catch2/catch.hpp>
#include <cmath>

#include "surface/bubble_wrap.h"
#include "surface/image_surface.h"
#include "surface/texture_file.h"

using namespace sas::surface;

namespace {

struct Kiosk {
  TextureFile file = LoadTextureFile(std::string(SAS_TEXTURES_DIR) + "/bubble_wrap/texture.toml");
  HeightField truth = LoadHeightMapPng(file.height_map_path, file.height_scale_mm,
                                       DisplayGeometry{}.pixel_pitch_mm());
};

double MaxInDisc(const HeightField& f, double cx, double cy, double r) {
  double top = -1.0;
  for (int y = std::max(0, static_cast<int>(cy - r));
       y <= std::min(f.height() - 1, static_cast<int>(cy + r)); ++y) {
    for (int x = std::max(0, static_cast<int>(cx - r));
         x <= std::min(f.width() - 1, static_cast<int>(cx + r)); ++x) {
      if (std::hypot(x - cx, y - cy) <= r) top = std::max(top, static_cast<double>(f.at(x, y)));
    }
  }
  return top;
}

}  // namespace

TEST_CASE("every bubble of the texture file's hexagonal layout is a dome in the true height map",
          "[surface]") {
  const Kiosk k;
  REQUIRE(k.file.bubbles.has_value());
  const auto& layout = k.file.bubbles->layout;
  const auto centres = layout.Centres(k.truth.width(), k.truth.height());
  REQUIRE(centres.size() > 50);
  for (const auto& [x, y] : centres) {
    // The top of the dome is at the centre: > 2.5 mm there, film (< 0.3 mm) just outside the rim.
    const int ix = static_cast<int>(std::lround(x)), iy = static_cast<int>(std::lround(y));
    CHECK(k.truth.at(ix, iy) * 1e3 > 2.5);
    const double out_x = x + layout.radius_px + 6.0;
    if (out_x < k.truth.width()) CHECK(k.truth.at(static_cast<int>(out_x), iy) * 1e3 < 0.3);
  }
  // Nearest neighbours are one pitch apart (hexagonal packing).
  for (std::size_t i = 1; i < 5; ++i) {
    CHECK(std::hypot(centres[i].first - centres[i - 1].first,
                     centres[i].second - centres[i - 1].second) == Approx(layout.pitch_px));
  }
}

TEST_CASE("a bubble pops only at the force threshold, once, stays flat, and Reset restores it",
          "[surface]") {
  const Kiosk k;
  BubbleWrapState state(k.file.bubbles->layout, k.file.bubbles->pop_force_n, k.truth);
  const double threshold = k.file.bubbles->pop_force_n;
  const auto [cx, cy] = state.centres()[20];
  const auto intact = state.field();

  CHECK_FALSE(state.Press(cx + 10, cy - 5, threshold * 0.99).has_value());  // too soft
  CHECK(state.popped_count() == 0);
  CHECK_FALSE(state.Press(cx + k.file.bubbles->layout.radius_px + 10, cy, threshold * 3)
                  .has_value());  // on the film

  const auto event = state.Press(cx + 10, cy - 5, threshold * 1.5);
  REQUIRE(event.has_value());
  CHECK(event->bubble == 20);
  CHECK(event->x_px == cx);
  CHECK(event->y_px == cy);
  CHECK(event->strength == Approx(1.5));
  CHECK(state.popped(20));
  CHECK(state.popped_count() == 1);
  // Flattened: nothing within the bubble (rim included) stands above the film any more.
  const double r = k.file.bubbles->layout.radius_px;
  CHECK(MaxInDisc(*state.field(), cx, cy, r * 1.2) * 1e3 < 0.3);
  // The neighbours and the untouched field are unchanged.
  const auto [nx, ny] = state.centres()[21];
  CHECK(MaxInDisc(*state.field(), nx, ny, r) == MaxInDisc(*intact, nx, ny, r));
  CHECK(MaxInDisc(*intact, cx, cy, r) * 1e3 > 2.5);
  // The summed-area table follows the new heights (the synth averages through it).
  CHECK(state.field()->BoxMean(static_cast<int>(cx) - 20, static_cast<int>(cy) - 20,
                               static_cast<int>(cx) + 20, static_cast<int>(cy) + 20) *
            1e3 <
        0.3);

  CHECK_FALSE(state.Press(cx, cy, threshold * 4).has_value());  // a popped bubble cannot pop again
  state.Reset();
  CHECK(state.popped_count() == 0);
  CHECK(MaxInDisc(*state.field(), cx, cy, r) * 1e3 > 2.5);
  CHECK(state.Press(cx, cy, threshold).has_value());  // exactly at the threshold pops
}

TEST_CASE("bubble wrap state refuses a non-positive threshold or an empty field", "[surface]") {
  const HeightField field(8, 8, 1e-4, std::pmr::vector<float>(64, 0.0f));
  CHECK_THROWS_AS(BubbleWrapState(BubbleLayout{}, 0.0, field), std::invalid_argument);
  CHECK_THROWS_AS(BubbleWrapState(BubbleLayout{}, 1.0, HeightField{}), std::invalid_argument);
}
