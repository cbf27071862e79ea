// Display probing through SDL2's real video drivers (offscreen needs no display server).
#include <catch2/catch.hpp>
#include <cstdlib>
#include <string>

#include "no_display_server.h"
#include "ui/display_probe.h"

TEST_CASE("the offscreen video driver is reported as a display with a desktop size", "[render]") {
  setenv("SDL_VIDEODRIVER", "offscreen", 1);
  const auto info = sas::ui::ProbeDisplay();
  unsetenv("SDL_VIDEODRIVER");
  INFO(info.problem);
  REQUIRE(info.available);
  CHECK(info.driver == "offscreen");
  CHECK(info.width_px > 0);
  CHECK(info.height_px > 0);
}

TEST_CASE("an unusable video driver is reported as no display, with the reason", "[render]") {
  setenv("SDL_VIDEODRIVER", "no-such-driver", 1);
  const auto info = sas::ui::ProbeDisplay();
  unsetenv("SDL_VIDEODRIVER");
  CHECK_FALSE(info.available);
  CHECK_FALSE(info.problem.empty());
}

TEST_CASE("without a display server SDL's automatic offscreen fallback does not count as a display",
          "[render]") {
  sas::ui::DisplayInfo info;
  {
    const sas::test::NoDisplayServer none;
    info = sas::ui::ProbeDisplay();
  }
  // On a box whose KMSDRM works this is a real display; everywhere else it must be "none".
  if (info.available) {
    CHECK(info.driver == "KMSDRM");
  } else {
    CHECK_FALSE(info.problem.empty());
  }
}
