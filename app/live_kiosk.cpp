// The live kiosk (see live_kiosk.h): one control loop on the main thread wiring the window, the
// pen, the switches, the microphone and the audio device to the KioskEngine and the VisitView.
// RunKiosk reads the command line and the configuration, opens the window, the engine and the
// devices (OpenDevices), and hands them to the LiveLoop.
//
// Loop, each pass: SDL events (mouse/touch fallback, keyboard tokens, staff chord) -> libinput pen
// readings -> switch events (TokenSelector) -> engine.Tick (session timers, recording, switches) ->
// audio supervisor Poll (reopens a lost device; the engine is told whether a callback runs) ->
// view.Advance and Present only when a frame is due -> watchdog ping when every thread is alive.
// The loop sleeps in SDL's event wait (2 ms while a pen tablet is connected, whose readings come
// from libinput's thread, so a reading waits at most that long; longer with mouse/touch, which
// wake it). While the staff panel is open the pen works its buttons (kiosk/staff_panel.h).
//
// systemd hears READY=1 only once the first frame is on the screen (everything before is start-up,
// under the unit's start timeout), and from then on a WATCHDOG=1 after every pass. A pass takes a
// bounded share of the input waiting for it (SDL events, pen readings, switch events: see
// KioskControl) and leaves the rest, timestamps intact, to the next passes, which then do not
// sleep: input that piled up while a slow machine started cannot hold off the frame or the ping.
#include "live_kiosk.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>

#include "files/kiosk_config.h"
#include "kiosk/ambient_gain.h"
#include "kiosk/device_configs.h"
#include "kiosk/health_metrics.h"
#include "kiosk/kiosk_control.h"
#include "kiosk/kiosk_engine.h"
#include "kiosk/kiosk_signals.h"
#include "kiosk/staff_panel.h"
#include "platform/audio/audio_input.h"
#include "platform/audio/audio_output.h"
#include "platform/audio/background_audio_output.h"
#include "platform/common/clock.h"
#include "platform/device_status.h"
#include "platform/input/switch_factory.h"
#include "platform/log/log.h"
#include "platform/pen/pen_source.h"
#include "platform/watchdog/busy_keeper.h"
#include "platform/watchdog/watchdog.h"
#include "sas/version.h"
#include "staff_panel_view.h"
#include "tools/command_line.h"
#include "ui/display_probe.h"
#include "ui/kiosk_window.h"
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

// The command line into `options`; an exit code (>= 0) when the kiosk must not run: --help, a
// usage error, or no display to run on.
int ParseKioskArgs(const std::vector<std::string>& args, std::FILE* out, std::FILE* err,
                   KioskArgs& options) {
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
  return -1;
}

// Opens the full-screen window once: the error, or empty when it is open.
std::string TryOpenWindow(const ui::KioskWindowOptions& options, ui::KioskWindow& window) {
  window = ui::KioskWindow(options);
  try {
    window.Open();
  } catch (const std::exception& error) {
    return error.what();
  }
  return {};
}

// Opens the full-screen window; false (logged) when there is none. The display can be slow to
// come up (a DRM device still held at boot, an X server under load), so it is tried for a few
// seconds before the kiosk gives up and exits for systemd to restart it.
bool OpenWindow(const kiosk::KioskConfig& config, platform::Logger& log, ui::KioskWindow& window) {
  ui::KioskWindowOptions options;
  options.staff_chord = {config.staff_chord, config.staff_chord_hold_s};
  constexpr int kTries = 10;
  constexpr auto kPause = std::chrono::milliseconds(500);
  std::string error;
  for (int attempt = 1; attempt <= kTries; ++attempt) {
    error = TryOpenWindow(options, window);
    if (error.rfind("staff chord", 0) == 0) {
      // A key name SDL does not know: staff must still get in, so keep the default chord.
      log.Error("config", error + " (using the default chord ctrl+alt+s)");
      options = ui::KioskWindowOptions{};
      error = TryOpenWindow(options, window);
    }
    if (error.empty()) return true;
    if (attempt == 1) {
      log.Warn("display", "cannot open the kiosk window: " + error + "; trying again for " +
                              std::to_string((kTries - 1) * kPause.count() / 1000) + " s");
    }
    if (attempt < kTries) std::this_thread::sleep_for(kPause);
  }
  log.Error("display", "cannot open the kiosk window: " + error);
  return false;
}

