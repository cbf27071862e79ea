// Soak run: an accelerated simulated day of random visitors through the
// real KioskEngine on its virtual clock, with the platform's audio callback core in place of the
// sound card (every 128-frame block of the day is rendered, idle time included: the engine's own
// idle path, nothing skipped) and the fake microphone fed synthesised speech.
//
// Visitors arrive after an idle gap longer than the idle timeout (so each gap ends in the engine's
// idle reset: the texture of the token left on a switch or the default one, bubbles un-popped,
// voice wiped, attract screen). Half of them take their token with them. Each visit is a
// random sequence of strokes in every style (scrape: pen upright, rub: tilted, roll), token
// switches (also mid-stroke), firm presses that pop bubbles, and voice recordings (speech-like
// signals of random pitch and length; some silent takes the kiosk must refuse), with pauses.
//
// Checked: zero NaN/Inf samples in the output, resident memory (/proc/self/statm) growth below
// 1 MB from the end of the warm-up to the end, the usage counters equal to what the visitors did
// and identical after a save and reload, the idle reset after every visit. Prints RSS over time.
//
//   kiosk_soak [--simulated-hours H (8)] [--max-wall-seconds S (0 = none)] [--seed N]
//              [--warmup-hours W (min(1, H/4))] [--rss-limit-kb K (1024; 0 = not checked)]
//              [--docs DIR (also write the summary and the checks to DIR/soak.md)]
// Exit 0 when every check held (a run cut short by --max-wall-seconds says so and checks what it
// ran), 1 otherwise, 2 on a usage error.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "files/counters_file.h"
#include "kiosk/kiosk_control.h"
#include "kiosk/kiosk_engine.h"
#include "kiosk/synthetic_voice.h"
#include "kiosk/virtual_visit.h"
#include "platform/audio/audio_input.h"
#include "platform/log/log.h"
#include "tools/command_line.h"

namespace {

namespace fs = std::filesystem;
using sas::kiosk::KioskEngine;

constexpr int kWidthPx = 1920;
constexpr int kHeightPx = 1080;
constexpr double kPenRateHz = 200.0;

long ResidentKb() {
  std::FILE* file = std::fopen("/proc/self/statm", "r");
  if (file == nullptr) return -1;
  long size = 0, resident = 0;
  const int n = std::fscanf(file, "%ld %ld", &size, &resident);
  std::fclose(file);
  return n == 2 ? resident * (sysconf(_SC_PAGESIZE) / 1024) : -1;
}

struct Options {
  double simulated_hours = 8.0;
  double max_wall_s = 0.0;
  double warmup_hours = -1.0;
  long rss_limit_kb = 1024;  // 0: not checked (sanitizer builds: ASan's quarantine keeps memory)
  unsigned seed = 20261123;
  std::string docs_dir;  // empty: the report goes to stdout only
};

class Day {
 public:
  explicit Day(const Options& options, const std::string& state_dir)
      : options_(options),
        rng_(options.seed),
        mic_(sas::kiosk::RecorderConfigFor(sas::kiosk::KioskConfig{})),
        engine_(EngineOptions(state_dir)),
        driver_(engine_, MakeHooks(), /*keep_output=*/false) {
    engine_.SetRecorder(&mic_.recorder());
    mic_.Start();
    driver_.SetMicrophone(&mic_);
    expected_strokes_.assign(engine_.textures().size(), 0);
    wall_start_ = std::chrono::steady_clock::now();
    warmup_s_ = options_.warmup_hours >= 0.0
                    ? options_.warmup_hours * 3600.0
                    : std::min(1.0, options_.simulated_hours / 4.0) * 3600.0;
  }

  bool Run() {
    const double end_s = options_.simulated_hours * 3600.0;
    std::printf("sim_h  wall_s  rss_kb  visitors  strokes  recordings  pops  nan\n");
    Sample();
    while (now_s() < end_s && !out_of_time_) {
      // Nobody there: longer than the idle timeout, so the engine's idle reset runs.
      const double idle_timeout_s = engine_.config().idle_timeout_s;
      Idle(Uniform(idle_timeout_s + 5.0, idle_timeout_s + 150.0));
      if (out_of_time_ || now_s() >= end_s) break;
      CheckIdleReset();
      Visit();
    }
    return Report();
  }

