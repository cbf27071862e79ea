// A small program around the ui layer for end-to-end tests under Xvfb and for looking at the tip
// deformation (it is not the kiosk: app/main.cpp wires the real thing). Commands:
//   snapshot <picture|checker> <out.png> [x0 y0 x1 y1 [pressure]]
//       headless: a simulated drag from (x0,y0) to (x1,y1) over 0.25 s, frame composed in software
//       while the tip is still down and moving, written as PNG (no display needed)
//   window <picture|checker> [seconds]
//       full-screen KioskWindow running the real event/redraw loop; prints one line per event
//       ("ready W H driver renderer", "down x y", "up x y", "staff open|closed", "token n",
//       "record pressed|released", "frames n") and stops after `seconds` (default: never)
//   check <screenshot.png> <picture|checker> <x> <y>
//       compares a screenshot with the picture fitted to it: exit 0 when the pixels within the
//       dent radius of (x, y) differ clearly from the picture and pixels far from it do not
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "dent_difference.h"
#include "tools/command_line.h"
#include "ui/kiosk_window.h"
#include "ui/picture_io.h"
#include "ui/texture_view.h"

namespace {

using sas::ui::ImageRgba;

// A checkerboard with a gradient: every displacement shows on it.
ImageRgba Checker(int w, int h) {
  ImageRgba img(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const bool dark = ((x / 24) + (y / 24)) % 2 == 0;
      const auto g = static_cast<std::uint8_t>(dark ? 70 + (x * 60) / w : 190 + (y * 50) / h);
      img.set(
          x, y,
          {g, static_cast<std::uint8_t>(g * 9 / 10), static_cast<std::uint8_t>(g * 8 / 10), 255});
    }
  }
  return img;
}

ImageRgba Picture(const std::string& name, int w, int h) {
  if (name == "checker") return Checker(w, h);
  return sas::ui::ResizeToCover(sas::ui::LoadPicture(name), w, h);
}

double Now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct Args {
  std::string picture, out, shot;
  std::vector<float> drag;  // x0 y0 x1 y1 [pressure]
  double seconds = -1.0;
  int x = 0, y = 0;
};

int Snapshot(const Args& a) {
  const int w = 800, h = 600;
  float x0 = 300, y0 = 300, x1 = 460, y1 = 300, pressure = 1.0f;
  if (a.drag.size() >= 4) {
    x0 = a.drag[0];
    y0 = a.drag[1];
    x1 = a.drag[2];
    y1 = a.drag[3];
  }
  if (a.drag.size() >= 5) pressure = a.drag[4];
  sas::ui::TextureView view(w, h);
  view.ShowPicture(std::make_shared<const ImageRgba>(Picture(a.picture, w, h)), 0.0, false);
  // 60 Hz drag, then the frame at the end of the stroke with the tip still down.
  constexpr int kSteps = 15;
  for (int i = 0; i <= kSteps; ++i) {
    const double t = i / 60.0;
    const float f = static_cast<float>(i) / kSteps;
    sas::platform::PenReading s;
    s.time_ns = static_cast<std::int64_t>(t * 1e9);
    s.x_px = x0 + (x1 - x0) * f;
    s.y_px = y0 + (y1 - y0) * f;
    s.pressure = pressure;
    s.tip_down = true;
    view.OnStylus(s);
    view.Advance(t);
  }
  ImageRgba out;
  sas::ui::ComposeFrame(view.TakeFrame(), out);
  sas::ui::SavePng(out, a.out);
  std::printf("snapshot %s depth %.2f px drag %.2f,%.2f px\n", a.out.c_str(),
              view.deformation().depth_px(), view.deformation().drag_x_px(),
              view.deformation().drag_y_px());
  return 0;
}

