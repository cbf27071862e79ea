// The kiosk's control loop body (see kiosk_control.h).
#include "kiosk/kiosk_control.h"

#include <malloc.h>

#include "kiosk/kiosk_signals.h"

namespace sas::kiosk {

std::string ConfigStatusLine(const std::string& path, const ConfigLoadResult& loaded) {
  std::string line = "Configuration: " + path;
  if (loaded.problem.empty()) return line + " (accepted)";
  line += loaded.source == ConfigLoadResult::Source::kLastGood
              ? " rejected, running on the last good copy: "
              : " rejected, running on the built-in defaults: ";
  return line + loaded.problem;
}

void ReportConfig(platform::DeviceStatusBoard& board, const ConfigLoadResult& loaded) {
  if (loaded.problem.empty()) {
    board.Set("config", platform::DeviceState::kOk, "configuration file loaded");
  } else {
    // "missing" = absent or rejected at start, a fallback is in use (platform/README.md states).
    board.Set("config", platform::DeviceState::kMissing, "rejected: " + loaded.problem);
  }
}

void ReportTextures(platform::DeviceStatusBoard& board, const KioskEngine& engine) {
  const auto& failures = engine.texture_failures();
  if (failures.empty()) {
    board.Set("textures", platform::DeviceState::kOk,
              std::to_string(engine.textures().size()) + " textures loaded");
    return;
  }
  std::string message = std::to_string(engine.textures().size()) + " of " +
                        std::to_string(engine.textures().size() + failures.size()) +
                        " textures loaded; left out: ";
  for (std::size_t i = 0; i < failures.size(); ++i) message += (i ? "; " : "") + failures[i];
  board.Set("textures", platform::DeviceState::kMissing, message);
}

void TuneAllocatorForLongRuns() {
  // 256 kB: well above the control loop's small strings and vectors, well below a picture.
  // Setting it also turns off glibc's dynamic threshold, which otherwise rises to the size of
  // the largest block freed so far and moves every later field onto the heap.
  mallopt(M_MMAP_THRESHOLD, 256 * 1024);
}

KioskControl::KioskControl(KioskEngine& engine, KioskDevices devices, platform::Logger& log)
    : engine_(&engine), devices_(devices), log_(&log) {
  engine_->SetAudioRunning(devices_.output->Running());
}

bool KioskControl::PointerActive() const {
  return devices_.pen == nullptr || !devices_.pen->Connected();
}

std::vector<SessionAction> KioskControl::Step(std::int64_t now_ns, const PenHandler& on_pen) {
  backlog_ = false;
  if (devices_.pen != nullptr) {
    platform::PenReading reading;
    int taken = 0;
    while (taken < kPenReadingsPerStep && devices_.pen->Pop(reading)) {
      ++taken;
      last_pen_ = reading;
      on_pen(reading);
    }
    backlog_ = taken == kPenReadingsPerStep;
    const bool connected = devices_.pen->Connected();
    // An unplugged tablet's stroke is lifted only after the readings it sent before it went.
    if (!backlog_ && pen_was_connected_ && !connected && last_pen_.tip_down) {
      // Unplugged mid-stroke: no tip-up will ever come from it. Lift the stroke where it was.
      platform::PenReading lift = last_pen_;
      lift.time_ns = now_ns;
      lift.kind = platform::PenReadingKind::kTipUp;
      lift.tip_down = false;
      lift.in_proximity = false;
      lift.pressure = 0.0;
      last_pen_ = lift;
      on_pen(lift);
    }
    if (!backlog_) pen_was_connected_ = connected;
  }
  platform::SwitchEvent switch_event;
  int switch_events = 0;
  while (switch_events < kSwitchEventsPerStep && devices_.switches->Pop(switch_event)) {
    ++switch_events;
    if (switch_event.input == platform::kRecordInput) {
      record_down_ = switch_event.pressed;
      engine_->OnRecordButton(switch_event.time_ns, switch_event.pressed);
    } else if (selector_.Apply(switch_event)) {
      engine_->OnToken(switch_event.time_ns, selector_.Selected());
    }
  }
  if (switch_events == kSwitchEventsPerStep) backlog_ = true;
  auto actions = engine_->Tick(now_ns);
  if (!actions.empty()) LogSessionActions(*log_, *engine_, actions);
  devices_.output->Poll(now_ns);
  engine_->SetAudioRunning(devices_.output->Running());
  if (devices_.input != nullptr) {
    engine_->SetMicrophoneLive(now_ns, devices_.input->Delivering(now_ns));
  }
  return actions;
}

bool KioskControl::Shutdown() {
  log_->Info("kiosk", "stopping");
  std::string error;
  const bool saved = engine_->SaveCounters(&error);
  if (!saved) log_->Warn("counters", "not saved at stop: " + error);
  devices_.output->Stop();
  engine_->SetAudioRunning(false);
  return saved;
}

bool KioskControl::Hangup() {
  // Everything else (devices, textures, gains) was read at start; a reload would need a restart.
  const std::string config_note =
      "the configuration is read at start (restart the unit to apply changes)";
  std::string error;
  if (!engine_->SaveCounters(&error)) {
    log_->Warn("kiosk", "SIGHUP: usage counters not saved (" + error + "); " + config_note);
    return false;
  }
  log_->Info("kiosk", "SIGHUP: usage counters saved; " + config_note);
  return true;
}

void KioskControl::ReportStatus() {
  std::string line = "SIGUSR1: status:";
  if (devices_.board != nullptr) {
    for (const auto& status : devices_.board->All()) {
      line += " " + status.device + " " + platform::DeviceStateName(status.state) +
              (status.backend.empty() ? "" : " (" + status.backend + ")") + ";";
    }
  }
  line += " audio " + std::string(devices_.output->Running() ? "running" : "silent") + "; visits " +
          std::to_string(engine_->session().counters().sessions);
  log_->Info("kiosk", line);
}

bool KioskControl::HandleSignals() {
  if (kiosk::TakeHangupRequest()) Hangup();
  if (kiosk::TakeStatusRequest()) ReportStatus();
  return kiosk::StopRequested();
}

void LogSessionActions(platform::Logger& log, const KioskEngine& engine,
                       const std::vector<SessionAction>& actions) {
  using Kind = SessionAction::Kind;
  for (const auto& action : actions) {
    switch (action.kind) {
      case Kind::kShowSurface:
        log.Info("session",
                 action.surface.voice
                     ? std::string("showing the voice")
                     : "showing " +
                           engine.textures()[static_cast<std::size_t>(action.surface.texture)].key);
        break;
      case Kind::kStartRecording:
        log.Info("session", "recording started");
        break;
      case Kind::kStopRecording:
        log.Info("session", "recording stopped");
        break;
      case Kind::kCancelRecording:
        log.Info("session", "recording cancelled");
        break;
      case Kind::kWipeVoice:
        log.Info("session", "voice wiped");
        break;
      case Kind::kEnterAttract:
        log.Info("session", "idle reset: attract screen");
        break;
      case Kind::kLeaveAttract:
        log.Info("session", "visit started");
        break;
      case Kind::kSpeak:
        if (action.cue == Cue::kRecordingTooQuiet) log.Info("session", "recording too quiet");
        if (action.cue == Cue::kRecordingTooLoud) log.Info("session", "recording too loud");
        if (action.cue == Cue::kRecordingUnavailable) {
          log.Info("session", "recording unavailable (no microphone)");
        }
        break;
      default:
        break;
    }
  }
}

}  // namespace sas::kiosk
