// The live kiosk (see live_kiosk.h): one control loop on the main thread wiring the window, the
// pen, the switches, the microphone and the audio device to the KioskEngine and the VisitView.
//
// Loop, each pass: SDL events (mouse/touch fallback, keyboard tokens, staff chord) -> libinput pen
// events -> switch events (TokenSelector) -> engine.Tick (session timers, recording, switches) ->
// audio supervisor Poll (reopens a lost device; the engine is told whether a callback runs) ->
// view.Advance and Present only when a frame is due -> watchdog ping when every thread is alive.
// The loop sleeps in SDL's event wait (2 ms while a pen tablet is connected, whose events come
// from libinput's thread, so a pen event waits at most that long; longer with mouse/touch, which
// wake it).
#include "live_kiosk.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>

#include "kiosk/ambient_gain.h"
#include "kiosk/command_line.h"
#include "kiosk/kiosk_config.h"
#include "kiosk/kiosk_control.h"
#include "kiosk/kiosk_engine.h"
#include "kiosk/kiosk_signals.h"
#include "platform/audio/audio_input.h"
#include "platform/audio/audio_output.h"
#include "platform/audio/background_audio_output.h"
#include "platform/common/clock.h"
#include "platform/device_status.h"
#include "platform/input/switch_factory.h"
#include "platform/input/token_selector.h"
#include "platform/log/log.h"
#include "platform/pen/pen_source.h"
#include "platform/watchdog/watchdog.h"
#include "sas/version.h"
#include "ui/display_probe.h"
#include "ui/kiosk_window.h"
#include "ui/overlay.h"
#include "ui/text.h"
#include "ui/ttf_text.h"
#include "visit_view.h"

namespace sas::app {
namespace {

namespace fs = std::filesystem;

struct KioskArgs {
  std::string config_path = "/etc/sketch-a-scratch/kiosk.toml";
  std::string state_dir;  // counters and the last good configuration
};

std::string DefaultStateDir() {
  if (const char* dir = std::getenv("STATE_DIRECTORY"); dir != nullptr && *dir)
    return dir;  // systemd
  if (const char* dir = std::getenv("XDG_STATE_HOME"); dir != nullptr && *dir) {
    return (fs::path(dir) / "sketch-a-scratch").string();
  }
  if (const char* home = std::getenv("HOME"); home != nullptr && *home) {
    return (fs::path(home) / ".local" / "state" / "sketch-a-scratch").string();
  }
  return "/var/lib/sketch-a-scratch";
}

std::string Fixed(double value, int decimals) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

// The staff panel's buttons (tapped with the pen or the mouse while the panel is open), in one
// row along its bottom edge.
enum class StaffButton {
  kTone,
  kSweep,
  kLowVibration,
  kVolumeDown,
  kVolumeUp,
  kVibrationDown,
  kVibrationUp,
  kCount
};

struct StaffButtons {
  std::array<ui::PixelRect, static_cast<std::size_t>(StaffButton::kCount)> rects;
  const ui::PixelRect& operator[](StaffButton b) const {
    return rects[static_cast<std::size_t>(b)];
  }
  // The button under (x, y), or kCount.
  StaffButton At(int x, int y) const {
    for (std::size_t i = 0; i < rects.size(); ++i) {
      if (rects[i].Contains(x, y)) return static_cast<StaffButton>(i);
    }
    return StaffButton::kCount;
  }
};

StaffButtons StaffButtonRects(int width, int height) {
  const ui::PixelRect panel = ui::StaffPanelRect(width, height);
  constexpr int kCount = static_cast<int>(StaffButton::kCount);
  const int h = 44, gap = 12;
  const int w = std::min(200, (panel.w - (kCount + 1) * gap) / kCount);
  const int y = panel.y + panel.h - h - gap;
  StaffButtons buttons;
  for (int i = 0; i < kCount; ++i) {
    buttons.rects[static_cast<std::size_t>(i)] = {panel.x + gap + i * (gap + w), y, w, h};
  }
  return buttons;
}

class StaffPanel {
 public:
  struct Inputs {
    const kiosk::KioskEngine* engine;
    const platform::AudioOutput* output;
    const platform::DeviceStatusBoard* board;
    const platform::SwitchInputs* switches;
    const platform::TokenSelector* selector;
    bool record_down;
    platform::PenReading pen;
    std::string config_line;
    int buffer_frames;
    int sample_rate_hz;
  };

