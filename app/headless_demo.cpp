// The headless default: a scripted visit through the kiosk engine (see headless_demo.h).
#include "headless_demo.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <span>

#include "calibration/population_levels.h"
#include "calibration/texture_levels.h"
#include "kiosk/data_dirs.h"
#include "kiosk/kiosk_engine.h"
#include "kiosk/synthetic_voice.h"
#include "kiosk/virtual_visit.h"
#include "sas/version.h"
#include "surface/loudness.h"
#include "surface/wav_writer.h"
#include "ui/picture_io.h"
#include "visit_view.h"

namespace sas::app {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = 3.14159265358979;

class Visit {
 public:
  Visit(const HeadlessOptions& options, std::FILE* out)
      : options_(options),
        out_(out),
        mic_(kiosk::RecorderConfigFor(kiosk::KioskConfig{})),
        engine_(EngineOptions(options)),
        view_(engine_, options.width_px, options.height_px),
        driver_(engine_, MakeHooks()) {
    engine_.SetRecorder(&mic_.recorder());
    // Every cue the visit hears, for visit.txt (a curator's texture must say its own name).
    engine_.SetCueObserver([this](const kiosk::CueEvent& cue) {
      heard_ += "cue " + cue.language + " " + cue.key + " t=" +
                std::to_string(static_cast<double>(cue.time_ns) * 1e-9) + " text=" + cue.text +
                "\n";
    });
    mic_.Start();
    driver_.SetMicrophone(&mic_);
  }

  static kiosk::KioskEngineOptions EngineOptions(const HeadlessOptions& options) {
    kiosk::KioskEngineOptions engine;
    // The visit ends with an idle reset; no pause before it may reach the timeout, and the
    // longest is the wait for the 4 s "now scratch your voice" banner to go before the voice's
    // stroke (a 2 s quick timeout wiped the voice there).
    engine.config.idle_timeout_s = options.quick ? 5.0 : 6.0;
    engine.countdown_s = options.quick ? 1.0 : 3.0;
    // The scripted visit plays the shipped cues, whatever a box's staff recorded: the same visit
    // and the same files on every machine.
    engine.config.staff_dir.clear();
    if (!options.config_path.empty()) {
      // A kiosk's token choices and its staff's textures (a curator's new texture on its token),
      // still with the shipped voice for everything else.
      const kiosk::KioskConfig box = kiosk::LoadKioskConfig(options.config_path);
      engine.config.token_textures = box.token_textures;
      engine.config.staff_dir = box.staff_dir;
      engine.staff_cues = false;
    }
    engine.screen_width_px = options.width_px;
    engine.screen_height_px = options.height_px;
    engine.virtual_clock = true;
    if (!options.texture_paths.empty()) engine.texture_paths = options.texture_paths;
    return engine;
  }

  double now_s() const { return driver_.now_s(); }
  std::size_t frames_rendered() const { return driver_.frames_kept(); }

  // Runs `seconds` of the visit (kiosk/virtual_visit.h); the view sees every pen sample, the
  // engine's actions and a frame per block, as the live kiosk's window does.
  void Run(double seconds, const kiosk::PenScript& pen = {}) { driver_.Advance(seconds, pen); }