// Every device besides the window, each set up from the configuration; a missing one falls back
// (silent audio, keys for tokens, mouse/touch for the pen) and says so on the board.
struct LiveDevices {
  std::unique_ptr<platform::AudioInput> input;
  std::unique_ptr<platform::BackgroundAudioOutput> output;
  platform::SwitchInputs switches;
  std::unique_ptr<platform::PenSource> pen;  // null: no libinput at all
};

LiveDevices OpenDevices(const kiosk::KioskConfig& config, kiosk::KioskEngine& engine,
                        platform::DeviceStatusBoard& board, const KioskBackends& backends,
                        int width, int height) {
  LiveDevices devices;
  // Microphone first (the engine keeps a pointer to its recorder), then the output.
  devices.input = platform::MakePortAudioInput(kiosk::AudioInputConfigFor(config),
                                               kiosk::RecorderConfigFor(config), board);
  if (devices.input->Start()) engine.SetRecorder(&devices.input->recorder());

  const platform::AudioOutputConfig output_config = kiosk::AudioOutputConfigFor(config);
  // Supervised on its own thread: a reopen can sit in ALSA for seconds, and the screen, the pen
  // and the idle reset must not wait for it.
  devices.output = std::make_unique<platform::BackgroundAudioOutput>(
      backends.audio_stream ? std::make_unique<platform::SupervisedAudioOutput>(
                                  backends.audio_stream(), engine.audio(), output_config, board)
                            : platform::MakePortAudioOutput(engine.audio(), output_config, board));
  devices.output->Start();  // absent: runs silent, the supervision thread retries with back-off
  engine.SetAudioRunning(devices.output->Running());

  const platform::SwitchesConfig switches_config = kiosk::SwitchesConfigFor(config);
  std::unique_ptr<platform::GpioEventSource> gpio_events;
  if (backends.gpio_events &&
      (switches_config.backend == "gpio" || switches_config.backend == "auto")) {
    gpio_events = backends.gpio_events(switches_config.gpio);
  }
  devices.switches = platform::OpenSwitchInputs(switches_config, board, std::move(gpio_events));

  devices.pen = platform::OpenPen(kiosk::PenConfigFor(config, width, height), board,
                                  backends.pen ? backends.pen() : nullptr);
  return devices;
}

// systemd's watchdog is pinged only while every device thread that runs reports heartbeats.
void WatchDeviceThreads(platform::WatchdogSupervisor& watchdog, const LiveDevices& devices) {
  watchdog.Watch("audio", [&devices]() -> std::int64_t {
    return devices.output->Running() ? devices.output->Stats().heartbeat_ns
                                     : platform::WatchdogSupervisor::kExempt;
  });
  if (devices.pen) watchdog.Watch("pen", [&devices]() { return devices.pen->HeartbeatNs(); });
  if (devices.switches.hardware) {
    watchdog.Watch("switches", [&devices]() -> std::int64_t {
      const auto beat = devices.switches.hardware->HeartbeatNs();
      return beat < 0 ? platform::WatchdogSupervisor::kExempt : beat;
    });
  }
}

// What one start-up stage may take before systemd gives up on the start (see RunKiosk).
constexpr std::uint64_t kStartStageBudgetUs = 90'000'000;

// The start is judged by its progress, not by its total: each stage done gives systemd's start
// timeout (the unit's TimeoutStartSec, 90 s by default) another kStartStageBudgetUs, so a slow
// but moving start (a cold SD card, an emulated or busy machine) is not killed, and a stage that
// hangs still is.
void ReportStartStage(const platform::SystemdNotifier& notifier, const std::string& stage) {
  notifier.Notify("EXTEND_TIMEOUT_USEC=" + std::to_string(kStartStageBudgetUs) +
                  "\nSTATUS=starting: " + stage);
}

// What the loop works on, all opened by RunKiosk.
struct LoopParts {
  const kiosk::KioskConfig& config;
  std::string config_line;  // the staff panel's line about the configuration file
  ui::KioskWindow& window;
  kiosk::KioskEngine& engine;
  VisitView& view;
  LiveDevices& devices;
  kiosk::KioskControl& control;
  platform::DeviceStatusBoard& board;
  platform::WatchdogSupervisor& watchdog;
  platform::Logger& log;
  const KioskBackends& backends;
  std::FILE* out;  // the "kiosk ready" line
  // The fleet's health metrics (kiosk/health_metrics.h).
  std::string metrics_path;  // "": none
  bool config_accepted;
  std::int64_t started_ns;  // CLOCK_MONOTONIC and Unix time of the process's start
  double started_unix_s;
};