  // Rebuilds the panel's text at most 4 times a second (a frame is drawn only when it changed).
  // Normal case, so paths read as they are and can be typed from the journal line it repeats;
  // lines wrap at spaces; the size follows the screen (16 px at 720p, 24 px at 1080p).
  const ui::Overlays& Build(const Inputs& in, ui::TextRenderer& text, int width, int height,
                            double now_s) {
    if (now_s - built_s_ < 0.25 && !overlays_.empty()) return overlays_;
    built_s_ = now_s;
    overlays_.clear();
    const ui::PixelRect panel = ui::StaffPanelRect(width, height);
    const bool ttf = text.Available();
    const int size_px = std::max(16, height / 45);
    const int scale = panel.w >= 1100 ? 2 : 1;
    const int line_h = ttf ? text.LineHeight(size_px) : (ui::kGlyphHeight + 4) * scale;
    const int bottom = panel.y + panel.h - 80;
    int y = panel.y + 16;
    const ui::Rgba white{235, 235, 235, 255};
    const ui::Rgba amber{250, 190, 60, 255};
    const auto line = [&](const std::string& content, ui::Rgba color) {
      if (!ttf) {
        // The bitmap fallback: capitals, cut at the panel's edge.
        const int max_chars = (panel.w - 32) / (ui::kGlyphAdvance * scale);
        if (y + line_h > bottom) return;
        ui::AddText(overlays_, panel.x + 16, y, scale,
                    content.substr(0, static_cast<std::size_t>(std::max(0, max_chars))), color);
        y += line_h;
        return;
      }
      // A long status (a rejected configuration's file:line: key: what) wraps rather than losing
      // its end, where the reason is; continuation lines are indented, so every row is wrapped
      // to the indented width (none runs past the panel's edge).
      bool first = true;
      for (const auto& row : text.Wrap(content, size_px, panel.w - 32 - 24)) {
        if (y + line_h > bottom) return;
        if (auto mask = text.Render(row, size_px)) {
          overlays_.push_back(
              {{panel.x + 16 + (first ? 0 : 24), y, mask->w, mask->h}, color, std::move(mask)});
        }
        first = false;
        y += line_h;
      }
    };
    line(std::string("Sketch-a-Scratch ") + kVersion +
             " - staff panel (the staff chord again closes it)",
         amber);
    for (const auto& status : in.board->All()) {
      line(status.device + ": " + platform::DeviceStateName(status.state) +
               (status.backend.empty() ? "" : " (" + status.backend + ")") + " - " + status.message,
           status.state == platform::DeviceState::kOk ? white : amber);
    }
    const auto stats = in.output->Stats();
    const double buffer_ms = 1e3 * in.buffer_frames / in.sample_rate_hz;
    line("Audio: " + std::string(in.output->Running() ? "running" : "silent (no device)") +
             ", xruns " + std::to_string(stats.xruns) + ", callback load " +
             Fixed(100.0 * static_cast<double>(stats.last_callback_ns) * 1e-6 / buffer_ms, 1) +
             "% (max " +
             Fixed(100.0 * static_cast<double>(stats.max_callback_ns) * 1e-6 / buffer_ms, 1) +
             "%) of " + Fixed(buffer_ms, 2) + " ms",
         white);
    const auto engine_stats = in.engine->audio_stats();
    line("Pen event -> first output sample: last " +
             Fixed(static_cast<double>(engine_stats.pen_to_sample_last_ns) * 1e-6, 2) +
             " ms, max " + Fixed(static_cast<double>(engine_stats.pen_to_sample_max_ns) * 1e-6, 2) +
             " ms (target " + Fixed(buffer_ms + 1.0, 2) + " ms), dropped " +
             std::to_string(engine_stats.dropped_commands),
         white);
    // The dose, for staff (README, staff guide: turning it into dB SPL with a phone meter once).
    const auto leq = [](std::optional<double> db) {
      return db ? Fixed(*db, 1) + " dBFS" : std::string("-");
    };
    line("Speaker Leq: last visit " + leq(in.engine->exposure().LastVisitDb()) + ", last hour " +
             leq(in.engine->exposure().LastHourDb()) + " (speaker ceiling " +
             Fixed(in.engine->config().sound_ceiling_db, 1) + " dBTP)",
         white);
    std::string tokens = "Switches: " + std::string(in.switches->ActiveBackend()) + ", tokens";
    for (int t = 0; t < platform::kTokenCount; ++t) {
      tokens += " " + std::to_string(t + 1) + (in.selector->Present(t) ? ": on" : ": off");
    }
    tokens +=
        ", record " + std::string(in.record_down ? "down" : "up") + ", showing " +
        (in.engine->surface().voice
             ? std::string("the voice")
             : in.engine->textures()[static_cast<std::size_t>(in.engine->surface().texture)].key) +
        ", language " + in.engine->language();
    line(tokens, white);
    const float level = in.engine->mic_level();
    line("Microphone: " +
             std::string(in.engine->recorder_present()
                             ? "level " +
                                   (level > 0.0f ? Fixed(20.0 * std::log10(level), 1) : "-inf") +
                                   " dBFS"
                             : "none (recording disabled)"),
         white);
    line("Pen: pressure " + Fixed(in.pen.pressure, 2) + ", tilt " + Fixed(in.pen.TiltDeg(), 1) +
             " deg, at " + Fixed(in.pen.x_px, 0) + "," + Fixed(in.pen.y_px, 0) +
             (in.pen.origin == platform::PenOrigin::kTablet  ? " (tablet)"
              : in.pen.origin == platform::PenOrigin::kTouch ? " (touch)"
                                                             : " (mouse)"),
         white);
    const auto& counters = in.engine->session().counters();
    std::string strokes = "Strokes:";
    for (std::size_t t = 0; t < counters.strokes_per_texture.size(); ++t) {
      strokes += " " + in.engine->textures()[t].key + " " +
                 std::to_string(counters.strokes_per_texture[t]);
    }
    line(strokes + ", voice " + std::to_string(counters.voice_strokes), white);
    line("Recordings " + std::to_string(counters.recordings) + " (failed " +
             std::to_string(counters.failed_recordings) + "), visits " +
             std::to_string(counters.sessions) + ", cues " +
             std::to_string(in.engine->cues_loaded()),
         white);
    line(in.config_line, white);
    const auto& staff = in.engine->staff_settings();
    line("Volume " + Fixed(staff.volume_db, 0) + " dB, vibration " + Fixed(staff.vibration_db, 0) +
             " dB",
         white);
    const StaffButtons buttons = StaffButtonRects(width, height);
    const char* low_vibration_label = in.engine->low_vibration() ? "Low vib on" : "Low vib off";
    for (const auto& [button, label] :
         {std::pair{StaffButton::kTone, "Test tone"}, std::pair{StaffButton::kSweep, "Sweep"},
          std::pair{StaffButton::kLowVibration, low_vibration_label},
          std::pair{StaffButton::kVolumeDown, "Volume -"},
          std::pair{StaffButton::kVolumeUp, "Volume +"},
          std::pair{StaffButton::kVibrationDown, "Vib -"},
          std::pair{StaffButton::kVibrationUp, "Vib +"}}) {
      const ui::PixelRect& rect = buttons[button];
      // A dark blue: the white label keeps 7:1 on it (8.9:1; the lighter blue it replaces gave
      // 5.8:1), and the button still stands out from the panel's near-black plate.
      overlays_.push_back({rect, {40, 62, 100, 255}});
      if (ttf) {
        if (auto mask = text.Render(label, std::min(size_px, rect.h * 6 / 10), true)) {
          overlays_.push_back(
              {{rect.x + (rect.w - mask->w) / 2, rect.y + (rect.h - mask->h) / 2, mask->w, mask->h},
               white,
               std::move(mask)});
        }
        continue;
      }
      // Seven buttons share a 720p panel's width: a label that does not fit goes down a size.
      const int label_scale = ui::TextWidth(label, 2) <= rect.w - 8 ? 2 : 1;
      ui::AddText(overlays_, rect.x + (rect.w - ui::TextWidth(label, label_scale)) / 2,
                  rect.y + (rect.h - ui::kGlyphHeight * label_scale) / 2, label_scale, label,
                  white);
    }
    return overlays_;
  }

