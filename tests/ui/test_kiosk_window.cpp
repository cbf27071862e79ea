// The full-screen kiosk window under SDL's `offscreen` video driver (no display server needed):
// size, no quit path, staff chord, input mapping, and what a presented frame really shows.
#include <SDL.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "no_display_server.h"
#include "sdl_test_events.h"
#include "ui/kiosk_window.h"
#include "ui/texture_view.h"

using sas::test::OffscreenDriver;
using sas::test::PushKey;
using sas::test::PushMouseButton;
using sas::test::PushMouseMotion;
using sas::ui::ImageRgba;
using sas::ui::KioskWindow;
using sas::ui::Rgba;
using sas::ui::UiEvent;

namespace {

double NowS() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Opens the window and drains what opening it queued (shown/exposed: redraw requests), so a test
// sees only the events it pushes.
void OpenSettled(KioskWindow& window) {
  window.Open();
  for (int quiet = 0; quiet < 3;) quiet = window.PollEvents(5).empty() ? quiet + 1 : 0;
}

std::vector<UiEvent> OfKind(const std::vector<UiEvent>& events, UiEvent::Kind kind) {
  std::vector<UiEvent> out;
  for (const auto& e : events) {
    if (e.kind == kind) out.push_back(e);
  }
  return out;
}

// Polls for up to `timeout_s`, collecting everything, until an event of `kind` arrives.
std::vector<UiEvent> PollUntil(KioskWindow& w, UiEvent::Kind kind, double timeout_s) {
  std::vector<UiEvent> all;
  const double end = NowS() + timeout_s;
  while (NowS() < end) {
    for (const auto& e : w.PollEvents(10)) all.push_back(e);
    if (!OfKind(all, kind).empty()) break;
  }
  return all;
}

ImageRgba Textured(int w, int h) {
  ImageRgba img(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const bool dark = ((x / 16) + (y / 16)) % 2 == 0;
      const auto v = static_cast<std::uint8_t>(dark ? 70 : 190);
      img.set(x, y, {v, v, static_cast<std::uint8_t>(v / 2), 255});
    }
  }
  return img;
}

double MeanDifferenceInRing(const ImageRgba& a, const ImageRgba& b, float cx, float cy, double r0,
                            double r1) {
  double sum = 0.0, n = 0.0;
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      const double r = std::hypot(x - double{cx}, y - double{cy});
      if (r < r0 || r >= r1) continue;
      const Rgba p = a.at(x, y), q = b.at(x, y);
      sum += (std::abs(p.r - q.r) + std::abs(p.g - q.g) + std::abs(p.b - q.b)) / 3.0;
      n += 1.0;
    }
  }
  return n > 0.0 ? sum / n : 0.0;
}

}  // namespace

TEST_CASE("the window opens full-screen at the desktop display size", "[render]") {
  OffscreenDriver driver;
  KioskWindow window;
  window.Open();
  SDL_DisplayMode mode{};
  REQUIRE(SDL_GetDesktopDisplayMode(0, &mode) == 0);
  CHECK(window.driver() == "offscreen");
  CHECK(window.width_px() == mode.w);
  CHECK(window.height_px() == mode.h);
  CHECK(window.width_px() > 1);
  CHECK(SDL_ShowCursor(SDL_QUERY) == SDL_DISABLE);
  CHECK_FALSE(SDL_IsScreenSaverEnabled());
}

TEST_CASE("quit requests, window close, Escape, Alt-F4 and Ctrl-Q neither end nor reach the loop",
          "[render]") {
  OffscreenDriver driver;
  KioskWindow window;
  OpenSettled(window);
  SDL_Event quit{};
  quit.type = SDL_QUIT;
  REQUIRE(SDL_PushEvent(&quit) == 1);
  SDL_Event close{};
  close.type = SDL_WINDOWEVENT;
  close.window.event = SDL_WINDOWEVENT_CLOSE;
  REQUIRE(SDL_PushEvent(&close) == 1);
  PushKey(SDLK_ESCAPE, true, KMOD_NONE);
  PushKey(SDLK_ESCAPE, false, KMOD_NONE);
  PushKey(SDLK_F4, true, KMOD_LALT);
  PushKey(SDLK_F4, false, KMOD_LALT);
  PushKey(SDLK_q, true, KMOD_LCTRL);
  PushKey(SDLK_q, false, KMOD_LCTRL);
  PushKey(SDLK_w, true, KMOD_LCTRL);
  const auto events = window.PollEvents();
  CHECK(events.empty());
  CHECK(window.is_open());
  // Still drawing afterwards.
  sas::ui::TextureView view(window.width_px(), window.height_px());
  view.ShowPicture(std::make_shared<const ImageRgba>(window.width_px(), window.height_px(),
                                                     Rgba{10, 20, 30, 255}),
                   0.0, false);
  view.Advance(0.0);
  ImageRgba shown;
  window.Present(view.TakeFrame(), &shown);
  CHECK(shown.at(5, 5) == Rgba{10, 20, 30, 255});
}