 private:
  static sas::kiosk::KioskEngineOptions EngineOptions(const std::string& state_dir) {
    sas::kiosk::KioskEngineOptions engine;
    engine.virtual_clock = true;
    engine.screen_width_px = kWidthPx;
    engine.screen_height_px = kHeightPx;
    engine.counters_path = (fs::path(state_dir) / "counters.toml").string();
    return engine;  // the shipped defaults otherwise: 60 s idle timeout, cues if built
  }

  double now_s() const { return driver_.now_s(); }
  double Uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }
  int Pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }

  // Each rendered block (kiosk/virtual_visit.h runs the engine as the headless visit does: pen
  // samples, tick, microphone, one 128-frame device block): NaN count, the minute's memory sample
  // and the wall-clock limit.
  sas::kiosk::VirtualVisit::Hooks MakeHooks() {
    sas::kiosk::VirtualVisit::Hooks hooks;
    hooks.on_block = [this](std::span<const float> block) {
      for (const float s : block) {
        if (!std::isfinite(s)) ++nan_;
      }
      if (now_s() >= next_sample_s_) Sample();
      if (options_.max_wall_s > 0.0 && ++blocks_since_clock_ >= 1024) {  // every 2.7 s simulated
        blocks_since_clock_ = 0;
        if (std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count() >
            options_.max_wall_s) {
          out_of_time_ = true;
        }
      }
    };
    return hooks;
  }

  void Advance(double seconds, const sas::kiosk::PenScript& pen = {}) {
    driver_.Advance(seconds, pen);
  }

  void Idle(double seconds) {
    // In pieces, so the wall-clock limit is honoured during long gaps too.
    while (seconds > 0.0 && !out_of_time_) {
      const double piece = std::min(seconds, 10.0);
      Advance(piece);
      seconds -= piece;
    }
  }

  void Sample() {
    const long rss = ResidentKb();
    const double wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count();
    if (rss_start_kb_ < 0) rss_start_kb_ = rss;
    rss_max_kb_ = std::max(rss_max_kb_, rss);
    rss_end_kb_ = rss;
    if (now_s() >= next_print_s_) {
      std::printf("%5.2f  %6.0f  %6ld  %8d  %7d  %10d  %4d  %3ld\n", now_s() / 3600.0, wall_s, rss,
                  visitors_, strokes_, good_recordings_ + failed_recordings_, pops_, nan_);
      std::fflush(stdout);
      next_print_s_ += options_.simulated_hours > 1.0 ? 1800.0 : 300.0;
    }
    next_sample_s_ += 60.0;
    if (options_.max_wall_s > 0.0 && wall_s > options_.max_wall_s) out_of_time_ = true;
  }

  // Memory is compared at the same point of every cycle: the kiosk idle on its attract screen
  // with no token on a switch (the default texture), just before the next visitor (between
  // visits the heap's high-water mark from a recording or a scene switch comes and goes with
  // glibc's trimming; a leak shows up here as a rising floor). An idle screen showing a token's
  // bubble wrap holds that texture's own poppable copy of its field, so it is not compared.
  void SampleIdle() {
    if (token_on_switch_ >= 0) return;
    const long rss = ResidentKb();
    if (now_s() < warmup_s_ || rss_warm_kb_ < 0) {
      rss_warm_kb_ = rss;
      if (now_s() < warmup_s_) return;
    }
    rss_idle_last_kb_ = rss;
    rss_after_warm_max_kb_ = std::max(rss_after_warm_max_kb_, rss);
    ++idle_samples_after_warmup_;
  }

  void CheckIdleReset() {
    SampleIdle();
    // The texture of the token still on a switch, else the default one.
    int expected = engine_.default_texture();
    for (std::size_t t = 0; t < engine_.textures().size(); ++t) {
      if (token_on_switch_ >= 0 && engine_.TokenForTexture(t) == token_on_switch_) {
        expected = static_cast<int>(t);
      }
    }
    if (engine_.session().mode() != sas::kiosk::SessionMode::kAttract || engine_.has_voice() ||
        engine_.popped_bubbles() != 0 || engine_.surface().texture != expected ||
        engine_.surface().voice) {
      ++idle_reset_failures_;
    }
    ++idle_resets_;
  }

  // One stroke from (x0, y0) to (x1, y1) (screen fractions); `midway` runs half-way through.
  void Stroke(double x0, double y0, double x1, double y1, double duration_s, double pressure,
              double tilt_deg, std::optional<sas::synth::ProbeStyle> style,
              const std::function<void()>& midway = {}) {
    const auto surface = engine_.surface();  // what the session counts the stroke on
    if (surface.voice) {
      ++expected_voice_strokes_;
    } else {
      ++expected_strokes_[static_cast<std::size_t>(surface.texture)];
    }
    ++strokes_;
    const auto pen = sas::kiosk::StraightStroke(
        {x0, y0, x1, y1, duration_s, pressure, tilt_deg, style}, now_s(), kWidthPx, kHeightPx);
    Advance(duration_s * 0.5, pen);
    if (midway) midway();
    Advance(duration_s * 0.5 + 0.05, pen);  // and the lift
  }

  void RandomStroke() {
    const double x0 = Uniform(0.05, 0.95), y0 = Uniform(0.05, 0.95);
    const double x1 = std::clamp(x0 + Uniform(-0.4, 0.4), 0.0, 1.0);
    const double y1 = std::clamp(y0 + Uniform(-0.3, 0.3), 0.0, 1.0);
    const int style = Pick(3);
    const double tilt = style == 1 ? Uniform(45.0, 60.0) : Uniform(0.0, 15.0);
    const auto forced = style == 2 ? std::optional(sas::synth::ProbeStyle::kRoll)
                                   : std::optional<sas::synth::ProbeStyle>();
    std::function<void()> midway;
    if (Pick(8) == 0) midway = [this] { Token(Pick(5) - 1); };  // a token switch mid-stroke
    Stroke(x0, y0, x1, y1, Uniform(0.3, 2.5), Uniform(0.25, 0.9), tilt, forced, midway);
  }

  void Token(int token) {
    token_on_switch_ = token;
    engine_.OnToken(driver_.now_ns(), token);
  }

  void PopBubble() {
    int bubble_token = -1;
    for (std::size_t t = 0; t < engine_.textures().size(); ++t) {
      if (engine_.textures()[t].loaded.bubbles) bubble_token = static_cast<int>(t);
    }
    if (bubble_token < 0) return;
    Token(bubble_token);
    Advance(0.6);
    const auto* state = engine_.bubbles();
    if (state == nullptr || state->centres().empty()) return;
    const auto& centre =
        state->centres()[static_cast<std::size_t>(Pick(static_cast<int>(state->centres().size())))];
    double sx = 0.0, sy = 0.0;
    engine_.FieldToScreen(centre.first, centre.second, &sx, &sy);
    if (sx < 0 || sy < 0 || sx >= kWidthPx || sy >= kHeightPx) return;
    const int before = engine_.popped_bubbles();
    Stroke(sx / kWidthPx, sy / kHeightPx, sx / kWidthPx + 0.002, sy / kHeightPx, 0.3, 1.0, 0.0, {});
    pops_ += engine_.popped_bubbles() - before;
  }

  void Record() {
    const bool silent = Pick(6) == 0;  // a visitor who says nothing: the kiosk must refuse it
    const double length_s = Uniform(0.8, 4.5);
    const double fs_hz = driver_.sample_rate_hz();
    driver_.SetVoice(silent ? std::vector<float>(static_cast<std::size_t>(length_s * fs_hz), 0.0f)
                            : sas::kiosk::SynthesiseVoice(fs_hz, length_s, Uniform(85.0, 260.0)));
    engine_.OnRecordButton(driver_.now_ns(), true);
    Advance(0.1);
    engine_.OnRecordButton(driver_.now_ns(), false);
    while (engine_.session().mode() == sas::kiosk::SessionMode::kCountdown) {
      Advance(0.1);  // the countdown: "speak after the tone", the count and the tone
    }
    while (driver_.voice_left() > 0 &&
           engine_.session().mode() == sas::kiosk::SessionMode::kRecording) {
      Advance(0.1);
    }
    if (engine_.session().mode() == sas::kiosk::SessionMode::kRecording) {
      engine_.OnRecordButton(driver_.now_ns(), true);  // the visitor ends the take
      Advance(0.05);
      engine_.OnRecordButton(driver_.now_ns(), false);
    }
    Advance(0.6);
    if (silent) {
      ++failed_recordings_;
    } else {
      ++good_recordings_;
      if (!engine_.has_voice()) ++voice_failures_;
    }
  }

  void Visit() {
    ++visitors_;
    // The first touch leaves the attract screen (it is a stroke too).
    Stroke(0.5, 0.5, 0.52, 0.5, 0.2, 0.5, 0.0, {});
    const int actions = 3 + Pick(10);
    for (int a = 0; a < actions && !out_of_time_; ++a) {
      const int what = Pick(20);
      if (what < 11) {
        RandomStroke();
      } else if (what < 15) {
        Token(Pick(5) - 1);  // place a token, or lift them all (-1)
        Advance(Uniform(0.2, 1.0));
      } else if (what < 17) {
        Record();
        if (engine_.has_voice()) RandomStroke();  // scratching the voice
      } else {
        PopBubble();
      }
      Advance(Uniform(0.3, 6.0));  // a pause, well inside the idle timeout
    }
    if (Pick(2) == 0) Token(-1);  // takes the token away; else it stays for the idle reset
  }

  // Prints a line of the report and keeps it for the docs page.
  void Say(const std::string& line) {
    std::printf("%s\n", line.c_str());
    said_.push_back(line);
  }

  void WriteDocs(bool ok) const {
    const std::string path = options_.docs_dir + "/soak.md";
    std::ofstream md(path);
    md << "# Soak: an accelerated day of visitors\n\n"
          "Written by `kiosk_soak --docs docs` (tests/kiosk/kiosk_soak.cpp); do not edit. "
          "Random visitors through the real engine on its virtual clock, every audio block of "
          "the day rendered (docs/engineering.md, \"Reliability\"). Seed "
       << options_.seed << ", " << options_.simulated_hours
       << " simulated hours asked. Result: " << (ok ? "every check held" : "**a check failed**")
       << ".\n\n";
    for (const auto& line : said_) md << "- " << line << "\n";
    if (!md) throw std::runtime_error("cannot write " + path);
    std::printf("wrote %s\n", path.c_str());
  }

  bool Report() {
    bool ok = true;
    const auto check = [&](bool condition, const std::string& what) {
      Say(std::string(condition ? "ok" : "FAIL") + ": " + what);
      ok = ok && condition;
    };
    Sample();
    const double wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count();
    const double simulated_h = now_s() / 3600.0;
    char line[512];
    std::snprintf(
        line, sizeof line,
        "soak: simulated %.2f h (asked %.2f h%s) in %.0f s wall (%.1fx real time), %d visitors, %d "
        "strokes, %d recordings (%d silent), %d bubbles popped, %d idle resets",
        simulated_h, options_.simulated_hours,
        out_of_time_ ? ", stopped at --max-wall-seconds" : "", wall_s,
        now_s() / std::max(wall_s, 1e-9), visitors_, strokes_,
        good_recordings_ + failed_recordings_, failed_recordings_, pops_, idle_resets_);
    Say(line);
    const long growth_kb = rss_after_warm_max_kb_ - rss_warm_kb_;
    std::snprintf(
        line, sizeof line,
        "soak: RSS start %ld kB, end %ld kB, max %ld kB (every minute); idle on the attract "
        "screen: after warm-up (%.2f h) %ld kB, highest since %ld kB, last %ld kB (%d samples)",
        rss_start_kb_, rss_end_kb_, rss_max_kb_, warmup_s_ / 3600.0, rss_warm_kb_,
        rss_after_warm_max_kb_, rss_idle_last_kb_, idle_samples_after_warmup_);
    Say(line);
    check(nan_ == 0, "NaN/Inf samples in the output: " + std::to_string(nan_));
    if (options_.rss_limit_kb > 0) {
      check(rss_warm_kb_ > 0 && idle_samples_after_warmup_ > 0 && growth_kb < options_.rss_limit_kb,
            "idle RSS growth after warm-up " + std::to_string(growth_kb) + " kB (limit " +
                std::to_string(options_.rss_limit_kb) + " kB)");
    } else {
      Say("not checked: RSS growth (--rss-limit-kb 0)");
    }
    check(visitors_ > 0 && strokes_ > 0, "visitors came and stroked");
    check(
        idle_reset_failures_ == 0,
        "idle reset (attract, the token's or the default texture, voice wiped, bubbles un-popped) "
        "before each of " +
            std::to_string(idle_resets_) + " visits");
    check(voice_failures_ == 0,
          "every spoken take became the surface (" + std::to_string(voice_failures_) + " did not)");
    const auto& counters = engine_.session().counters();
    check(counters.sessions == static_cast<std::uint64_t>(visitors_),
          "visits counted " + std::to_string(counters.sessions) + " = visitors " +
              std::to_string(visitors_));
    check(counters.strokes_per_texture == expected_strokes_ &&
              counters.voice_strokes == expected_voice_strokes_,
          "strokes counted per texture and on the voice = strokes made");
    check(counters.recordings == static_cast<std::uint64_t>(good_recordings_) &&
              counters.failed_recordings == static_cast<std::uint64_t>(failed_recordings_),
          "recordings counted " + std::to_string(counters.recordings) + " good, " +
              std::to_string(counters.failed_recordings) + " refused");
    std::string error;
    const bool saved = engine_.SaveCounters(&error);
    sas::kiosk::UsageCounters reloaded;
    std::vector<std::string> keys;
    for (const auto& texture : engine_.textures()) keys.push_back(texture.key);
    const bool loaded = sas::kiosk::LoadCounters((fs::path(state_dir_) / "counters.toml").string(),
                                                 keys, &reloaded, &error);
    check(saved && loaded && reloaded == counters, "counters file after save reads back equal");
    if (!options_.docs_dir.empty()) WriteDocs(ok);
    return ok;
  }

 public:
  std::string state_dir_;

 private:
  Options options_;
  std::mt19937 rng_;
  sas::platform::FakeAudioInput mic_;  // before the engine: it holds a pointer to the recorder
  KioskEngine engine_;
  sas::kiosk::VirtualVisit driver_;  // the audio loop on the virtual clock (after the engine)
  std::chrono::steady_clock::time_point wall_start_;
  double warmup_s_ = 3600.0;
  double next_sample_s_ = 0.0;
  double next_print_s_ = 0.0;
  bool out_of_time_ = false;
  int blocks_since_clock_ = 0;
  long nan_ = 0;
  long rss_start_kb_ = -1, rss_warm_kb_ = -1, rss_end_kb_ = -1, rss_max_kb_ = -1;
  long rss_after_warm_max_kb_ = -1, rss_idle_last_kb_ = -1;
  int idle_samples_after_warmup_ = 0;
  int token_on_switch_ = -1;  // the token the visitors left on a switch, -1 none
  int visitors_ = 0, strokes_ = 0, pops_ = 0, idle_resets_ = 0, idle_reset_failures_ = 0;
  int good_recordings_ = 0, failed_recordings_ = 0, voice_failures_ = 0;
  std::vector<std::uint64_t> expected_strokes_;
  std::uint64_t expected_voice_strokes_ = 0;
  std::vector<std::string> said_;
};

}  // namespace