  // One stroke with the pen, then the pen lifted for the tail. Writes <name>.wav and a snapshot
  // <name>.png at the end of the stroke (tip still down). Returns the visit.txt line.
  std::string DoStroke(const std::string& name, kiosk::PenStroke stroke,
                       const std::function<void(double)>& midway = {}, double stroke_s = 0.0) {
    stroke.duration_s = stroke_s > 0.0 ? stroke_s : options_.stroke_s();
    const double kStrokeS = stroke.duration_s;
    const double kTailS = options_.tail_s();
    const std::size_t first = frames_rendered();
    const double w = options_.width_px, h = options_.height_px;
    bool midway_done = false;
    const auto pen = kiosk::StraightStroke(stroke, now_s(), options_.width_px, options_.height_px);
    Run(stroke.hover_s + kStrokeS * 0.5, pen);  // the hover, then half the stroke
    if (midway) {
      midway(now_s());
      midway_done = true;
    }
    Run(kStrokeS * 0.5 - 0.02, pen);  // the snapshot while the tip is still down and moving
    view_.Advance(now_s(), false);
    ui::ImageRgba frame;
    ui::ComposeFrame(view_.view().TakeFrame(), frame);
    const std::string png = name + ".png";
    ui::SavePng(frame, (fs::path(options_.out_dir) / png).string());
    const double x_end = stroke.x1 * w, y_end = stroke.y1 * h;
    Run(0.02 + 0.1, pen);  // lifted
    Run(kTailS - 0.1);
    const std::size_t last = frames_rendered();
    {  // The whole stroke's level, from its landing to just after its lift (one buffer's delay),
       // as the visitor population is measured (texture_levels.h, whole_strokes).
      const double fs = driver_.sample_rate_hz();
      const double delay_s = driver_.block_frames() / fs + stroke.hover_s;
      const auto from = first + static_cast<std::size_t>(std::llround(delay_s * fs));
      const auto to = first + static_cast<std::size_t>(std::llround(
                                  (delay_s + kStrokeS + kiosk::kGapAfterLiftS) * fs));
      const std::span<const float> all(driver_.output());
      levels_[name] = {surface::KWeightedLoudnessDb(all, fs, from, to, 2),
                       surface::RmsDb(all.subspan(1), from, to, 2)};
    }
    const std::string wav = name + ".wav";
    surface::WriteWav((fs::path(options_.out_dir) / wav).string(),
                      driver_.output().data() + first * 2, last - first, 2,
                      static_cast<int>(driver_.sample_rate_hz()));
    char line[512];
    std::snprintf(line, sizeof line,
                  "stroke %s wav=%s png=%s plain=%s x=%.0f y=%.0f down_s=%.3f tail_s=%.3f%s\n",
                  name.c_str(), wav.c_str(), png.c_str(), plain_.c_str(), x_end, y_end, kStrokeS,
                  kTailS, midway_done ? " token_switch=mid" : "");
    if (!options_.quiet)
      std::fprintf(out_, "  %-28s %s, %s\n", name.c_str(), wav.c_str(), png.c_str());
    return line;
  }

  // The undeformed picture now on screen, as <name>.png (the reference for the snapshots).
  void SavePlain(const std::string& name) {
    view_.Advance(now_s(), false);
    plain_ = name + ".png";
    ui::SavePng(*view_.current_picture(), (fs::path(options_.out_dir) / plain_).string());
  }

  void SetPlain(const std::string& name) { plain_ = name + ".png"; }
  // Puts the token of textures()[texture] on its switch. Tokens are switches in the four textures'
  // order; with a texture left out, texture index and switch number differ.
  void Token(int texture) {
    engine_.OnToken(driver_.now_ns(), engine_.TokenForTexture(static_cast<std::size_t>(texture)));
  }
  void RecordButton(bool pressed) { engine_.OnRecordButton(driver_.now_ns(), pressed); }
  void SetVoice(std::vector<float> voice) { driver_.SetVoice(std::move(voice)); }
  kiosk::KioskEngine& engine() { return engine_; }
  VisitView& view() { return view_; }
  std::size_t voice_left() const { return driver_.voice_left(); }
  void ClearAudio() { driver_.ClearOutput(); }
  // Loudness (LUFS, ch 1) and vibration strength (dB RMS, ch 2) of each stroke so far, by name.
  const std::map<std::string, std::pair<double, double>>& levels() const { return levels_; }
  // visit.txt's "cue <language> <key> t=<s> text=<sentence>" lines of the cues heard so far.
  const std::string& heard() const { return heard_; }

 private:
  kiosk::VirtualVisit::Hooks MakeHooks() {
    kiosk::VirtualVisit::Hooks hooks;
    hooks.on_pen = [this](const platform::PenReading& pen) { view_.OnStylus(pen); };
    hooks.on_tick = [this](std::vector<kiosk::SessionAction> actions) {
      view_.Apply(actions, now_s());
    };
    hooks.before_render = [this] { view_.Advance(now_s(), false); };
    return hooks;
  }