TEST_CASE("the staff chord held for its hold time toggles the staff panel, once per hold",
          "[render]") {
  OffscreenDriver driver;
  sas::ui::KioskWindowOptions options;
  options.staff_chord.keys = "ctrl+alt+s";
  options.staff_chord.hold_s = 0.05;
  KioskWindow window(options);
  window.Open();
  const double start = NowS();
  PushKey(SDLK_s, true, KMOD_LCTRL | KMOD_LALT);
  const auto first = PollUntil(window, UiEvent::Kind::kStaffChord, 1.0);
  const double took = NowS() - start;
  REQUIRE(OfKind(first, UiEvent::Kind::kStaffChord).size() == 1);
  CHECK(OfKind(first, UiEvent::Kind::kStaffChord)[0].pressed);
  CHECK(window.staff_panel_open());
  CHECK(took >= 0.05 - 0.002);  // SDL's event timestamps have 1 ms resolution
  // Holding on does not fire again.
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  CHECK(OfKind(window.PollEvents(), UiEvent::Kind::kStaffChord).empty());
  PushKey(SDLK_s, false, KMOD_LCTRL | KMOD_LALT);
  // A second hold closes the panel.
  PushKey(SDLK_s, true, KMOD_RCTRL | KMOD_RALT);
  const auto second = PollUntil(window, UiEvent::Kind::kStaffChord, 1.0);
  REQUIRE(OfKind(second, UiEvent::Kind::kStaffChord).size() == 1);
  CHECK_FALSE(OfKind(second, UiEvent::Kind::kStaffChord)[0].pressed);
  CHECK_FALSE(window.staff_panel_open());
}

TEST_CASE("the chord key without its modifiers, or released early, is no staff chord", "[render]") {
  OffscreenDriver driver;
  sas::ui::KioskWindowOptions options;
  options.staff_chord.hold_s = 0.1;
  KioskWindow window(options);
  window.Open();
  PushKey(SDLK_s, true, KMOD_LCTRL);  // alt missing
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  CHECK(OfKind(window.PollEvents(), UiEvent::Kind::kStaffChord).empty());
  PushKey(SDLK_s, false, KMOD_LCTRL);
  PushKey(SDLK_s, true, KMOD_LCTRL | KMOD_LALT);
  PushKey(SDLK_LALT, false, KMOD_LCTRL);  // let go of alt before the hold time
  window.PollEvents();
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  CHECK(OfKind(window.PollEvents(), UiEvent::Kind::kStaffChord).empty());
  CHECK_FALSE(window.staff_panel_open());
}

TEST_CASE("a staff chord held long enough counts even when the loop only looks after its release",
          "[render]") {
  OffscreenDriver driver;
  sas::ui::KioskWindowOptions options;
  options.staff_chord.hold_s = 0.1;
  KioskWindow window(options);
  window.Open();
  // A slow frame: the key goes down and up again while nobody polls.
  PushKey(SDLK_s, true, KMOD_LCTRL | KMOD_LALT);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  PushKey(SDLK_s, false, KMOD_LCTRL | KMOD_LALT);
  const auto events = window.PollEvents();
  REQUIRE(OfKind(events, UiEvent::Kind::kStaffChord).size() == 1);
  CHECK(window.staff_panel_open());
}

TEST_CASE("a chord a visitor could type by accident, or a misspelt one, is refused at set-up",
          "[render]") {
  OffscreenDriver driver;
  for (const char* bad : {"s", "shift+s", "ctrl+alt+nosuchkey", "hyper+s", "ctrl+"}) {
    sas::ui::KioskWindowOptions options;
    options.staff_chord.keys = bad;
    KioskWindow window(options);
    INFO(bad);
    CHECK_THROWS_AS(window.Open(), sas::ui::WindowError);
  }
}

