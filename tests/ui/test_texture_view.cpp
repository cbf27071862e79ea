// The exploring screen's frame scheduling, cross-fade and overlays (software composition).
#include <catch2/catch.hpp>
#include <memory>
#include <utility>

#include "ui/overlay.h"
#include "ui/texture_view.h"

using sas::platform::PenReading;
using sas::ui::ImageRgba;
using sas::ui::Rgba;
using sas::ui::TextureView;

namespace {

constexpr int kW = 320;
constexpr int kH = 240;

std::shared_ptr<const ImageRgba> Solid(std::uint8_t v) {
  return std::make_shared<const ImageRgba>(kW, kH, Rgba{v, v, v, 255});
}

PenReading Tip(float x, float y, float pressure, bool down, double t_s) {
  PenReading s;
  s.time_ns = static_cast<std::int64_t>(t_s * 1e9);
  s.x_px = x;
  s.y_px = y;
  s.pressure = pressure;
  s.tip_down = down;
  return s;
}

ImageRgba Compose(TextureView& view) {
  ImageRgba out;
  sas::ui::ComposeFrame(view.TakeFrame(), out);
  return out;
}

}  // namespace

TEST_CASE("no frame is produced while nothing changes, and hovering changes nothing", "[render]") {
  TextureView view(kW, kH);
  view.ShowPicture(Solid(100), 0.0, false);
  CHECK(view.Advance(0.0));  // the first picture must be drawn
  view.TakeFrame();
  CHECK_FALSE(view.Advance(0.5));
  double t = 0.5;
  for (int i = 0; i < 20; ++i) {
    t += 1.0 / 60.0;
    view.OnStylus(Tip(50.0f + 5.0f * static_cast<float>(i), 100.0f, 0.0f, false, t));
    CHECK_FALSE(view.Advance(t));
  }
}

TEST_CASE("a press keeps frames coming until the dent has settled, then they stop", "[render]") {
  TextureView view(kW, kH);
  view.ShowPicture(Solid(100), 0.0, false);
  view.Advance(0.0);
  view.TakeFrame();
  view.OnStylus(Tip(160, 120, 0.8f, true, 0.0));
  int frames = 0;
  double t = 0.0;
  for (int i = 0; i < 60; ++i) {
    t += 1.0 / 60.0;
    if (view.Advance(t)) {
      ++frames;
      view.TakeFrame();
    }
  }
  // Press time constant 20 ms: settled well within a second, and not after one frame.
  CHECK(frames > 3);
  CHECK(frames < 40);
  CHECK_FALSE(view.Advance(t + 0.1));
  CHECK(view.deformation().active());  // still pressed: the dent stays, but needs no frames
}

TEST_CASE("a texture switch cross-fades from the old picture to the new one and then stops",
          "[render]") {
  sas::ui::TextureViewConfig cfg;
  cfg.cross_fade_s = 0.4;
  TextureView view(kW, kH, cfg);
  view.ShowPicture(Solid(0), 0.0, false);
  view.Advance(0.0);
  view.TakeFrame();
  view.ShowPicture(Solid(200), 1.0, true);
  view.Advance(1.0);
  CHECK(Compose(view).at(10, 10).r == 0);
  view.Advance(1.2);  // half-way: smoothstep(0.5) = 0.5
  CHECK(Compose(view).at(10, 10).r == 100);
  view.Advance(1.3);  // smoothstep(0.75) = 0.84375
  CHECK(Compose(view).at(10, 10).r == 169);
  CHECK(view.Advance(1.41));
  CHECK(Compose(view).at(10, 10).r == 200);
  CHECK_FALSE(view.fading());
  CHECK_FALSE(view.Advance(1.5));
}

TEST_CASE("a picture of the wrong size is refused", "[render]") {
  TextureView view(kW, kH);
  CHECK_THROWS_AS(view.ShowPicture(std::make_shared<const ImageRgba>(10, 10), 0.0),
                  std::invalid_argument);
}