int main(int argc, char** argv) {
  Options options;
  CLI::App app{
      "An accelerated simulated day of random visitors through the kiosk engine: no "
      "NaN, bounded memory, every visit counted.",
      "kiosk_soak"};
  sas::kiosk::AddNumberOption(app, "--simulated-hours", options.simulated_hours, 1e-6, 1000.0,
                              "length of the simulated day, h (default 8)");
  sas::kiosk::AddNumberOption(app, "--max-wall-seconds", options.max_wall_s, 0.0, 1e9,
                              "cut the run after this much wall time, checking what ran (0: no "
                              "limit)");
  sas::kiosk::AddNumberOption(app, "--warmup-hours", options.warmup_hours, 0.0, 1000.0,
                              "simulated time before the memory baseline, h (default "
                              "min(1, H/4))");
  app.add_option("--rss-limit-kb", options.rss_limit_kb,
                 "allowed resident-memory growth after the warm-up, kB (default 1024; 0: not "
                 "checked)")
      ->check(CLI::Range(0L, 100000000L));
  app.add_option("--seed", options.seed, "the visitors' seed");
  app.add_option("--docs", options.docs_dir,
                 "also write the summary and the checks to DIR/soak.md");
  if (const int code = sas::kiosk::ParseProgramCommandLine(app, argc, argv); code >= 0) return code;
  char state_template[] = "/tmp/sas-soak-XXXXXX";
  if (mkdtemp(state_template) == nullptr) {
    std::perror("kiosk_soak: mkdtemp");
    return 1;
  }
  sas::kiosk::TuneAllocatorForLongRuns();  // as the live kiosk does at start
  bool ok = false;
  try {
    Day day(options, state_template);
    day.state_dir_ = state_template;
    ok = day.Run();
  } catch (const std::exception& error) {
    std::fprintf(stderr, "kiosk_soak: %s\n", error.what());
  }
  std::error_code ignored;
  fs::remove_all(state_template, ignored);
  return ok ? 0 : 1;
}