  HeadlessOptions options_;
  std::FILE* out_;
  platform::FakeAudioInput mic_;  // before the engine: it holds a pointer to the recorder
  kiosk::KioskEngine engine_;
  VisitView view_;
  kiosk::VirtualVisit driver_;  // the audio loop on the virtual clock (after engine and view)
  std::string plain_;
  std::map<std::string, std::pair<double, double>> levels_;
  std::string heard_;
};

// The visit's strokes: every style on every texture, three times each (kDirections).
struct StrokeStyle {
  const char* name;
  double tilt_deg;
  std::optional<synth::ProbeStyle> style;
};
constexpr StrokeStyle kStyles[] = {{"scrape", 0.0, synth::ProbeStyle::kScrape},
                                   {"rub", 55.0, synth::ProbeStyle::kRub},
                                   {"roll", 0.0, synth::ProbeStyle::kRoll}};
// A stroke along the screen, then two crossing it at its middle, rising and falling at 35°. One
// straight line is not a texture's typical stroke (along the wooden board's grain a stroke barely
// catches, ~15 dB under one across it), and the visit compares the textures, not one line on each.
struct StrokeDirection {
  const char* suffix;
  double angle_deg;  // the crossing strokes' angle, 600 px long; 0: the stroke along
};
constexpr StrokeDirection kDirections[] = {{"", 0.0}, {"_rising", 35.0}, {"_falling", -35.0}};

// Each texture chosen by its token, then stroked in every style and direction; visit.txt lines.
std::string StrokeEveryStyle(Visit& visit, const HeadlessOptions& options) {
  std::string report;
  const auto& textures = visit.engine().textures();
  for (std::size_t t = 0; t < textures.size(); ++t) {
    visit.Token(static_cast<int>(t));  // a token on switch t: name cue, cross-fade
    visit.Run(0.6);
    visit.SavePlain(textures[t].key);
    int row = 0;
    for (const auto& style : kStyles) {
      for (const auto& direction : kDirections) {
        // 0.55 pressure: 1.1 N on the synth, 2.2 N on a bubble (below its 2.5 N pop force) so
        // each style is heard on intact bubbles; popping comes next.
        kiosk::PenStroke stroke{0.2, 0.3 + 0.2 * row, 0.75, 0.35 + 0.2 * row, 0.0, 0.55, 0.0, {}};
        if (direction.angle_deg != 0.0) {
          const double angle = direction.angle_deg * kPi / 180.0;
          const double half_x = 300.0 * std::cos(angle) / options.width_px;
          const double half_y = 300.0 * std::sin(angle) / options.height_px;
          const double cx = 0.5 * (stroke.x0 + stroke.x1), cy = 0.5 * (stroke.y0 + stroke.y1);
          stroke.x0 = cx - half_x;
          stroke.y0 = cy + half_y;
          stroke.x1 = cx + half_x;
          stroke.y1 = cy - half_y;
        }
        stroke.tilt_deg = style.tilt_deg;
        stroke.style = style.style;
        stroke.hover_s = 0.04;  // the hand comes in moving (the per-stroke gain knows its speed)
        report += visit.DoStroke(textures[t].key + "_" + style.name + direction.suffix, stroke);
      }
      ++row;
    }
  }
  return report;
}

// The same strokes on every texture: how far apart their levels are (levels/stroke_gain.h), each
// texture's level the power mean of a style's strokes. Printed; returns the visit.txt lines.
std::string PrintSpreads(Visit& visit, std::FILE* out) {
  std::string report;
  const auto& textures = visit.engine().textures();
  for (const auto& style : kStyles) {
    double lo[2] = {1e9, 1e9}, hi[2] = {-1e9, -1e9};
    std::string each;
    for (const auto& texture : textures) {
      double power[2] = {0.0, 0.0};
      int found = 0;
      for (const auto& direction : kDirections) {
        const auto it = visit.levels().find(texture.key + "_" + style.name + direction.suffix);
        if (it == visit.levels().end()) continue;
        power[0] += std::pow(10.0, it->second.first / 10.0);
        power[1] += std::pow(10.0, it->second.second / 10.0);
        ++found;
      }
      if (found == 0) continue;
      const double level[2] = {10.0 * std::log10(power[0] / found),
                               10.0 * std::log10(power[1] / found)};
      char text[96];
      std::snprintf(text, sizeof text, "%s%s %.1f/%.1f", each.empty() ? "" : ", ",
                    texture.key.c_str(), level[0], level[1]);
      each += text;
      for (int c = 0; c < 2; ++c) {
        lo[c] = std::min(lo[c], level[c]);
        hi[c] = std::max(hi[c], level[c]);
      }
    }
    std::fprintf(out,
                 "  the same %s strokes on the %zu textures: loudness within %.1f LU, "
                 "vibration within %.1f dB (LUFS/dB RMS: %s)\n",
                 style.name, textures.size(), hi[0] - lo[0], hi[1] - lo[1], each.c_str());
    char line[128];
    std::snprintf(line, sizeof line, "spread %s loudness_lu=%.2f vibration_db=%.2f\n", style.name,
                  hi[0] - lo[0], hi[1] - lo[1]);
    report += line;
  }
  return report;
}

}  // namespace