// The main loop (main thread) and the little it keeps between passes.
class LiveLoop {
 public:
  explicit LiveLoop(LoopParts parts)
      : p_(std::move(parts)),
        width_(p_.window.width_px()),
        height_(p_.window.height_px()),
        buttons_(StaffButtonRects(width_, height_)),
        ambient_(kiosk::AmbientGainConfigFrom(p_.config)),
        metrics_(p_.metrics_path, p_.config.metrics_interval_s, p_.log),
        box_name_(p_.config.box_name.empty() ? kiosk::DefaultBoxName() : p_.config.box_name) {}

  // Passes until SIGTERM/SIGINT.
  void Run() {
    while (!p_.control.HandleSignals()) {
      const std::int64_t pass_start_ns = platform::MonotonicNowNs();
      HandleWindowEvents();
      const std::int64_t now_ns = platform::MonotonicNowNs();
      const double now_s = static_cast<double>(now_ns) * 1e-9;
      const auto actions =
          p_.control.Step(now_ns, [this](const platform::PenReading& pen) { OnPen(pen); });
      if (!actions.empty()) p_.view.Apply(actions, now_s);
      ShowPassiveStroke(now_ns);
      FollowStaffPanel();
      AdaptToAmbient(now_s);
      WriteMetrics(now_ns);
      const std::int64_t draw_start_ns = platform::MonotonicNowNs();
      // A slow renderer's frame can outlast WatchdogSec without the kiosk being hung: the keeper
      // pings for the loop while it draws, for a bounded time (busy_keeper.h).
      if (ready_) draw_keeper_.Begin(draw_start_ns, pinged_);
      Draw(now_s);
      draw_keeper_.End();
      if (ready_) pinged_ = p_.watchdog.Tick(now_ns);  // pings follow READY=1, never precede it
      const std::int64_t end_ns = platform::MonotonicNowNs();
      NoteSlowPass(pass_start_ns, draw_start_ns, end_ns);
      if (p_.backends.on_pass) p_.backends.on_pass(pass_start_ns, end_ns);
    }
  }

 private:
  // A pass slower than this is a display too slow for visitors (the draw keeper holds the
  // watchdog off for 60 s of one frame, then systemd restarts the kiosk); staff and installers
  // learn it from the journal: one warning at most a minute, with how many since the last.
  static constexpr std::int64_t kSlowPassNs = 2'000 * platform::kNsPerMs;
  static constexpr std::int64_t kSlowPassReportNs = 60'000 * platform::kNsPerMs;

  void NoteSlowPass(std::int64_t start_ns, std::int64_t draw_start_ns, std::int64_t end_ns) {
    if (end_ns - start_ns <= kSlowPassNs) return;
    ++slow_passes_;
    if (slow_reported_ns_ != 0 && end_ns - slow_reported_ns_ < kSlowPassReportNs) return;
    char line[160];
    std::snprintf(line, sizeof line,
                  "a loop pass took %.1f s (drawing %.1f s); %d such since the last report; "
                  "systemd's watchdog restarts the kiosk after 60 s in one frame",
                  static_cast<double>(end_ns - start_ns) * 1e-9,
                  static_cast<double>(end_ns - draw_start_ns) * 1e-9, slow_passes_);
    p_.log.Warn("kiosk", line);
    slow_reported_ns_ = end_ns;
    slow_passes_ = 0;
  }

  // SDL events one pass takes at most: like the pen's budget (KioskControl), many times what a
  // mouse or touch screen sends in a frame, and a bounded amount of work.
  static constexpr std::size_t kSdlEventsPerPass = 64;