TEST_CASE("a mouse drag becomes pointer down, moves and up at the pushed pixel positions",
          "[render]") {
  OffscreenDriver driver;
  sas::ui::KioskWindowOptions options;
  options.press.light = options.press.firm = 0.7f;  // a constant press, to check it is carried
  KioskWindow window(options);
  OpenSettled(window);
  PushMouseMotion(10, 20);  // hover
  PushMouseButton(100, 120, true);
  PushMouseMotion(130, 125);
  PushMouseMotion(160, 130);
  PushMouseButton(160, 130, false);
  const auto events = window.PollEvents();
  REQUIRE(events.size() == 5);
  CHECK(events[0].kind == UiEvent::Kind::kPointerMove);
  CHECK_FALSE(events[0].stylus.tip_down);
  CHECK(events[0].stylus.pressure == 0.0f);
  CHECK(events[1].kind == UiEvent::Kind::kPointerDown);
  CHECK(events[1].stylus.x_px == 100.0f);
  CHECK(events[1].stylus.y_px == 120.0f);
  CHECK(events[1].stylus.pressure == 0.7f);
  CHECK(events[2].kind == UiEvent::Kind::kPointerMove);
  CHECK(events[2].stylus.tip_down);
  CHECK(events[2].stylus.x_px == 130.0f);
  CHECK(events[3].stylus.y_px == 130.0f);
  CHECK(events[4].kind == UiEvent::Kind::kPointerUp);
  CHECK_FALSE(events[4].stylus.tip_down);
  CHECK(events[4].stylus.tilt_x_deg == 0.0f);
  CHECK(events[4].stylus.origin == sas::platform::PenOrigin::kMouse);
  for (std::size_t i = 1; i < events.size(); ++i) CHECK(events[i].time_ns >= events[i - 1].time_ns);
  const auto now_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                          std::chrono::steady_clock::now().time_since_epoch())
                          .count();
  CHECK(now_ns - events[4].time_ns < 1'000'000'000);  // stamped on the monotonic clock
}

TEST_CASE(
    "a touch finger becomes a stroke in pixels with the panel's pressure and a second finger "
    "and SDL's synthetic mouse events are ignored",
    "[render]") {
  OffscreenDriver driver;
  KioskWindow window;
  OpenSettled(window);
  auto finger = [](Uint32 type, SDL_FingerID id, float x, float y, float p) {
    SDL_Event e{};
    e.type = type;
    e.tfinger.touchId = 1;
    e.tfinger.fingerId = id;
    e.tfinger.x = x;
    e.tfinger.y = y;
    e.tfinger.pressure = p;
    REQUIRE(SDL_PushEvent(&e) == 1);
  };
  finger(SDL_FINGERDOWN, 7, 0.25f, 0.5f, 0.3f);
  SDL_Event synthetic{};
  synthetic.type = SDL_MOUSEBUTTONDOWN;
  synthetic.button.which = SDL_TOUCH_MOUSEID;
  synthetic.button.button = SDL_BUTTON_LEFT;
  REQUIRE(SDL_PushEvent(&synthetic) == 1);
  finger(SDL_FINGERDOWN, 8, 0.9f, 0.9f, 1.0f);  // a second finger
  finger(SDL_FINGERMOTION, 7, 0.5f, 0.5f, 0.9f);
  finger(SDL_FINGERUP, 7, 0.5f, 0.5f, 0.0f);
  const auto events = window.PollEvents();
  REQUIRE(events.size() == 3);
  const float w = static_cast<float>(window.width_px()), h = static_cast<float>(window.height_px());
  CHECK(events[0].kind == UiEvent::Kind::kPointerDown);
  CHECK(events[0].stylus.x_px == Approx(0.25f * w));
  CHECK(events[0].stylus.y_px == Approx(0.5f * h));
  CHECK(events[0].stylus.pressure == Approx(0.3f));
  CHECK(events[0].stylus.origin == sas::platform::PenOrigin::kTouch);
  CHECK(events[1].stylus.pressure == Approx(0.9f));
  CHECK(events[1].stylus.x_px == Approx(0.5f * w));
  CHECK(events[2].kind == UiEvent::Kind::kPointerUp);
}

TEST_CASE(
    "a flood of pointer motion is taken a bounded number of SDL events per poll, the rest in "
    "order at the next polls",
    "[render]") {
  OffscreenDriver driver;
  KioskWindow window;
  OpenSettled(window);
  for (int x = 0; x < 150; ++x) PushMouseMotion(x, 40);
  std::vector<std::vector<UiEvent>> polls;
  for (int i = 0; i < 3; ++i) polls.push_back(window.PollEvents(i == 0 ? 0 : 5, 64));
  REQUIRE(polls[0].size() == 64);
  REQUIRE(polls[1].size() == 64);
  REQUIRE(polls[2].size() == 22);
  int x = 0;
  std::int64_t last_ns = 0;
  for (const auto& poll : polls) {
    for (const auto& e : poll) {
      CHECK(e.stylus.x_px == static_cast<float>(x++));
      CHECK(e.time_ns >= last_ns);
      last_ns = e.time_ns;
    }
  }
  CHECK(window.PollEvents().empty());
}

