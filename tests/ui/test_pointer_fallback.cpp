// The mouse fallback through the kiosk's own window and engine, as the live loop wires them
// (app/live_kiosk.cpp: pointer events -> KioskEngine::OnPen): SDL events pushed under SDL's
// offscreen video driver, the engine on the real textures. A press held on a bubble grows until
// the bubble pops; a quick click stays light; the right button and the roll key (Space) roll.
#include <SDL.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <utility>
#include <vector>

#include "kiosk/kiosk_engine.h"
#include "sdl_test_events.h"
#include "ui/kiosk_window.h"

using sas::kiosk::KioskEngine;
using sas::platform::PenReading;
using sas::test::OffscreenDriver;
using sas::test::PushKey;
using sas::test::PushMouseButton;
using sas::test::PushMouseMotion;
using sas::ui::KioskWindow;
using sas::ui::UiEvent;

namespace {

std::int64_t NowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// The window and the engine wired as the live loop wires them (no tablet: the pointer drives).
struct Fallback {
  static sas::kiosk::KioskEngineOptions Options() {
    sas::kiosk::KioskEngineOptions options;
    options.cues_dir = "/nonexistent";
    return options;
  }

  // Opens the window and an engine sized to it, bubble wrap on its token.
  void Open() {
    window.Open();
    for (int quiet = 0; quiet < 3;) quiet = window.PollEvents(5).empty() ? quiet + 1 : 0;
    auto options = Options();
    options.screen_width_px = window.width_px();
    options.screen_height_px = window.height_px();
    engine.emplace(options);
    for (std::size_t t = 0; t < engine->textures().size(); ++t) {
      if (engine->textures()[t].loaded.bubbles) bubble_texture = static_cast<int>(t);
    }
    REQUIRE(bubble_texture >= 0);
    engine->OnToken(NowNs(), engine->TokenForTexture(static_cast<std::size_t>(bubble_texture)));
    engine->Tick(NowNs());
    REQUIRE(engine->surface().texture == bubble_texture);
  }

  // One poll of the window (waiting up to `wait_ms` for an event); each pointer event goes to the
  // engine, then to `after` (with it). Returns them.
  template <typename After>
  std::vector<PenReading> Poll(int wait_ms, After after) {
    std::vector<PenReading> readings;
    for (const auto& event : window.PollEvents(wait_ms)) {
      if (event.kind == UiEvent::Kind::kPointerDown || event.kind == UiEvent::Kind::kPointerMove ||
          event.kind == UiEvent::Kind::kPointerUp) {
        engine->OnPen(event.stylus);
        after(event.stylus);
        readings.push_back(event.stylus);
      }
    }
    engine->Tick(NowNs());
    return readings;
  }
  std::vector<PenReading> Poll(int wait_ms) {
    return Poll(wait_ms, [](const PenReading&) {});
  }

  // Screen pixels of the `n`th bubble (in the centres' order) that lies well inside the screen.
  std::pair<int, int> BubbleOnScreen(int n, int* index) const {
    const auto& centres = engine->bubbles()->centres();
    for (std::size_t i = 0; i < centres.size(); ++i) {
      double sx = 0.0, sy = 0.0;
      engine->FieldToScreen(centres[i].first, centres[i].second, &sx, &sy);
      if (sx < 100 || sy < 100 || sx > window.width_px() - 100 || sy > window.height_px() - 100)
        continue;
      if (n-- == 0) {
        *index = static_cast<int>(i);
        return {static_cast<int>(std::lround(sx)), static_cast<int>(std::lround(sy))};
      }
    }
    FAIL("not enough bubbles on the screen");
    return {0, 0};
  }

  OffscreenDriver driver;
  KioskWindow window;
  std::optional<KioskEngine> engine;
  int bubble_texture = -1;
};

}  // namespace

