// What visitors read: the attract screen, exploring, the countdown, the recording and the voice
// surface. Checked: each screen's sentences are the language table's (read from the file, not
// from the view) and drawn in the TTF font at a size that follows the screen; every text plate
// keeps white text at 7:1 or more against the plate laid over the brightest pixel under it.
// Run plainly, at 1920x1080 and 1280x720 composed in software (ui::ComposeFrame). Run by
// tests/e2e/screens_xvfb_e2e.sh with SAS_SCREENS_WINDOW=1 on an Xvfb display, at the display's
// size through the kiosk's own full-screen window (SDL's X11 renderer, pixels read back from it),
// which must show what the software composition shows. With SAS_SCREENSHOTS_DIR set the screens
// are written there as JPEGs (docs/screenshots/, listed in README).
#include <toml++/toml.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "kiosk/kiosk_engine.h"
#include "kiosk/synthetic_voice.h"
#include "kiosk/virtual_visit.h"
#include "platform/audio/audio_input.h"
#include "sas/version.h"
#include "ui/kiosk_window.h"
#include "ui/picture_io.h"
#include "visit_view.h"

namespace {

using sas::kiosk::KioskEngine;

constexpr double kFs = 48000.0;
constexpr int kFrames = 128;

std::string Screen(const std::string& language, const std::string& key) {
  const toml::table table =
      toml::parse_file(std::string(sas::kSourceDir) + "/textures/strings/" + language + ".toml");
  return table["screen"][key].value_or(std::string("?"));
}

// The attract screen's invitation, one part a line, from the table file itself.
std::vector<std::string> Invitation(const std::string& language) {
  const toml::table table =
      toml::parse_file(std::string(sas::kSourceDir) + "/textures/strings/" + language + ".toml");
  std::vector<std::string> parts;
  for (const char* part : {"scratch", "rest", "roll", "token", "record", "language"}) {
    parts.push_back(table["invitation"][part].value_or(std::string("?")));
  }
  return parts;
}

// WCAG 2 relative luminance of an sRGB colour.
double Luminance(double r, double g, double b) {
  const auto lin = [](double c) {
    c /= 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  };
  return 0.2126 * lin(r) + 0.7152 * lin(g) + 0.0722 * lin(b);
}

// The lowest contrast of white text over `plate` composited on each pixel of `under` it.
double WorstPlateContrast(const sas::ui::ImageRgba& under, const sas::ui::PixelRect& plate) {
  const auto c = sas::app::kPlateColor;
  const double a = c.a / 255.0;
  double worst = 1e9;
  for (int y = std::max(0, plate.y); y < std::min(under.height(), plate.y + plate.h); ++y) {
    for (int x = std::max(0, plate.x); x < std::min(under.width(), plate.x + plate.w); ++x) {
      const auto p = under.at(x, y);
      const double l =
          Luminance(c.r * a + p.r * (1 - a), c.g * a + p.g * (1 - a), c.b * a + p.b * (1 - a));
      worst = std::min(worst, (1.0 + 0.05) / (l + 0.05));
    }
  }
  return worst;
}

struct Shot {
  std::string name;
  std::vector<std::string> texts;  // what the screen says
};

class Screens {
 public:
  Screens(int width, int height, const std::string& language = "en",
          const std::string& cues_dir = "/nonexistent")
      : width_(width),
        height_(height),
        mic_(sas::kiosk::RecorderConfigFor(Config())),
        engine_(Options(width, height, language, cues_dir)),
        view_(engine_, width, height) {
    engine_.SetRecorder(&mic_.recorder());
    mic_.Start();
    engine_.SetAudioRunning(true);
  }

  static sas::kiosk::KioskConfig Config() {
    sas::kiosk::KioskConfig config;
    config.record_max_duration_s = 3.0;
    return config;
  }
  static sas::kiosk::KioskEngineOptions Options(int width, int height, const std::string& language,
                                                const std::string& cues_dir) {
    sas::kiosk::KioskEngineOptions options;
    options.virtual_clock = true;
    options.cues_dir = cues_dir;
    options.screen_width_px = width;
    options.screen_height_px = height;
    options.config = Config();
    options.config.language = language;
    return options;
  }