 private:
  double built_s_ = -1.0;
  ui::Overlays overlays_;
};

}  // namespace

int RunKiosk(const std::vector<std::string>& args, std::FILE* out, std::FILE* err,
             const KioskBackends& backends) {
  KioskArgs options;
  CLI::App app("Runs the kiosk full-screen on the display (exits 1 when there is none).", "kiosk");
  app.add_option("--config", options.config_path,
                 "configuration file (default /etc/sketch-a-scratch/kiosk.toml)");
  app.add_option("--state-dir", options.state_dir,
                 "folder for the usage counters and the last good configuration (default "
                 "$STATE_DIRECTORY, else $XDG_STATE_HOME/sketch-a-scratch, else "
                 "~/.local/state/sketch-a-scratch)");
  if (const int code = kiosk::ParseCommandLine(app, args, out, err); code >= 0) return code;
  // Without a screen SDL falls back to its invisible offscreen driver and the kiosk would run
  // for no one, counting visits into the home folder. Refuse before anything is written; a test
  // that wants the virtual driver asks for it by name in SDL_VIDEODRIVER (ProbeDisplay).
  if (const auto display = ui::ProbeDisplay(); !display.available) {
    std::fprintf(err,
                 "sketch-a-scratch kiosk: no display (%s); set DISPLAY or WAYLAND_DISPLAY, or run "
                 "on a console with KMS (`sketch-a-scratch demo` runs without one)\n",
                 display.problem.c_str());
    return kiosk::kExitRuntimeError;
  }
  if (options.state_dir.empty()) options.state_dir = DefaultStateDir();
  // SIGHUP (the unit's reload) or SIGUSR1 would otherwise end the kiosk and lose the counters
  // since the last save; the loop saves them, or reports the status, instead (one arriving while
  // the textures load waits for the first pass). A closed stdout/stderr pipe must not end it
  // either.
  kiosk::CatchHangupAndIgnoreWriteSignals();
  kiosk::TuneAllocatorForLongRuns();
  auto& log = platform::DefaultLogger();
  platform::DeviceStatusBoard board(log);
  std::error_code dir_error;
  fs::create_directories(options.state_dir, dir_error);
  if (dir_error)
    log.Warn("kiosk", "state folder " + options.state_dir + ": " + dir_error.message());

  const auto loaded = kiosk::LoadKioskConfigWithFallback(
      options.config_path, (fs::path(options.state_dir) / "kiosk.last-good.toml").string());
  const kiosk::KioskConfig& config = loaded.config;
  // One journal line now (the kiosk may still fail to open a window), and the staff panel's
  // "config" status: "missing: rejected: <file>:<line>: <key>: <what> (using ...)".
  kiosk::ReportConfig(board, loaded);
  const std::string config_line = kiosk::ConfigStatusLine(options.config_path, loaded);

  ui::KioskWindowOptions window_options;
  window_options.staff_chord = {config.staff_chord, config.staff_chord_hold_s};
  ui::KioskWindow window(window_options);
  try {
    try {
      window.Open();
    } catch (const ui::WindowError& error) {
      // A key name SDL does not know: staff must still get in, so keep the default chord.
      if (std::string(error.what()).rfind("staff chord", 0) != 0) throw;
      log.Error("config", std::string(error.what()) + " (using the default chord ctrl+alt+s)");
      window = ui::KioskWindow(ui::KioskWindowOptions{});
      window.Open();
    }
  } catch (const std::exception& error) {
    log.Error("display", std::string("cannot open the kiosk window: ") + error.what());
    return 1;
  }
  const int width = window.width_px(), height = window.height_px();
  kiosk::CatchStopSignals();

  kiosk::KioskEngineOptions engine_options;
  engine_options.config = config;
  engine_options.screen_width_px = width;
  engine_options.screen_height_px = height;
  engine_options.counters_path = (fs::path(options.state_dir) / "counters.toml").string();
  engine_options.staff_settings_path = (fs::path(options.state_dir) / "staff.toml").string();
  engine_options.attract_stroke = config.attract_passive_stroke;
  std::unique_ptr<kiosk::KioskEngine> engine;
  std::unique_ptr<VisitView> view;
  try {
    engine = std::make_unique<kiosk::KioskEngine>(engine_options);
    view = std::make_unique<VisitView>(*engine, width, height);
  } catch (const std::exception& error) {
    log.Error("kiosk", std::string("cannot load the textures: ") + error.what());
    return 1;
  }
  engine->SetStatusBoard(&board);
  kiosk::ReportTextures(board, *engine);

  // Microphone first (the engine keeps a pointer to its recorder), then the output.
  platform::AudioInputConfig input_config;
  input_config.device = config.input_device;
  input_config.sample_rate_hz = config.sample_rate_hz;
  platform::VoiceRecorderConfig recorder_config;
  recorder_config.sample_rate_hz = config.sample_rate_hz;
  recorder_config.max_duration_s = config.record_max_duration_s;
  recorder_config.clip_level = static_cast<float>(config.record_clip_level);
  recorder_config.silence_rms_dbfs = config.record_silence_rms_dbfs;
  auto input = platform::MakePortAudioInput(input_config, recorder_config, board);
  if (input->Start()) engine->SetRecorder(&input->recorder());

  platform::AudioOutputConfig output_config;
  output_config.device = config.output_device;
  output_config.sample_rate_hz = config.sample_rate_hz;
  output_config.frames_per_buffer = config.buffer_frames;
  output_config.reopen_backoff_initial_s = config.reopen_backoff_initial_s;
  output_config.reopen_backoff_max_s = config.reopen_backoff_max_s;
  output_config.stall_timeout_s = config.stall_timeout_s;
  // Supervised on its own thread: a reopen can sit in ALSA for seconds, and the screen, the pen
  // and the idle reset must not wait for it.
  auto output = std::make_unique<platform::BackgroundAudioOutput>(
      backends.audio_stream ? std::make_unique<platform::SupervisedAudioOutput>(
                                  backends.audio_stream(), *engine, output_config, board)
                            : platform::MakePortAudioOutput(*engine, output_config, board));
  output->Start();  // absent: runs silent, the supervision thread retries with back-off
  engine->SetAudioRunning(output->Running());

  platform::SwitchesConfig switches_config;
  switches_config.backend = config.switches_backend;
  switches_config.gpio.chip = config.gpio_chip;
  for (std::size_t i = 0; i < switches_config.gpio.lines.size() && i < config.gpio_lines.size();
       ++i) {
    switches_config.gpio.lines[i] = config.gpio_lines[i];
  }
  switches_config.gpio.active_low = config.switches_active_low;
  switches_config.gpio.debounce_ms = config.switches_debounce_ms;
  switches_config.mcp2221.path = config.mcp2221_path;
  switches_config.mcp2221.active_low = config.switches_active_low;
  switches_config.mcp2221.debounce_ms = config.switches_debounce_ms;
  switches_config.mcp2221.poll_interval_ms = config.mcp2221_poll_ms;
  std::unique_ptr<platform::GpioEventSource> gpio_events;
  if (backends.gpio_events &&
      (switches_config.backend == "gpio" || switches_config.backend == "auto")) {
    gpio_events = backends.gpio_events(switches_config.gpio);
  }
  auto switches = platform::OpenSwitchInputs(switches_config, board, std::move(gpio_events));

  platform::PenConfig pen_config;
  pen_config.screen_width_px = width;
  pen_config.screen_height_px = height;
  pen_config.seat = config.pen_seat;
  pen_config.device_name_contains = config.pen_device;
  auto pen = platform::OpenPen(pen_config, board);
  kiosk::KioskControl control(*engine, {output.get(), pen.get(), &switches, &board}, log);

  platform::WatchdogSupervisor watchdog(2'000 * platform::kNsPerMs);
  watchdog.Watch("audio", [&]() -> std::int64_t {
    return output->Running() ? output->Stats().heartbeat_ns : platform::WatchdogSupervisor::kExempt;
  });
  if (pen) watchdog.Watch("pen", [&]() { return pen->HeartbeatNs(); });
  if (switches.hardware) {
    watchdog.Watch("switches", [&]() -> std::int64_t {
      const auto beat = switches.hardware->HeartbeatNs();
      return beat < 0 ? platform::WatchdogSupervisor::kExempt : beat;
    });
  }
  watchdog.Ready("exploring");
  std::fprintf(out, "kiosk ready %dx%d %s (%s), audio %s, pen %s, switches %s\n", width, height,
               window.driver().c_str(), window.renderer_name().c_str(),
               output->Running() ? "running" : "silent",
               pen ? (pen->Connected() ? "libinput" : "mouse/touch (libinput waiting for a tablet)")
                   : "mouse/touch",
               switches.ActiveBackend());
  std::fflush(out);

  StaffPanel staff;
  platform::PenReading last_pen{};
  const StaffButtons buttons = StaffButtonRects(width, height);
  const auto stylus_to_engine = [&](const platform::PenReading& s) {
    last_pen = s;
    view->OnStylus(s);
    // While the staff panel is open the pen works its buttons; elsewhere it still explores.
    if (window.staff_panel_open() && s.tip_down) {
      const StaffButton button = buttons.At(static_cast<int>(s.x_px), static_cast<int>(s.y_px));
      if (button != StaffButton::kCount) {
        static std::int64_t last_press_ns = 0;
        if (s.time_ns - last_press_ns > 500 * platform::kNsPerMs) {
          last_press_ns = s.time_ns;
          engine->OnStaffActivity(s.time_ns);
          const auto gains_line = [&] {
            const auto& staff_settings = engine->staff_settings();
            log.Info("staff", "volume " + Fixed(staff_settings.volume_db, 0) + " dB, vibration " +
                                  Fixed(staff_settings.vibration_db, 0) + " dB");
          };
          switch (button) {
            case StaffButton::kTone:
              engine->PlayTestTone();
              log.Info("staff", "test tone on the speaker");
              break;
            case StaffButton::kSweep:
              engine->PlayTransducerSweep();
              log.Info("staff", "sweep on the transducer");
              break;
            case StaffButton::kLowVibration:
              engine->SetLowVibration(!engine->low_vibration());
              log.Info("staff", engine->low_vibration() ? "low-vibration mode on"
                                                        : "low-vibration mode off");
              break;
            case StaffButton::kVolumeDown:
            case StaffButton::kVolumeUp:
              engine->StepVolume(button == StaffButton::kVolumeUp ? 1 : -1);
              gains_line();
              break;
            case StaffButton::kVibrationDown:
            case StaffButton::kVibrationUp:
              engine->StepVibration(button == StaffButton::kVibrationUp ? 1 : -1);
              gains_line();
              break;
            case StaffButton::kCount:
              break;
          }
          view->view().Invalidate();
        }
        return;
      }
    }
    engine->OnPen(s);
  };

  // Ambient-adaptive sound gain (gains.ambient_adaptive): the microphone's meter while the attract
  // screen is up, a few times a second.
  kiosk::AmbientGain ambient(kiosk::AmbientGainConfigFrom(config));
  double ambient_last_s = -1.0;
  bool passive_shown = false;  // the view is drawing the passive stroke's dent

  while (!control.HandleSignals()) {
    const std::int64_t pass_start_ns = platform::MonotonicNowNs();
    const int wait_ms = view->view().NeedsRedraw() ? 0 : (pen && pen->Connected() ? 2 : 8);
    for (const auto& event : window.PollEvents(wait_ms)) {
      using Kind = ui::UiEvent::Kind;
      switch (event.kind) {
        case Kind::kPointerDown:
        case Kind::kPointerMove:
        case Kind::kPointerUp:
          // A working tablet speaks through libinput instead; unplugged, the mouse/touch stands in.
          if (control.PointerActive()) stylus_to_engine(event.stylus);
          break;
        case Kind::kTokenKey:
          if (event.token >= 0) {
            switches.keyboard->OnKey(static_cast<char>('1' + event.token), true, event.time_ns);
          }
          break;
        case Kind::kRecordKey:
          switches.keyboard->OnKey('r', event.pressed, event.time_ns);
          break;
        case Kind::kLanguageKey:
          if (engine->NextLanguage(event.time_ns)) {
            log.Info("session", "language " + engine->language());
            view->view().Invalidate();
          }
          break;
        case Kind::kStaffChord:
          engine->OnStaffChord(event.time_ns);
          log.Info("staff", event.pressed ? "staff panel opened" : "staff panel closed");
          break;
        case Kind::kRedraw:
          view->view().Invalidate();
          break;
      }
    }
    const std::int64_t now_ns = platform::MonotonicNowNs();
    const double now_s = static_cast<double>(now_ns) * 1e-9;
    const auto actions = control.Step(now_ns, stylus_to_engine);
    if (!actions.empty()) view->Apply(actions, now_s);
    // The passive stroke's dent travels with its virtual probe (drawn like a pen's).
    if (const auto passive = engine->passive_pen()) {
      view->OnStylus(*passive);
      passive_shown = true;
    } else if (passive_shown) {
      passive_shown = false;
      platform::PenReading s;
      s.time_ns = now_ns;
      s.x_px = last_pen.x_px;
      s.y_px = last_pen.y_px;
      view->OnStylus(s);  // lifted
    }
    // The session decides whether the panel is open (it closes a forgotten one by itself).
    if (window.staff_panel_open() != engine->session().staff_panel_open()) {
      window.set_staff_panel_open(engine->session().staff_panel_open());
      if (!window.staff_panel_open()) log.Info("staff", "staff panel closed (timeout)");
      view->view().Invalidate();
    }
    if (config.ambient_adaptive && engine->recorder_present() && now_s - ambient_last_s >= 0.25) {
      const double dt_s = ambient_last_s < 0.0 ? 0.25 : now_s - ambient_last_s;
      ambient_last_s = now_s;
      const double level = std::max(static_cast<double>(engine->mic_level()), 1e-6);
      // Only while the kiosk itself is quiet (between passive strokes, no cue): the microphone
      // would otherwise hear the box and turn it up further.
      ambient.Update(
          20.0 * std::log10(level), dt_s,
          engine->session().mode() == kiosk::SessionMode::kAttract && engine->AmbientListening());
      engine->SetAmbientGainDb(ambient.gain_db());
    }

    ui::Overlays staff_overlays;
    if (window.staff_panel_open()) {
      staff_overlays = staff.Build({engine.get(), output.get(), &board, &switches,
                                    &control.selector(), control.record_down(), last_pen,
                                    config_line, config.buffer_frames, config.sample_rate_hz},
                                   view->text(), width, height, now_s);
    }
    if (view->Advance(now_s, window.staff_panel_open(), std::move(staff_overlays))) {
      window.Present(view->view().TakeFrame());
    }
    watchdog.Tick(now_ns);
    if (backends.on_pass) backends.on_pass(pass_start_ns, platform::MonotonicNowNs());
  }
  control.Shutdown();
  input->Stop();
  engine->SetRecorder(nullptr);
  input->recorder().Wipe();
  window.Close();
  return 0;
}

}  // namespace sas::app