  void HandleWindowEvents() {
    const bool tablet = p_.devices.pen && p_.devices.pen->Connected();
    // Input left over from the last pass is worked off without sleeping first.
    const bool busy = p_.view.view().NeedsRedraw() || p_.control.Backlog();
    const int wait_ms = busy ? 0 : (tablet ? 2 : 8);
    for (const auto& event : p_.window.PollEvents(wait_ms, kSdlEventsPerPass)) {
      using Kind = ui::UiEvent::Kind;
      switch (event.kind) {
        case Kind::kPointerDown:
        case Kind::kPointerMove:
        case Kind::kPointerUp:
          // A working tablet speaks through libinput instead; unplugged, the mouse/touch stands in.
          if (p_.control.PointerActive()) OnPen(event.stylus);
          break;
        case Kind::kTokenKey:
          if (event.token >= 0) {
            p_.devices.switches.keyboard->OnKey(static_cast<char>('1' + event.token), true,
                                                event.time_ns);
          }
          break;
        case Kind::kRecordKey:
          p_.devices.switches.keyboard->OnKey('r', event.pressed, event.time_ns);
          break;
        case Kind::kLanguageKey:
          if (p_.engine.NextLanguage(event.time_ns)) {
            p_.log.Info("session", "language " + p_.engine.language());
            p_.view.view().Invalidate();
          }
          break;
        case Kind::kStaffChord:
          p_.engine.OnStaffChord(event.time_ns);
          p_.log.Info("staff", event.pressed ? "staff panel opened" : "staff panel closed");
          break;
        case Kind::kRedraw:
          p_.view.view().Invalidate();
          break;
      }
    }
  }

  // Every reading, from the tablet or the pointer: the dent follows it; while the staff panel is
  // open a touch on a button works the button, anywhere else it still explores.
  void OnPen(const platform::PenReading& pen) {
    last_pen_ = pen;
    p_.view.OnStylus(pen);
    if (p_.window.staff_panel_open() && pen.tip_down) {
      const auto button = buttons_.At(static_cast<int>(pen.x_px), static_cast<int>(pen.y_px));
      if (button != kiosk::StaffButton::kCount) {
        if (staff_.Press(button, pen.time_ns, p_.engine, p_.log)) p_.view.view().Invalidate();
        return;
      }
    }
    p_.engine.OnPen(pen);
  }

  // The passive stroke's dent travels with its virtual probe (drawn like a pen's).
  void ShowPassiveStroke(std::int64_t now_ns) {
    if (const auto passive = p_.engine.passive_pen()) {
      p_.view.OnStylus(*passive);
      passive_shown_ = true;
    } else if (passive_shown_) {
      passive_shown_ = false;
      platform::PenReading lifted;
      lifted.time_ns = now_ns;
      lifted.x_px = last_pen_.x_px;
      lifted.y_px = last_pen_.y_px;
      p_.view.OnStylus(lifted);
    }
  }

  // The session decides whether the panel is open (it closes a forgotten one by itself).
  void FollowStaffPanel() {
    const bool open = p_.engine.session().staff_panel_open();
    if (p_.window.staff_panel_open() == open) return;
    p_.window.set_staff_panel_open(open);
    if (!open) p_.log.Info("staff", "staff panel closed (timeout)");
    p_.view.view().Invalidate();
  }

  // Ambient-adaptive sound gain (gains.ambient_adaptive): the microphone's meter while the
  // attract screen is up, a few times a second.
  void AdaptToAmbient(double now_s) {
    if (!p_.config.ambient_adaptive || !p_.engine.recorder_present() ||
        now_s - ambient_last_s_ < 0.25) {
      return;
    }
    const double dt_s = ambient_last_s_ < 0.0 ? 0.25 : now_s - ambient_last_s_;
    ambient_last_s_ = now_s;
    const double level = std::max(static_cast<double>(p_.engine.mic_level()), 1e-6);
    // Only while the kiosk itself is quiet (between passive strokes, no cue): the microphone
    // would otherwise hear the box and turn it up further.
    ambient_.Update(
        20.0 * std::log10(level), dt_s,
        p_.engine.session().mode() == kiosk::SessionMode::kAttract && p_.engine.AmbientListening());
    p_.engine.SetAmbientGainDb(ambient_.gain_db());
  }

