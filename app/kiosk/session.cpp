// The kiosk Session state machine (see session.h for the rules).
#include "kiosk/session.h"

#include <algorithm>
#include <numeric>

namespace sas::kiosk {

double AttractCycleS(const SessionConfig& config) {
  return std::accumulate(config.attract_slots_s.begin(), config.attract_slots_s.end(), 0.0);
}

Session::Session(const SessionConfig& config) : config_(config) {
  config_.texture_count = std::max(config_.texture_count, 1);
  config_.default_texture = ClampTexture(config_.default_texture);
  surface_ = {false, config_.default_texture};
  counters_.strokes_per_texture.assign(static_cast<std::size_t>(config_.texture_count), 0);
}

int Session::ClampTexture(int texture) const {
  return std::clamp(texture, 0, config_.texture_count - 1);
}

void Session::Emit(SessionAction::Kind kind) {
  actions_.push_back({kind});
}

void Session::Speak(Cue cue, int texture) {
  SessionAction action{SessionAction::Kind::kSpeak};
  action.cue = cue;
  action.surface = {false, texture};
  actions_.push_back(action);
}

void Session::Show(SurfaceChoice surface, bool speak_name) {
  if (surface == surface_) return;
  surface_ = surface;
  SessionAction action{SessionAction::Kind::kShowSurface};
  action.surface = surface;
  actions_.push_back(action);
  if (speak_name && !surface.voice) {
    Speak(Cue::kTextureName, surface.texture);
    named_ = true;
  }
}

// The texture under the pen is named once when a visit starts, however it starts.
void Session::NameTexture() {
  if (named_ || surface_.voice) return;
  named_ = true;
  Speak(Cue::kTextureName, surface_.texture);
}

// Any visitor activity: leaves the attract screen and restarts the idle timer. The visit itself
// is counted at the first pen contact (OnPen).
void Session::Activity(double now_s) {
  last_activity_s_ = now_s;
  if (mode_ == SessionMode::kAttract) {
    mode_ = SessionMode::kExploring;
    Emit(SessionAction::Kind::kLeaveAttract);
  }
}

void Session::OnPen(double now_s, bool tip_down) {
  // A hover over the attract screen is nobody yet (a nudged mouse, a pen lying by the display).
  if (!tip_down && !tip_down_ && mode_ == SessionMode::kAttract) return;
  Activity(now_s);
  if (tip_down && !tip_down_) {
    if (!visit_counted_) {
      visit_counted_ = true;
      CountOne(counters_.sessions);
      NameTexture();
    }
    if (surface_.voice) {
      CountOne(counters_.voice_strokes);
    } else {
      CountOne(counters_.strokes_per_texture[static_cast<std::size_t>(surface_.texture)]);
    }
  }
  tip_down_ = tip_down;
}

void Session::OnTokenSelection(double now_s, int texture) {
  Activity(now_s);
  token_texture_ = texture < 0 ? -1 : ClampTexture(texture);
  // A token placed while recording does not interrupt the take; it applies afterwards.
  if (mode_ == SessionMode::kCountdown || mode_ == SessionMode::kRecording) return;
  const SurfaceChoice choice{false, token_texture_ < 0 ? config_.default_texture : token_texture_};
  if (choice == surface_) {
    NameTexture();  // the token chose what was shown already: still named once
  } else {
    Show(choice, true);
  }
}

void Session::CancelRecordingFlow(bool speak_description) {
  if (mode_ == SessionMode::kRecording) Emit(SessionAction::Kind::kCancelRecording);
  mode_ = SessionMode::kExploring;
  if (speak_description) {
    Speak(Cue::kTextureDescription, surface_.voice ? config_.default_texture : surface_.texture);
  }
}

void Session::OnRecordButton(double now_s, bool pressed) {
  Activity(now_s);
  if (pressed == button_down_) return;  // repeated level, not an edge
  button_down_ = pressed;
  if (!pressed) return;
  button_down_since_s_ = now_s;
  hold_handled_ = false;
  switch (mode_) {
    case SessionMode::kExploring:
    case SessionMode::kAttract:
      mode_ = SessionMode::kCountdown;
      phase_started_s_ = now_s;
      next_count_ = 3;
      Speak(Cue::kRecordCountdown, surface_.texture);
      break;
    case SessionMode::kCountdown:
      // Second press: the visitor wants to know more, not to record.
      hold_handled_ = true;
      CancelRecordingFlow(true);
      break;
    case SessionMode::kRecording:
      // A press while recording ends the take early.
      Emit(SessionAction::Kind::kStopRecording);
      mode_ = SessionMode::kExploring;
      break;
  }
}

void Session::OnRecordingFinished(double now_s, RecordingOutcome outcome) {
  Activity(now_s);
  mode_ = SessionMode::kExploring;
  switch (outcome) {
    case RecordingOutcome::kOk:
      CountOne(counters_.recordings);
      has_voice_ = true;
      surface_ = {false, -1};  // force the cross-fade even from a previous voice surface
      Show({true, 0}, false);
      Speak(Cue::kVoiceReady, 0);
      return;
    case RecordingOutcome::kSilent:
      Speak(Cue::kRecordingTooQuiet, surface_.texture);
      break;
    case RecordingOutcome::kClipped:
      Speak(Cue::kRecordingTooLoud, surface_.texture);
      break;
    case RecordingOutcome::kNoMicrophone:
      Speak(Cue::kRecordingUnavailable, surface_.texture);
      break;
  }
  CountOne(counters_.failed_recordings);
}

void Session::OnStaffChord(double now_s) {
  last_activity_s_ = now_s;
  staff_last_s_ = now_s;
  staff_panel_open_ = !staff_panel_open_;
  SessionAction action{SessionAction::Kind::kStaffPanel};
  action.open = staff_panel_open_;
  actions_.push_back(action);
}

void Session::OnPenRest(double now_s) {
  Activity(now_s);
  // Exploring a texture only: a voice has no description, and a take is not interrupted.
  if (mode_ != SessionMode::kExploring || surface_.voice) return;
  Speak(Cue::kTextureDescription, surface_.texture);
}

// The countdown's spoken numbers and the tone, each once, at fixed times after the press: the
// tone ends where the recording starts, the numbers a step apart before it (the step shrinks
// when the countdown is too short for 1 s steps after the intro sentence).
void Session::CountDown(double now_s) {
  const double tone_at = std::max(0.0, config_.countdown_s - config_.tone_s);
  const double step = std::min(config_.count_step_s, tone_at / 4.0);
  const double elapsed = now_s - phase_started_s_;
  while (next_count_ >= 0 && elapsed >= tone_at - next_count_ * step) {
    if (next_count_ > 0) {
      SessionAction action{SessionAction::Kind::kSpeak};
      action.cue = Cue::kCount;
      action.count = next_count_;
      action.surface = surface_;
      actions_.push_back(action);
    } else {
      Speak(Cue::kRecordTone, surface_.texture);
    }
    --next_count_;
  }
}

void Session::OnStaffActivity(double now_s) {
  staff_last_s_ = now_s;
  last_activity_s_ = now_s;
}

void Session::Tick(double now_s) {
  if (staff_panel_open_ && now_s - staff_last_s_ >= config_.staff_panel_timeout_s) {
    // Forgotten open: close it, and the idle timer starts from now (the staff just left).
    staff_panel_open_ = false;
    last_activity_s_ = now_s;
    SessionAction action{SessionAction::Kind::kStaffPanel};
    action.open = false;
    actions_.push_back(action);
  }
  if (button_down_ && !hold_handled_ && now_s - button_down_since_s_ >= config_.long_hold_s) {
    hold_handled_ = true;
    last_activity_s_ = now_s;
    CancelRecordingFlow(true);
  }
  if (mode_ == SessionMode::kCountdown) CountDown(now_s);
  AttractCycle(now_s);
  if (mode_ == SessionMode::kCountdown && now_s - phase_started_s_ >= config_.countdown_s) {
    mode_ = SessionMode::kRecording;
    phase_started_s_ = now_s;
    Emit(SessionAction::Kind::kStartRecording);
  } else if (mode_ == SessionMode::kRecording && now_s - phase_started_s_ >= config_.record_max_s) {
    mode_ = SessionMode::kExploring;  // the recorder reports back through OnRecordingFinished
    Emit(SessionAction::Kind::kStopRecording);
  }
  // The idle reset never interrupts a recording in progress, nor the staff at work.
  const bool busy = mode_ == SessionMode::kCountdown || mode_ == SessionMode::kRecording ||
                    staff_panel_open_ || tip_down_;
  if (mode_ != SessionMode::kAttract && !busy &&
      now_s - last_activity_s_ >= config_.idle_timeout_s) {
    mode_ = SessionMode::kAttract;
    visit_counted_ = false;
    named_ = false;
    next_slot_ = 0;
    next_slot_s_ = now_s;  // the cycle starts over with the configured language
    if (has_voice_) {
      has_voice_ = false;
      Emit(SessionAction::Kind::kWipeVoice);
    }
    Emit(SessionAction::Kind::kResetTextures);
    // The texture of a token left on a switch (the switches report edges, so nothing else would
    // bring it back), else the default one. Not spoken: nobody is there to hear it.
    Show({false, token_texture_ < 0 ? config_.default_texture : token_texture_}, false);
    Emit(SessionAction::Kind::kEnterAttract);
  }
}

void Session::AttractCycle(double now_s) {
  const auto& slots = config_.attract_slots_s;
  if (mode_ != SessionMode::kAttract || slots.empty()) return;
  if (staff_panel_open_) {
    next_slot_s_ = std::max(next_slot_s_, now_s);  // resumes where it was once the panel closes
    return;
  }
  if (now_s < next_slot_s_) return;
  SessionAction action{SessionAction::Kind::kAttractLanguage};
  action.count = next_slot_;
  actions_.push_back(action);
  Speak(Cue::kInvitation, surface_.texture);
  // From now, not from when the slot was due: a late tick never squeezes the next language.
  next_slot_s_ = now_s + slots[static_cast<std::size_t>(next_slot_)];
  next_slot_ = (next_slot_ + 1) % static_cast<int>(slots.size());
}

std::vector<SessionAction> Session::TakeActions() {
  std::vector<SessionAction> taken;
  taken.swap(actions_);
  return taken;
}

double Session::SecondsLeft(double now_s) const {
  if (mode_ == SessionMode::kCountdown) {
    return std::max(0.0, config_.countdown_s - (now_s - phase_started_s_));
  }
  if (mode_ == SessionMode::kRecording) {
    return std::max(0.0, config_.record_max_s - (now_s - phase_started_s_));
  }
  return 0.0;
}

void Session::RestoreCounters(const UsageCounters& counters) {
  counters_ = counters;
  counters_.strokes_per_texture.resize(static_cast<std::size_t>(config_.texture_count), 0);
}

}  // namespace sas::kiosk