TEST_CASE("the dent is drawn over a cross-fade from the blended picture", "[render]") {
  TextureView view(kW, kH);
  view.ShowPicture(Solid(0), 0.0, false);
  view.ShowPicture(Solid(200), 0.0, true);
  view.OnStylus(Tip(160, 120, 1.0f, true, 0.0));
  view.Advance(0.0);
  view.OnStylus(Tip(160, 120, 1.0f, true, 0.2));
  view.Advance(0.2);  // fade weight smoothstep(0.2/0.45)
  const ImageRgba shown = Compose(view);
  const Rgba outside = shown.at(10, 10);
  CHECK(outside.r > 0);
  CHECK(outside.r < 200);
  // At the rim of the footprint the patch continues the blended picture seamlessly.
  const float r = view.deformation().config().radius_px;
  CHECK(static_cast<int>(shown.at(160 + static_cast<int>(r) + 1, 120).r) == outside.r);
  CHECK(std::abs(static_cast<int>(shown.at(160 + static_cast<int>(r) - 1, 120).r) - outside.r) <=
        1);
}

TEST_CASE("overlays are drawn where placed, and changing them asks for a frame", "[render]") {
  TextureView view(kW, kH);
  view.ShowPicture(Solid(100), 0.0, false);
  view.Advance(0.0);
  view.TakeFrame();
  sas::ui::Overlays overlays;
  sas::ui::AddStaffPanelFrame(overlays, kW, kH);
  view.SetOverlays(overlays);
  CHECK(view.Advance(0.1));
  const ImageRgba shown = Compose(view);
  const auto panel = sas::ui::StaffPanelRect(kW, kH);
  // Inside the panel: 100 blended towards the panel colour (16,20,28) at alpha 210/255.
  const Rgba inside = shown.at(panel.x + panel.w / 2, panel.y + panel.h / 2);
  CHECK(inside.r == static_cast<int>(std::lround(100 * (45.0 / 255.0) + 16 * (210.0 / 255.0))));
  CHECK(shown.at(panel.x, panel.y).r == 230);  // the frame
  CHECK(shown.at(2, 2).r == 100);              // outside
  view.SetOverlays(overlays);                  // same overlays: nothing to draw
  CHECK_FALSE(view.Advance(0.2));
}

TEST_CASE("the countdown bar shrinks with the time left and the level meter grows with level",
          "[render]") {
  auto covered = [](const sas::ui::Overlays& o, Rgba color) {
    long area = 0;
    for (const auto& s : o) {
      if (s.color == color) area += static_cast<long>(s.rect.w) * s.rect.h;
    }
    return area;
  };
  sas::ui::Overlays full, half;
  sas::ui::AddCountdownBar(full, 1920, 1080, 1.0f);
  sas::ui::AddCountdownBar(half, 1920, 1080, 0.5f);
  const Rgba bar{255, 255, 255, 220};
  CHECK(covered(half, bar) * 2 == Approx(covered(full, bar)).margin(2 * 1080 * 0.03));
  auto lit = [](float level) {
    sas::ui::Overlays o;
    sas::ui::AddLevelMeter(o, 1920, 1080, level);
    return o.size();
  };
  CHECK(lit(0.0f) < lit(0.3f));
  CHECK(lit(0.3f) < lit(1.0f));
  sas::ui::Overlays clip;
  sas::ui::AddLevelMeter(clip, 1920, 1080, 1.0f);
  CHECK(clip.back().color.r > 200);  // the top segment is red
  CHECK(clip.back().color.g < 100);
}

TEST_CASE("the recording sign's shapes: a disc covers its middle, a ring only its edge",
          "[render]") {
  const auto disc = sas::ui::CircleMask(40);
  const auto ring = sas::ui::CircleMask(40, 4);
  REQUIRE(disc->w == 40);
  REQUIRE(ring->h == 40);
  const auto at = [](const sas::ui::TextMask& m, int x, int y) {
    return m.alpha[static_cast<std::size_t>(y * m.w + x)];
  };
  CHECK(at(*disc, 20, 20) == 255);
  CHECK(at(*disc, 0, 0) == 0);  // a disc, not a square
  CHECK(at(*ring, 20, 20) == 0);
  CHECK(at(*ring, 20, 1) == 255);  // inside the 4 px edge
  CHECK(at(*ring, 0, 0) == 0);
  CHECK(disc->text.empty());  // a shape: the screens' text readers skip it
}