// The level matching judged as the tests judge it (calibration/population_levels.h): the visitor
// population played on the textures this visit loaded, at the kiosk's default gains (~15 s).
static void PrintPopulation(std::FILE* out, const kiosk::KioskEngine& engine, bool quick) {
  if (quick) {
    std::fprintf(out,
                 "  visitor population: left out of the quick visit "
                 "(docs/population-levels.md has its figures)\n");
    return;
  }
  std::vector<std::string> paths;
  for (const auto& path : kiosk::FindTextureFiles()) {
    const std::string key = fs::path(path).parent_path().filename().string();
    for (const auto& texture : engine.textures()) {
      if (texture.key == key) paths.push_back(path);
    }
  }
  if (paths.size() < 2) {
    std::fprintf(out, "  visitor population: left out (it compares two textures or more)\n");
    return;
  }
  const kiosk::KioskConfig defaults;
  const int count = 200;
  const unsigned seed = 2026;
  const auto strokes = kiosk::VisitorPopulation(count, seed);
  std::vector<kiosk::PopulationLevels> rows;
  for (std::size_t t = 0; t < paths.size(); ++t) {
    rows.push_back(kiosk::MeasurePopulation(paths, t, strokes, defaults));
  }
  const auto targets = kiosk::CheckPopulationTargets(rows, defaults.haptic_ceiling_db);
  std::fprintf(out,
               "  visitor population (%d strokes, seed %u, the default gains), per texture: median "
               "loudness (against the mean of the medians), its 5-95 %% spread, the loudest stroke "
               "over the median, median vibration, and the medians of scrape / rub / roll:\n",
               count, seed);
  for (const auto& r : rows) {
    const auto style = [&](const char* k) {
      return r.per_style.count(k) ? r.per_style.at(k).first : 0.0;
    };
    std::fprintf(out,
                 "    %-15s %.1f LUFS (%+.1f LU), %.1f to %.1f, loudest +%.1f LU; vibration "
                 "%.1f dB (%+.1f); %.1f / %.1f / %.1f LUFS\n",
                 (r.name + ":").c_str(), r.sound_median, r.sound_median - targets.mean_sound,
                 r.sound_p5, r.sound_p95, r.sound_max - r.sound_median, r.haptic_median,
                 r.haptic_median - targets.mean_haptic, style("scrape"), style("rub"),
                 style("roll"));
  }
  std::fprintf(out, "    targets: %s\n",
               kiosk::DescribeTargets(targets, defaults.haptic_ceiling_db).c_str());
}

// A step of the visit that needs a texture which did not load: said on the console and in
// visit.txt, so a shorter visit is never mistaken for the whole one.
static void Skipped(std::FILE* out, std::string* report, const std::string& what) {
  std::fprintf(out, "  skipped: %s\n", what.c_str());
  *report += "skipped " + what + "\n";
}

// Bubble wrap again: a firm press on one bubble pops it (a burst of sound, a flat patch).
static std::string PopBubble(Visit& visit, const HeadlessOptions& options, std::FILE* out) {
  std::string report;
  const auto& textures = visit.engine().textures();
  int bubble_texture = -1;
  for (std::size_t t = 0; t < textures.size(); ++t) {
    if (textures[t].loaded.bubbles) bubble_texture = static_cast<int>(t);
  }
  if (bubble_texture < 0) Skipped(out, &report, "the bubble pop (no bubble wrap loaded)");
  if (bubble_texture >= 0) {
    visit.Token(bubble_texture);
    visit.Run(0.6);
    visit.SavePlain(textures[static_cast<std::size_t>(bubble_texture)].key + "_intact");
    const auto* state = visit.engine().bubbles();
    // The bubble nearest the screen's centre, in screen pixels.
    double best = 1e18, bx = 0.0, by = 0.0;
    for (const auto& [fx, fy] : state->centres()) {
      double sx = 0.0, sy = 0.0;
      visit.engine().FieldToScreen(fx, fy, &sx, &sy);
      const double d = std::hypot(sx - options.width_px / 2.0, sy - options.height_px / 2.0);
      if (d < best) {
        best = d;
        bx = sx;
        by = sy;
      }
    }
    const double fx0 = bx / options.width_px, fy0 = by / options.height_px;
    report +=
        visit.DoStroke("bubble_wrap_pop", {fx0, fy0, fx0 + 0.002, fy0, 0.0, 1.0, 0.0, {}}, {}, 0.3);
    report += "pop popped=" + std::to_string(visit.engine().popped_bubbles()) +
              " x=" + std::to_string(static_cast<int>(bx)) +
              " y=" + std::to_string(static_cast<int>(by)) + "\n";
    visit.SavePlain(textures[static_cast<std::size_t>(bubble_texture)].key + "_popped");
  }
  return report;
}