  // The health metrics file, every few seconds and soon after a device's state changed. Written
  // on this thread (a small file; the counters file is saved here too), never the audio thread.
  void WriteMetrics(std::int64_t now_ns) {
    // The board is looked at four times a second, not every pass (it copies the table).
    if (!metrics_.enabled() || now_ns - metrics_checked_ns_ < 250 * platform::kNsPerMs) return;
    metrics_checked_ns_ = now_ns;
    const auto devices = p_.board.All();
    std::string state_key = p_.config_accepted ? "config accepted;" : "config rejected;";
    for (const auto& device : devices) {
      state_key += device.device + "=" + platform::DeviceStateName(device.state) + ";";
    }
    if (!metrics_.Due(now_ns, state_key)) return;
    kiosk::HealthSnapshot snapshot;
    snapshot.version = kVersion;
    snapshot.box_name = box_name_;
    snapshot.start_time_s = p_.started_unix_s;
    snapshot.uptime_s = static_cast<double>(now_ns - p_.started_ns) * 1e-9;
    snapshot.devices = devices;
    const platform::AudioCallbackStats audio = p_.devices.output->Stats();
    snapshot.xruns = audio.xruns;
    if (audio.heartbeat_ns > 0) {
      snapshot.audio_callback_age_s =
          std::max(0.0, static_cast<double>(now_ns - audio.heartbeat_ns) * 1e-9);
    }
    snapshot.counters = p_.engine.PersistedCounters();
    snapshot.texture_keys = p_.engine.counter_keys();
    snapshot.speaker_leq_last_hour_dbfs = p_.engine.exposure().LastHourDb();
    const kiosk::SurfaceChoice shown = p_.engine.surface();
    snapshot.texture_shown =
        shown.voice ? "voice" : p_.engine.textures()[static_cast<std::size_t>(shown.texture)].key;
    snapshot.config_accepted = p_.config_accepted;
    metrics_.Write(now_ns, state_key, kiosk::FormatHealthMetrics(snapshot));
  }

  void Draw(double now_s) {
    ui::Overlays staff_overlays;
    if (p_.window.staff_panel_open()) {
      if (staff_view_.Due(now_s)) {
        const kiosk::StaffPanelInputs inputs{&p_.engine,
                                             p_.devices.output.get(),
                                             &p_.board,
                                             &p_.devices.switches,
                                             &p_.control.selector(),
                                             p_.control.record_down(),
                                             last_pen_,
                                             p_.config_line,
                                             p_.config.buffer_frames,
                                             p_.config.sample_rate_hz};
        staff_view_.Build(kiosk::StaffPanelLines(inputs), kiosk::StaffButtonCaptions(p_.engine),
                          p_.engine.low_vibration(), p_.view.text(), width_, height_, now_s);
      }
      staff_overlays = staff_view_.overlays();
    }
    const std::int64_t start_ns = platform::MonotonicNowNs();
    if (p_.view.Advance(now_s, p_.window.staff_panel_open(), std::move(staff_overlays))) {
      p_.window.Present(p_.view.view().TakeFrame());
      if (p_.backends.on_present) p_.backends.on_present(platform::MonotonicNowNs());
      if (!ready_) WarmUp(platform::MonotonicNowNs() - start_ns);
    }
  }

  // The first frames of a cold renderer can each take many seconds (a software GL compiling its
  // shaders under emulation took 9.5 and 19 s, and the next frame again over 10 s), and systemd's
  // watchdog (10 s) runs from READY=1. So the kiosk is ready once a frame draws at an interactive
  // pace; frames before that are start-up stages, each extending the start timeout. After
  // kMaxWarmUpFrames it is ready anyway, with a warning: a display that stays that slow is a fault
  // the watchdog is there to catch.
  static constexpr int kMaxWarmUpFrames = 8;
  void WarmUp(std::int64_t draw_ns) {
    ++warm_up_frames_;
    char frame[64];
    std::snprintf(frame, sizeof frame, "frame %d took %.1f s", warm_up_frames_,
                  static_cast<double>(draw_ns) * 1e-9);
    if (draw_ns <= kSlowPassNs) {
      AnnounceReady();
    } else if (warm_up_frames_ >= kMaxWarmUpFrames) {
      p_.log.Warn("kiosk",
                  std::string("the display is still slow (") + frame + "); starting anyway");
      AnnounceReady();
    } else {
      ReportStartStage(notifier_, std::string("drawing: ") + frame);
    }
  }