TEST_CASE("keys 1-4 and 0 stand in for the tokens and R for the record button", "[render]") {
  OffscreenDriver driver;
  KioskWindow window;
  OpenSettled(window);
  PushKey(SDLK_3, true, KMOD_NONE);
  PushKey(SDLK_3, false, KMOD_NONE);
  PushKey(SDLK_KP_1, true, KMOD_NUM);
  PushKey(SDLK_0, true, KMOD_NONE);
  PushKey(SDLK_r, true, KMOD_NONE);
  PushKey(SDLK_r, false, KMOD_NONE);
  PushKey(SDLK_5, true, KMOD_NONE);
  const auto events = window.PollEvents();
  REQUIRE(events.size() == 5);
  CHECK(events[0].kind == UiEvent::Kind::kTokenKey);
  CHECK(events[0].token == 2);
  CHECK(events[1].token == 0);
  CHECK(events[2].token == -1);
  CHECK(events[3].kind == UiEvent::Kind::kRecordKey);
  CHECK(events[3].pressed);
  CHECK(events[4].kind == UiEvent::Kind::kRecordKey);
  CHECK_FALSE(events[4].pressed);
}

TEST_CASE(
    "a presented frame read back shows the dent at the drag point and the picture "
    "elsewhere, as the software compositor draws it",
    "[render]") {
  OffscreenDriver driver;
  KioskWindow window;
  window.Open();
  const int w = window.width_px(), h = window.height_px();
  const auto picture = std::make_shared<const ImageRgba>(Textured(w, h));
  sas::ui::TextureView view(w, h);
  view.ShowPicture(picture, NowS(), false);
  const int x0 = w / 3, y = h / 2;
  PushMouseButton(x0, y, true);
  for (int i = 0; i < 12; ++i) {
    for (const auto& e : window.PollEvents()) view.OnStylus(e.stylus);
    view.Advance(NowS());
    if (view.NeedsRedraw()) window.Present(view.TakeFrame());
    std::this_thread::sleep_for(std::chrono::milliseconds(16));
    PushMouseMotion(x0 + 6 * (i + 1), y);
  }
  for (const auto& e : window.PollEvents()) view.OnStylus(e.stylus);
  view.Advance(NowS());
  const float tip_x = static_cast<float>(x0 + 72), tip_y = static_cast<float>(y);
  REQUIRE(view.deformation().centre_x_px() == tip_x);
  REQUIRE(view.deformation().depth_px() > 5.0f);
  ImageRgba shown;
  const auto& frame = view.TakeFrame();
  window.Present(frame, &shown);
  REQUIRE(shown.width() == w);
  const float r = view.deformation().config().radius_px;
  const double near = MeanDifferenceInRing(shown, *picture, tip_x, tip_y, 0.0, 0.8 * r);
  const double far = MeanDifferenceInRing(shown, *picture, tip_x, tip_y, 1.05 * r, 4.0 * r);
  INFO("mean difference near the tip " << near << ", around it " << far << " (renderer "
                                       << window.renderer_name() << ")");
  CHECK(near > 10.0);
  CHECK(far < 0.01);
  ImageRgba composed;
  sas::ui::ComposeFrame(frame, composed);
  CHECK(MeanDifferenceInRing(shown, composed, tip_x, tip_y, 0.0, 1e9) < 0.01);
}

TEST_CASE("the cross-fade the window draws matches the software compositor within one level",
          "[render]") {
  OffscreenDriver driver;
  KioskWindow window;
  window.Open();
  const int w = window.width_px(), h = window.height_px();
  sas::ui::TextureView view(w, h);
  view.ShowPicture(std::make_shared<const ImageRgba>(w, h, Rgba{20, 200, 60, 255}), 0.0, false);
  view.ShowPicture(std::make_shared<const ImageRgba>(Textured(w, h)), 0.0, true);
  view.Advance(0.2);
  REQUIRE(view.fading());
  ImageRgba shown, composed;
  const auto& frame = view.TakeFrame();
  window.Present(frame, &shown);
  sas::ui::ComposeFrame(frame, composed);
  int worst = 0;
  for (int yy = 0; yy < h; yy += 7) {
    for (int xx = 0; xx < w; xx += 7) {
      const Rgba a = shown.at(xx, yy), b = composed.at(xx, yy);
      worst = std::max({worst, std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
    }
  }
  CHECK(worst <= 1);
}

TEST_CASE(
    "with no display the kiosk window refuses SDL's automatic offscreen fallback (nobody would "
    "see it) and says so",
    "[render]") {
  std::string driver, error;
  {
    const sas::test::NoDisplayServer none;
    KioskWindow window;
    try {
      window.Open();
      if (const char* name = SDL_GetCurrentVideoDriver()) driver = name;
    } catch (const sas::ui::WindowError& e) {
      error = e.what();
    }
  }
  // On a box whose KMSDRM works the window is real; everywhere else it must not open.
  if (error.empty()) {
    CHECK(driver == "KMSDRM");
  } else {
    INFO(error);
    CHECK(error.find("virtual 'offscreen' driver") != std::string::npos);
  }
}