int Window(const Args& a) {
  const double run_s = a.seconds;
  sas::ui::KioskWindowOptions options;
  options.staff_chord.hold_s = 0.3;
  sas::ui::KioskWindow window(options);
  window.Open();
  const int w = window.width_px(), h = window.height_px();
  sas::ui::TextureView view(w, h);
  view.ShowPicture(std::make_shared<const ImageRgba>(Picture(a.picture, w, h)), Now(), false);
  std::printf("ready %d %d %s %s\n", w, h, window.driver().c_str(), window.renderer_name().c_str());
  std::fflush(stdout);
  const double start = Now();
  std::uint64_t frames = 0;
  double last_report = start;
  while (run_s < 0 || Now() - start < run_s) {
    for (const auto& e : window.PollEvents(view.NeedsRedraw() ? 0 : 50)) {
      using K = sas::ui::UiEvent::Kind;
      switch (e.kind) {
        case K::kPointerDown:
          std::printf("down %.0f %.0f\n", e.stylus.x_px, e.stylus.y_px);
          break;
        case K::kPointerUp:
          std::printf("up %.0f %.0f\n", e.stylus.x_px, e.stylus.y_px);
          break;
        case K::kStaffChord:
          std::printf("staff %s\n", e.pressed ? "open" : "closed");
          break;
        case K::kTokenKey:
          std::printf("token %d\n", e.token);
          break;
        case K::kRecordKey:
          std::printf("record %s\n", e.pressed ? "pressed" : "released");
          break;
        case K::kLanguageKey:
          std::printf("language\n");
          break;
        case K::kRedraw:
          view.Invalidate();
          break;
        case K::kPointerMove:
          break;
      }
      if (e.kind == K::kPointerDown || e.kind == K::kPointerMove || e.kind == K::kPointerUp) {
        view.OnStylus(e.stylus);
      }
      std::fflush(stdout);
    }
    sas::ui::Overlays overlays;
    if (window.staff_panel_open()) sas::ui::AddStaffPanelFrame(overlays, w, h);
    view.SetOverlays(std::move(overlays));
    if (view.Advance(Now())) {
      window.Present(view.TakeFrame());
      ++frames;
    }
    if (Now() - last_report > 1.0) {
      std::printf("frames %llu\n", static_cast<unsigned long long>(frames));
      std::fflush(stdout);
      last_report = Now();
    }
  }
  return 0;
}

int Check(const Args& a) {
  const ImageRgba shot = sas::ui::LoadPicture(a.shot);
  const ImageRgba pic = Picture(a.picture, shot.width(), shot.height());
  const int cx = a.x, cy = a.y;
  const auto dent = sas::test::MeasureDent(shot, pic, cx, cy);
  const double near_mean = dent.near_mean, far_mean = dent.far_mean;
  std::printf("near-dent mean difference %.2f, far mean difference %.3f\n", near_mean, far_mean);
  return near_mean > 8.0 && far_mean < 1.0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"A small program around the ui layer for the end-to-end tests under Xvfb.",
               "ui_e2e_app"};
  app.require_subcommand(1);
  Args a;
  const std::string picture_help = "a picture file, or checker (a checkerboard with a gradient)";
  CLI::App* snapshot = app.add_subcommand(
      "snapshot",
      "headless: a simulated 0.25 s drag, the frame composed in software while the "
      "tip is still down, written as PNG");
  snapshot->add_option("picture", a.picture, picture_help)->required();
  snapshot->add_option("out", a.out, "the PNG to write")->required();
  snapshot->add_option("drag", a.drag, "x0 y0 x1 y1 [pressure] (default 300 300 460 300 1)")
      ->expected(0, 5);
  CLI::App* window = app.add_subcommand(
      "window", "full-screen KioskWindow running the real event loop, one line per event");
  window->add_option("picture", a.picture, picture_help)->required();
  window->add_option("seconds", a.seconds, "stop after this long (default: never)");
  CLI::App* check = app.add_subcommand(
      "check",
      "exit 0 when the screenshot differs from the picture within the dent radius of "
      "(x, y) and not far from it");
  check->add_option("shot", a.shot, "the screenshot (PNG)")->required();
  check->add_option("picture", a.picture, picture_help)->required();
  check->add_option("x", a.x, "dent centre, px")->required();
  check->add_option("y", a.y, "dent centre, px")->required();
  if (const int code = sas::kiosk::ParseProgramCommandLine(app, argc, argv); code >= 0) return code;
  try {
    if (snapshot->parsed()) return Snapshot(a);
    if (window->parsed()) return Window(a);
    return Check(a);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ui_e2e_app: %s\n", e.what());
    return 1;
  }
}