  // Runs the engine and the view for `seconds`, feeding `voice` into the microphone while armed.
  void Run(double seconds, const std::vector<float>* voice = nullptr) {
    std::vector<float> out(kFrames * 2);
    for (double s = 0.0; s < seconds; s += kFrames / kFs) {
      view_.Apply(engine_.Tick(t_ns_), now_s());
      if (voice && mic_.recorder().Recording() && voice_pos_ < voice->size()) {
        const std::size_t n = std::min<std::size_t>(kFrames, voice->size() - voice_pos_);
        mic_.Feed(voice->data() + voice_pos_, n);
        voice_pos_ += n;
      }
      engine_.audio().Render(out.data(), kFrames, 2);
      t_ns_ += static_cast<std::int64_t>(kFrames / kFs * 1e9);
      view_.Advance(now_s(), false);
    }
  }

  void Pen(double x, double y, bool down) {
    sas::platform::PenReading pen;
    pen.time_ns = t_ns_;
    pen.x_px = x;
    pen.y_px = y;
    pen.pressure = down ? 0.8 : 0.0;
    pen.tip_down = down;
    engine_.OnPen(pen);
    view_.OnStylus(pen);
  }

  // Draws frames on this window instead of in software (the Xvfb run).
  void UseWindow(sas::ui::KioskWindow* window) { window_ = window; }

  // The frame's pixels: through the window when there is one (checked against the software
  // composition), else composed in software.
  sas::ui::ImageRgba Draw(const sas::ui::Frame& frame) {
    sas::ui::ImageRgba composed;
    sas::ui::ComposeFrame(frame, composed);
    if (window_ == nullptr) return composed;
    sas::ui::ImageRgba shown;
    window_->PollEvents();
    window_->Present(frame, &shown);
    REQUIRE(shown.width() == composed.width());
    double differences = 0.0;
    for (int y = 0; y < shown.height(); y += 3) {
      for (int x = 0; x < shown.width(); x += 3) {
        differences += std::abs(shown.at(x, y).r - composed.at(x, y).r) +
                       std::abs(shown.at(x, y).g - composed.at(x, y).g);
      }
    }
    const double mean = differences / (2.0 * (shown.height() / 3) * (shown.width() / 3));
    INFO("window against software composition, mean difference " << mean);
    CHECK(mean < 2.0);
    return shown;
  }

  // Composes the screen, checks what it says and its plates, and writes it when asked.
  void Check(const Shot& shot) {
    INFO(shot.name << " " << width_ << "x" << height_);
    view_.Advance(now_s(), false);
    const sas::ui::Frame& frame = view_.view().TakeFrame();
    std::vector<std::string> drawn;
    int tallest = 0;
    for (const auto& o : frame.overlays) {
      if (o.mask && !o.mask->text.empty()) {  // text; a shape's mask (the recording dot) has none
        drawn.push_back(o.mask->text);
        tallest = std::max(tallest, o.mask->h);
      }
    }
    // A long sentence wraps onto several lines: read the lines in drawing order.
    std::string said;
    for (const auto& line : drawn) said += line + " ";
    for (const auto& text : shot.texts) {
      INFO("expected on screen: " << text);
      CHECK(said.find(text + " ") != std::string::npos);
    }
    if (!shot.texts.empty()) {
      // The largest line follows the screen: at least 1/20 of its height (36 px at 720p).
      CHECK(tallest >= height_ / 20);
      REQUIRE_FALSE(view_.plates().empty());
    }
    sas::ui::Frame bare = frame;  // what is under the plates: the picture alone
    bare.overlays.clear();
    const sas::ui::ImageRgba under = Draw(bare);
    const sas::ui::ImageRgba composed = Draw(frame);
    for (const auto& plate : view_.plates()) CHECK(WorstPlateContrast(under, plate) >= 7.0);
    if (const char* dir = std::getenv("SAS_SCREENSHOTS_DIR"); dir != nullptr && *dir) {
      sas::ui::SaveJpeg(composed, std::string(dir) + "/" + shot.name + "-" +
                                      std::to_string(width_) + "x" + std::to_string(height_) +
                                      ".jpg");
    }
  }

  double now_s() const { return static_cast<double>(t_ns_) * 1e-9; }
  KioskEngine& engine() { return engine_; }
  sas::app::VisitView& view() { return view_; }
  int width_, height_;