TEST_CASE(
    "pointer fallback: a mouse press held still on a bubble grows through the window's SDL events "
    "until the bubble pops after about a second, while a quick click leaves its bubble whole",
    "[render]") {
  Fallback kiosk;
  kiosk.Open();
  int quick_bubble = -1, held_bubble = -1;
  const auto [qx, qy] = kiosk.BubbleOnScreen(0, &quick_bubble);
  const auto [hx, hy] = kiosk.BubbleOnScreen(1, &held_bubble);

  // A quick click: down and up at once, the press as light as it starts.
  PushMouseButton(qx, qy, true, SDL_BUTTON_LEFT);
  PushMouseButton(qx, qy, false, SDL_BUTTON_LEFT);
  const auto click = kiosk.Poll(0);
  REQUIRE(click.size() == 2);
  CHECK(click[0].tip_down);
  CHECK(click[0].pressure < 0.35);
  CHECK(kiosk.engine->popped_bubbles() == 0);

  // Held still on another bubble: the window reports the growing press while nothing moves,
  // until the pop (a generous deadline only stops a kiosk that never pops it).
  PushMouseButton(hx, hy, true, SDL_BUTTON_LEFT);
  std::int64_t down_ns = -1, popped_ns = -1;
  double popped_pressure = 0.0;
  int resting_reports = 0;
  const std::int64_t deadline = NowNs() + 20'000'000'000;
  while (popped_ns < 0 && NowNs() < deadline) {
    kiosk.Poll(5, [&](const PenReading& r) {
      if (down_ns < 0 && r.tip_down) down_ns = r.time_ns;
      if (down_ns >= 0 && r.time_ns > down_ns) ++resting_reports;
      if (kiosk.engine->popped_bubbles() > 0 && popped_ns < 0) {
        popped_ns = r.time_ns;
        popped_pressure = r.pressure;
      }
    });
  }
  PushMouseButton(hx, hy, false, SDL_BUTTON_LEFT);
  kiosk.Poll(0);
  REQUIRE(popped_ns >= 0);
  CHECK(kiosk.engine->popped_bubbles() == 1);
  CHECK(kiosk.engine->bubbles()->popped(held_bubble));
  CHECK_FALSE(kiosk.engine->bubbles()->popped(quick_bubble));
  CHECK(resting_reports >= 10);  // the press grew without a motion event
  // Not before the press reached the bubble's pop force (about a second by the events' stamps;
  // later only on a machine too busy to poll).
  CHECK(popped_pressure >= 0.62);
  CHECK(static_cast<double>(popped_ns - down_ns) * 1e-9 >= 0.9);
}

TEST_CASE(
    "pointer fallback: a right-button drag, and a left-button drag while Space is held, roll the "
    "stroke through the window and the engine, the left button alone with the texture's own "
    "probe",
    "[render]") {
  Fallback kiosk;
  kiosk.Open();
  // Away from the bubbles' test: anywhere on the picture.
  const int y = kiosk.window.height_px() / 2;
  // (A busy machine may add the resting press's report after a poll's events: only the events'
  // own readings and the button readings are looked at.)
  const auto drag = [&](Uint8 button, int x0) {
    PushMouseButton(x0, y, true, button);
    for (int i = 1; i <= 4; ++i) PushMouseMotion(x0 + 10 * i, y);
    auto readings = kiosk.Poll(0);
    REQUIRE(readings.size() >= 5);
    readings.resize(5);
    CHECK(readings.back().x_px == Approx(x0 + 40));
    return readings;
  };
  const auto button_reading = [&] {
    for (const auto& r : kiosk.Poll(0)) {
      if (r.kind == sas::platform::PenReadingKind::kButton) return r;
    }
    FAIL("no button reading");
    return PenReading{};
  };
  const auto lift = [&](Uint8 button, int x) {
    PushMouseButton(x, y, false, button);
    kiosk.Poll(0);
  };

  auto left = drag(SDL_BUTTON_LEFT, 200);
  CHECK_FALSE(left.back().barrel_button);
  CHECK(kiosk.engine->stroke_style() != sas::synth::ProbeStyle::kRoll);
  // Space pressed mid-stroke: the stroke rolls at once (a reading of its own, no motion needed)
  // and scrapes again when it is let go.
  PushKey(SDLK_SPACE, true);
  CHECK(button_reading().barrel_button);
  CHECK(kiosk.engine->stroke_style() == sas::synth::ProbeStyle::kRoll);
  PushKey(SDLK_SPACE, false);
  CHECK_FALSE(button_reading().barrel_button);
  CHECK(kiosk.engine->stroke_style() != sas::synth::ProbeStyle::kRoll);
  lift(SDL_BUTTON_LEFT, 240);

  auto right = drag(SDL_BUTTON_RIGHT, 400);
  CHECK(right.front().tip_down);
  CHECK(right.back().barrel_button);
  CHECK(kiosk.engine->stroke_style() == sas::synth::ProbeStyle::kRoll);
  lift(SDL_BUTTON_RIGHT, 440);

  // Space held before the touch: the whole left-button stroke rolls.
  PushKey(SDLK_SPACE, true);
  kiosk.Poll(0);
  left = drag(SDL_BUTTON_LEFT, 600);
  CHECK(left.front().barrel_button);
  CHECK(kiosk.engine->stroke_style() == sas::synth::ProbeStyle::kRoll);
  PushKey(SDLK_SPACE, false);
  lift(SDL_BUTTON_LEFT, 640);
}