  // The first frame is on the screen: the kiosk is up for systemd (READY=1; its watchdog runs from
  // here, fed after every pass) and for whoever started it (one line on `out`).
  void AnnounceReady() {
    ready_ = true;
    p_.watchdog.Ready("exploring");
    const auto& pen = p_.devices.pen;
    const char* pen_kind = !pen               ? "mouse/touch"
                           : pen->Connected() ? "libinput"
                                              : "mouse/touch (libinput waiting for a tablet)";
    std::fprintf(p_.out, "kiosk ready %dx%d %s (%s), audio %s, pen %s, switches %s\n", width_,
                 height_, p_.window.driver().c_str(), p_.window.renderer_name().c_str(),
                 p_.devices.output->Running() ? "running" : "silent", pen_kind,
                 p_.devices.switches.ActiveBackend());
    std::fflush(p_.out);
  }

  LoopParts p_;
  int width_, height_;
  StaffButtons buttons_;
  kiosk::StaffPanel staff_;
  StaffPanelView staff_view_;
  platform::PenReading last_pen_{};
  kiosk::AmbientGain ambient_;
  kiosk::HealthMetricsWriter metrics_;
  std::string box_name_;
  std::int64_t metrics_checked_ns_ = 0;
  double ambient_last_s_ = -1.0;
  bool passive_shown_ = false;  // the view is drawing the passive stroke's dent
  bool ready_ = false;          // a frame drew at an interactive pace and READY=1 was sent
  bool pinged_ = false;         // the last pass's watchdog tick pinged (every thread alive)
  // Pings while a frame draws: every 2 s (the watched threads' heartbeat age, a fifth of the
  // unit's WatchdogSec), for at most 60 s of one frame.
  platform::BusyKeeper draw_keeper_{[] { platform::SystemdNotifier{}.Ping(); },
                                    2'000 * platform::kNsPerMs, 60'000 * platform::kNsPerMs};
  int warm_up_frames_ = 0;  // frames presented before that
  platform::SystemdNotifier notifier_{};
  int slow_passes_ = 0;  // passes over kSlowPassNs since the last report
  std::int64_t slow_reported_ns_ = 0;
};

}  // namespace

int RunKiosk(const std::vector<std::string>& args, std::FILE* out, std::FILE* err,
             const KioskBackends& backends) {
  const std::int64_t started_ns = platform::MonotonicNowNs();
  const double started_unix_s = static_cast<double>(std::time(nullptr));
  KioskArgs options;
  if (const int code = ParseKioskArgs(args, out, err, options); code >= 0) return code;
  // SIGHUP (the unit's reload) or SIGUSR1 would otherwise end the kiosk and lose the counters
  // since the last save; the loop saves them, or reports the status, instead (one arriving while
  // the textures load waits for the first pass). A closed stdout/stderr pipe must not end it
  // either.
  kiosk::CatchHangupAndIgnoreWriteSignals();
  kiosk::TuneAllocatorForLongRuns();
  auto& log = platform::DefaultLogger();
  platform::DeviceStatusBoard board(log);
  const platform::SystemdNotifier notifier;
  const auto started = [&notifier](const char* stage) { ReportStartStage(notifier, stage); };
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
  started("configuration read, opening the display");

  ui::KioskWindow window;
  if (!OpenWindow(config, log, window)) return 1;
  started("display open, loading the textures");
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
  started("textures loaded, opening the devices");
  kiosk::ReportTextures(board, *engine);

  LiveDevices devices = OpenDevices(config, *engine, board, backends, width, height);
  kiosk::KioskControl control(*engine,
                              {devices.output.get(), devices.pen.get(), &devices.switches, &board,
                               engine->recorder_present() ? devices.input.get() : nullptr},
                              log);
  platform::WatchdogSupervisor watchdog(2'000 * platform::kNsPerMs);
  WatchDeviceThreads(watchdog, devices);
  watchdog.ReportTo(&log);
  started("devices open, drawing the first frame");

  // A relative metrics file is in the state folder (the package links it into node-exporter's).
  std::string metrics_path;
  if (!config.metrics_file.empty()) {
    metrics_path = (fs::path(options.state_dir) / config.metrics_file).string();
  }
  LiveLoop({config, kiosk::ConfigStatusLine(options.config_path, loaded), window, *engine, *view,
            devices, control, board, watchdog, log, backends, out, metrics_path,
            loaded.source == kiosk::ConfigLoadResult::Source::kFile, started_ns, started_unix_s})
      .Run();
  control.Shutdown();
  devices.input->Stop();
  engine->SetRecorder(nullptr);
  devices.input->recorder().Wipe();
  window.Close();
  return 0;
}

}  // namespace sas::app