void AddHeadlessOptions(CLI::App& app, HeadlessOptions& options) {
  app.add_option("--out", options.out_dir,
                 "folder for the visit's WAVs, PNGs and visit.txt (default sketch-a-scratch-demo)")
      ->check([](const std::string& dir) { return dir.empty() ? "needs a folder" : ""; });
  app.add_flag("--quick", options.quick,
               "shorter strokes, countdown and idle timeout (the sanitizer build's test)");
}

int RunHeadlessDemo(const HeadlessOptions& options, std::FILE* out, std::FILE* err) {
  try {
    std::error_code error;
    fs::create_directories(options.out_dir, error);
    if (error) {
      std::fprintf(err, "sketch-a-scratch: cannot create %s: %s\n", options.out_dir.c_str(),
                   error.message().c_str());
      return 1;
    }
    const std::string out_dir = fs::absolute(options.out_dir).string();
    std::fprintf(out, "Headless default: a scripted visit (no display), writing to %s\n",
                 out_dir.c_str());
    Visit visit(options, out);
    std::string report = "# sketch-a-scratch " + std::string(kVersion) +
                         " headless visit: one line per stroke (screen " +
                         std::to_string(options.width_px) + "x" +
                         std::to_string(options.height_px) + " px)\n";
    // A texture that does not load is left out by the engine; the visit goes on with the rest.
    for (const auto& failure : visit.engine().texture_failures()) {
      Skipped(out, &report, "texture " + failure);
    }
    report += StrokeEveryStyle(visit, options);
    if (!options.quiet) {
      report += PrintSpreads(visit, out);
      PrintPopulation(out, visit.engine(), options.quick);
    }
    report += PopBubble(visit, options, out);
    const auto& textures = visit.engine().textures();

    // A token switch in the middle of a stroke: the sound cross-fades, the picture too. With all
    // four textures, from the third to the second; it needs two.
    if (textures.size() >= 2) {
      const int before = static_cast<int>(std::min<std::size_t>(2, textures.size() - 1));
      const int after = before - 1;
      visit.Token(before);
      visit.Run(0.6);
      visit.SavePlain("token_switch_before");
      report += visit.DoStroke(
          "token_switch", {0.2, 0.5, 0.8, 0.5, 0.0, 0.7, 0.0, {}},
          [&](double) {
            visit.Token(after);
            visit.SetPlain(textures[static_cast<std::size_t>(after)].key);  // shown after
          },
          1.2);  // long enough for the 0.45 s fade to end before the snapshot
    } else {
      Skipped(out, &report, "the token switch in mid-stroke (it needs two textures)");
    }

    // The voice: record button, countdown, 2.4 s of "speech", a second press ends the take early.
    visit.SetVoice(kiosk::SynthesiseVoice(visit.engine().config().sample_rate_hz, 2.4, 120.0));
    visit.RecordButton(true);
    visit.Run(0.1);
    visit.RecordButton(false);
    visit.Run(options.quick ? 1.2 : 3.2);  // the countdown, then the recorder is armed
    while (visit.voice_left() > 0 &&
           visit.engine().session().mode() == kiosk::SessionMode::kRecording) {
      visit.Run(0.1);
    }
    visit.RecordButton(true);
    visit.Run(0.05);
    visit.RecordButton(false);
    visit.Run(0.6);
    if (!visit.engine().has_voice()) {
      std::fprintf(err, "sketch-a-scratch: the voice recording did not become a surface (%s)\n",
                   visit.view().message().c_str());
      return 1;
    }
    visit.SavePlain("voice_surface");
    visit.Run(4.1);  // the "now scratch your voice" banner has gone: the snapshot shows the dent
    report += visit.DoStroke("voice_scrape", {0.15, 0.4, 0.85, 0.45, 0.0, 0.7, 0.0, {}});

    // Nobody touches it: the idle reset wipes the voice and shows the default texture.
    visit.ClearAudio();
    visit.Run(visit.engine().config().idle_timeout_s + 0.5);
    const bool wiped = !visit.engine().has_voice() && visit.engine().voice_image() == nullptr;
    report += std::string("idle_reset voice_wiped=") + (wiped ? "yes" : "no") +
              " attract=" + (visit.view().attract() ? "yes" : "no") + "\n";
    visit.SavePlain("idle_reset");
    report += visit.heard();
    {
      std::FILE* file = std::fopen((fs::path(out_dir) / "visit.txt").c_str(), "w");
      if (file == nullptr) {
        std::fprintf(err, "sketch-a-scratch: cannot write visit.txt in %s\n", out_dir.c_str());
        return 1;
      }
      std::fputs(report.c_str(), file);
      std::fclose(file);
    }
    if (!wiped) {
      std::fprintf(err, "sketch-a-scratch: the idle reset did not wipe the voice\n");
      return 1;
    }
    const auto stats = visit.engine().audio_stats();
    std::fprintf(out,
                 "Done: %llu probe commands, %llu scene switches, pen-to-sound delay %.2f ms "
                 "(one %d-frame buffer). Listen to the WAVs (ch 1 sound, ch 2 vibration) and look "
                 "at the PNGs in %s (visit.txt lists them).\n",
                 static_cast<unsigned long long>(stats.commands),
                 static_cast<unsigned long long>(stats.switches),
                 static_cast<double>(stats.pen_to_sample_max_ns) * 1e-6,
                 visit.engine().config().buffer_frames, out_dir.c_str());
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(err, "sketch-a-scratch: headless visit failed: %s\n", error.what());
    return 1;
  }
}