 private:
  sas::platform::FakeAudioInput mic_;
  KioskEngine engine_;
  sas::app::VisitView view_;
  std::int64_t t_ns_ = 0;
  std::size_t voice_pos_ = 0;
  sas::ui::KioskWindow* window_ = nullptr;
};

void PlayScreens(Screens& screens) {
  const int w = screens.width_, h = screens.height_;
  REQUIRE(screens.view().text().Available());  // fonts-b612 (install/packages.txt)
  screens.Run(0.5);
  screens.Check({"attract", Invitation("en")});
  screens.engine().OnToken(static_cast<std::int64_t>(screens.now_s() * 1e9), 0);
  screens.Run(0.6);
  for (int i = 0; i < 30; ++i) {  // a stroke across the bubble wrap: the dent under the pen
    screens.Pen(w * (0.3 + 0.01 * i), h * 0.5, true);
    screens.Run(0.01);
  }
  // The visit's texture named on a banner as it is spoken (the token chose it).
  screens.Check({"exploring",
                 {toml::parse_file(std::string(sas::kSourceDir) +
                                   "/textures/bubble_wrap/texture.toml")["name"]
                      .value_or(std::string("?"))}});
  screens.Pen(w * 0.6, h * 0.5, false);
  screens.engine().OnRecordButton(static_cast<std::int64_t>(screens.now_s() * 1e9), true);
  screens.Run(0.05);
  screens.engine().OnRecordButton(static_cast<std::int64_t>(screens.now_s() * 1e9), false);
  screens.Run(2.6);  // the intro, then the count: "3" shows
  screens.Check({"countdown", {Screen("en", "countdown"), "3"}});
  const auto voice = sas::kiosk::SynthesiseVoice(kFs, 2.5);
  screens.Run(3.3, &voice);  // the tone, then 0.8 s into the take
  screens.Check(
      {"recording",
       {Screen("en", "recording_sign"), Screen("en", "recording"), Screen("en", "meter_good")}});
  screens.Run(3.0, &voice);  // the 3 s take ends: the voice is the surface
  REQUIRE(screens.engine().has_voice());
  screens.Check({"voice", {Screen("en", "voice_ready")}});
}

}  // namespace

TEST_CASE(
    "visitor screens say the language table's sentences on plates of at least 7 to 1 at "
    "1920x1080 and 1280x720",
    "[render]") {
  if (const char* window = std::getenv("SAS_SCREENS_WINDOW"); window != nullptr && *window) {
    sas::ui::KioskWindowOptions options;
    options.vsync = false;
    sas::ui::KioskWindow kiosk_window(options);
    kiosk_window.Open();
    INFO("driver " << kiosk_window.driver());
    REQUIRE(kiosk_window.driver() == "x11");
    Screens screens(kiosk_window.width_px(), kiosk_window.height_px());
    screens.UseWindow(&kiosk_window);
    PlayScreens(screens);
    return;
  }
  for (const auto& [w, h] : {std::pair{1920, 1080}, std::pair{1280, 720}}) {
    Screens screens(w, h);
    PlayScreens(screens);
  }
}

TEST_CASE("in German the visitor screens say the German table's sentences", "[render]") {
  Screens screens(1280, 720, "de");
  screens.Run(0.5);
  screens.Check({"attract-de", Invitation("de")});
  const auto now_ns = static_cast<std::int64_t>(screens.now_s() * 1e9);
  screens.engine().OnRecordButton(now_ns, true);
  screens.engine().OnRecordButton(now_ns + 1'000'000, false);
  screens.Run(2.6);
  screens.Check({"countdown-de", {Screen("de", "countdown"), "3"}});
}

// Not in the sanitizer build: a minute of frames there costs a minute of the suite, and the same
// engine path runs under the sanitizers in kiosk_tests (the blind visit's attract cycle).
#if defined(SAS_CUES_DIR) && !defined(__SANITIZE_ADDRESS__)
TEST_CASE(
    "with no key pressed the attract screen draws each visitor language's invitation in its "
    "turn, all five within a minute",
    "[render]") {
  // The shipped cues set the turns' lengths; the view draws what the engine's language says.
  Screens screens(1280, 720, "en", SAS_CUES_DIR);
  const auto& choices = screens.engine().config().visitor_languages;
  REQUIRE(choices.size() == 5);
  screens.Run(0.5);
  for (const auto& code : choices) {
    // The turn of `code`: its table on the screen (checked on the drawn text and its plates).
    while (screens.engine().language() != code && screens.now_s() < 60.0) screens.Run(0.25);
    INFO(code << " at " << screens.now_s() << " s");
    REQUIRE(screens.engine().language() == code);
    screens.Check({"attract-cycle-" + code, Invitation(code)});
  }
}
#endif

TEST_CASE("the meter's words follow the microphone level", "[render]") {
  CHECK(std::string(sas::app::MeterWordKey(0.001f)) == "meter_louder");  // -60 dBFS
  CHECK(std::string(sas::app::MeterWordKey(0.1f)) == "meter_good");      // -20 dBFS
  CHECK(std::string(sas::app::MeterWordKey(0.9f)) == "meter_too_loud");  // -0.9 dBFS
}