int RunTexturePreview(const std::string& texture_toml, const std::string& out_dir, std::FILE* out,
                      std::FILE* err) {
  try {
    HeadlessOptions options;
    options.out_dir = out_dir;
    options.texture_paths = {texture_toml};
    // The others as the kiosk holds them: the per-stroke matching refers to their levels.
    for (const auto& path : kiosk::FindTextureFiles()) {
      if (fs::path(path).parent_path().filename() != fs::path(texture_toml).parent_path().filename())
        options.texture_paths.push_back(path);
    }
    fs::create_directories(out_dir);
    Visit visit(options, out);
    if (!visit.engine().texture_failures().empty() ||
        visit.engine().textures().front().key !=
            fs::path(texture_toml).parent_path().filename().string()) {
      std::fprintf(err, "sketch-a-scratch texture preview: %s does not load\n",
                   texture_toml.c_str());
      return 1;
    }
    const std::string key = visit.engine().textures().front().key;
    visit.Token(0);
    visit.Run(0.6);
    visit.SavePlain(key);
    std::string report = "# sketch-a-scratch " + std::string(kVersion) + " preview of " +
                         texture_toml + ": one line per stroke\n";
    int row = 0;
    for (const auto& style : kStyles) {
      kiosk::PenStroke stroke{0.2, 0.3 + 0.2 * row, 0.75, 0.35 + 0.2 * row, 0.0, 0.55, 0.0, {}};
      stroke.tilt_deg = style.tilt_deg;
      stroke.style = style.style;
      stroke.hover_s = 0.04;
      const std::string name = key + "_" + style.name;
      std::string line = visit.DoStroke(name, stroke);
      const auto level = visit.levels().at(name);
      char figures[96];
      std::snprintf(figures, sizeof figures, " loudness_lufs=%.1f vibration_db=%.1f", level.first,
                    level.second);
      line.insert(line.size() - 1, figures);
      report += line;
      ++row;
    }
    report += visit.heard();
    std::FILE* file = std::fopen((fs::path(out_dir) / "preview.txt").c_str(), "w");
    if (file == nullptr) {
      std::fprintf(err, "sketch-a-scratch texture preview: cannot write preview.txt in %s\n",
                   out_dir.c_str());
      return 1;
    }
    std::fputs(report.c_str(), file);
    std::fclose(file);
    std::fprintf(out, "Preview of %s in %s (preview.txt lists the WAVs and PNGs)\n", key.c_str(),
                 fs::absolute(out_dir).c_str());
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(err, "sketch-a-scratch texture preview: %s\n", error.what());
    return 1;
  }
}

}  // namespace sas::app
