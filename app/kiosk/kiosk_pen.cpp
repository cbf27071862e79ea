// The kiosk engine's pen side (see kiosk_engine.h): screen pixels -> field samples, each pen
// sample -> a ProbeCommand for the player (gesture.h mapping, per-stroke loudness correction,
// bubble pops), the pen's rest for the layered description, and the attract screen's passive
// stroke.
#include "kiosk/kiosk_engine.h"

#include <algorithm>
#include <cmath>

#include "surface/image_surface.h"

namespace sas::kiosk {
namespace {

// Speed a bubble's pop at strength 1 gives the probe (m/s), as an impulse on the material's probe
// mass: well above a tap's landing speed, so a pop stands out from the rubbing around it. A speed,
// not an impulse, so the pop's sound does not depend on how heavy the pen's nib is.
constexpr double kPopSpeedMps = 0.4;
// Tip force a pen's full pressure stands for when pressing a bubble (N). The synth's mapping tops
// out at 2 N (gesture.h: what a stroke feels), below the bubbles' 2.5 N pop force; a pen
// saturates its pressure scale at roughly 4 N of tip force, so a firm press (pressure > 0.6) pops.
constexpr double kBubblePressMaxForceN = 4.0;
// The pen counts as resting while it stays within this radius of where it settled (a hand holding
// a pen still drifts by a millimetre or two).
constexpr double kRestRadiusMm = 3.0;
// The passive stroke (attract): a gentle, slow stroke in bursts, with quiet gaps between them in
// which the microphone measures the room (ambient gain), kPassiveGainDb below a visitor's stroke.
constexpr double kPassiveBurstS = 8.0;
constexpr double kPassiveGapS = 6.0;
constexpr double kPassiveRingOutS = 1.0;  // after a burst, before the room is measured again
constexpr double kPassiveSpeedMmS = 60.0;
constexpr double kPassivePressure = 0.35;
// Per-stroke gain ramps (stroke_gain.h): while a stroke plays, over 20 ms (no audible step); for
// the first kLandingWindowS of a stroke over 1 ms, so the landing click gets the stroke's gain.
constexpr double kStrokeRampS = 0.02;
constexpr double kLandingRampS = 0.001;
constexpr double kLandingWindowS = 0.01;

}  // namespace

void KioskEngine::ScreenToField(double x_px, double y_px, double* fx, double* fy) const {
  // The picture covers the screen (picture_io.h ResizeToCover): uniform scale, centred crop.
  const auto& field = *current_field_;
  const double sw = options_.screen_width_px, sh = options_.screen_height_px;
  const double scale = std::max(sw / field.width(), sh / field.height());
  const double crop_x = (field.width() * scale - sw) / 2.0;
  const double crop_y = (field.height() * scale - sh) / 2.0;
  *fx = (x_px + crop_x) / scale;
  *fy = (y_px + crop_y) / scale;
}

void KioskEngine::FieldToScreen(double fx, double fy, double* x_px, double* y_px) const {
  const auto& field = *current_field_;
  const double sw = options_.screen_width_px, sh = options_.screen_height_px;
  const double scale = std::max(sw / field.width(), sh / field.height());
  *x_px = fx * scale - (field.width() * scale - sw) / 2.0;
  *y_px = fy * scale - (field.height() * scale - sh) / 2.0;
}

const surface::BubbleWrapState* KioskEngine::bubbles() const {
  if (bubble_texture_ < 0) return nullptr;
  const auto& state = textures_[static_cast<std::size_t>(bubble_texture_)].loaded.bubbles;
  return state ? &*state : nullptr;
}

int KioskEngine::popped_bubbles() const {
  const auto* state = bubbles();
  return state ? state->popped_count() : 0;
}

ProbeShape KioskEngine::UntiltedProbe(const SurfaceChoice& choice) const {
  if (choice.voice) return {kVoiceWidthMm, synth::ProbeStyle::kScrape};
  const auto& probe = textures_[static_cast<std::size_t>(choice.texture)].loaded.file.probe;
  return {probe.width_mm, probe.style};
}

void KioskEngine::OnPen(const platform::PenReading& pen, std::optional<synth::ProbeStyle> style) {
  last_now_ns_ = std::max(last_now_ns_, pen.time_ns);
  session_.OnPen(static_cast<double>(pen.time_ns) * 1e-9, pen.tip_down);
  WatchPenRest(pen);
  if (passive_down_) {
    // The passive probe owns the scene until a visitor touches: a hover over the attract screen
    // must not lift it; a touch takes the probe over where the pen is (its command follows).
    if (!pen.tip_down && session_.mode() == SessionMode::kAttract) return;
    passive_down_ = false;
  }
  const auto& field = *current_field_;
  double fx = 0.0, fy = 0.0;
  ScreenToField(pen.x_px, pen.y_px, &fx, &fy);
  const double pitch = field.pitch_m();
  double x_m = fx * pitch, y_m = fy * pitch;
  const double pressure = std::clamp(pen.pressure, 0.0, 1.0);

  synth::ProbeCommand command;
  command.tip_down = pen.tip_down && pressure > 0.0;
  // A barrel button pressed or released mid-stroke comes between two position reports and
  // carries the last one: the stroke goes on from where the scene has carried the probe since, at
  // the same speed, so the style switch neither stops nor pulls back the probe (either would be a
  // step under the tip). The next report's speed then spans the whole interval again. Long after
  // the last report the pen has stopped: then the button's reading is an ordinary one.
  const double since_last_s =
      have_last_pen_ ? static_cast<double>(pen.time_ns - last_pen_.time_ns) * 1e-9 : 0.0;
  const bool continuation = pen.kind == platform::PenReadingKind::kButton && command.tip_down &&
                            have_last_pen_ && last_pen_.tip_down && since_last_s >= 0.0 &&
                            since_last_s <= kMaxReportGapS;
  if (continuation) {
    x_m = last_fx_ + dir_x_ * last_velocity_mps_ * since_last_s;
    y_m = last_fy_ + dir_y_ * last_velocity_mps_ * since_last_s;
    fx = x_m / pitch;
    fy = y_m / pitch;
    command.velocity_mps = last_velocity_mps_;
  }
  command.x_m = x_m;
  command.y_m = y_m;
  if (!continuation && command.tip_down && have_last_pen_ && last_pen_.tip_down) {
    const double dx = x_m - last_fx_, dy = y_m - last_fy_;
    const double distance = std::hypot(dx, dy);
    const double dt_s = std::max(1e-3, static_cast<double>(pen.time_ns - last_pen_.time_ns) * 1e-9);
    command.velocity_mps = distance / dt_s;
    if (distance > 1e-9) {
      dir_x_ = dx / distance;
      dir_y_ = dy / distance;
    }
  }
  command.direction_x = dir_x_;
  command.direction_y = dir_y_;
  const SurfaceChoice choice = session_.surface();
  ApplyPenReading(pen, current_relief_m_, UntiltedProbe(choice), style, mapping_, command);

  // Per-stroke loudness matching (stroke_gain.h): the smoothed stroke's correction for the scene
  // the pen plays; held while the pen is up. The speed counts hover reports too (touch-down).
  if (!continuation) {
    const double dt_s =
        have_last_pen_ ? static_cast<double>(pen.time_ns - last_pen_.time_ns) * 1e-9 : 0.0;
    const bool recent = have_last_pen_ && dt_s > 0.0 && dt_s <= kMaxReportGapS;
    const double speed_mm_s =
        recent ? std::hypot(x_m - last_fx_, y_m - last_fy_) / dt_s * 1e3 : 0.0;
    stroke_.Update(command.tip_down, recent, speed_mm_s, pressure, dt_s);
  }
  if (command.tip_down && !(have_last_pen_ && last_pen_.tip_down)) stroke_down_ns_ = pen.time_ns;
  auto& control = player_->control();
  if (command.tip_down && control.current_slot() >= 0) {
    stroke_style_ = command.style;
    stroke_width_mm_ = command.width_mm;
    stroke_correction_ = CorrectionFor(stroke_texture_);
    // Landing: the new stroke's gain must be in place when its landing click (the loudest part
    // of a slow stroke) sounds, one buffer from now, so it ramps over kLandingRampS; the scene
    // only rings out the last stroke's tail meanwhile. Then over the scene's 20 ms.
    const bool landing =
        static_cast<double>(pen.time_ns - stroke_down_ns_) * 1e-9 < kLandingWindowS;
    control.scene(control.current_slot())
        .SetStrokeGains(std::pow(10.0, stroke_correction_.sound_db / 20.0),
                        std::pow(10.0, stroke_correction_.haptic_db / 20.0),
                        landing ? kLandingRampS : kStrokeRampS);
  }

  // Bubble wrap: a hard enough press pops the bubble under the tip (a burst through the contact).
  if (command.tip_down && !choice.voice && choice.texture == bubble_texture_) {
    auto& state = textures_[static_cast<std::size_t>(bubble_texture_)].loaded.bubbles;
    if (state) {
      if (const auto pop = state->Press(fx, fy, pressure * kBubblePressMaxForceN)) {
        command.burst_impulse_n_s =
            kPopSpeedMps *
            textures_[static_cast<std::size_t>(bubble_texture_)].material.params.probe.mass_kg *
            pop->strength;
        bubbles_dirty_ = true;
      }
    }
  }

  control.Probe(pen.time_ns, command);
  if (continuation) return;
  have_last_pen_ = true;
  last_pen_ = pen;
  last_fx_ = x_m;
  last_fy_ = y_m;
  last_velocity_mps_ = command.velocity_mps;
}

void KioskEngine::WatchPenRest(const platform::PenReading& pen) {
  if (!pen.tip_down || pen.pressure <= 0.0) {
    rest_since_ns_ = -1;
    return;
  }
  const double radius_px = kRestRadiusMm / surface::DisplayGeometry{}.pixel_pitch_mm();
  if (rest_since_ns_ < 0 || std::hypot(pen.x_px - rest_x_px_, pen.y_px - rest_y_px_) > radius_px) {
    // Touched down or moved on: a new place to rest, described again when the pen stops there.
    rest_x_px_ = pen.x_px;
    rest_y_px_ = pen.y_px;
    rest_since_ns_ = pen.time_ns;
    rest_spoken_ = false;
  }
}

void KioskEngine::LiftPassiveProbe(std::int64_t now_ns) {
  if (!passive_down_) return;
  passive_down_ = false;
  passive_quiet_since_ns_ = now_ns;
  synth::ProbeCommand lift = last_passive_command_;
  lift.tip_down = false;
  lift.velocity_mps = 0.0;
  player_->control().Probe(now_ns, lift);
}

void KioskEngine::PassiveStroke(std::int64_t now_ns) {
  // The stroke belongs to the attract screen alone, with nobody at the box: whatever ends it (a
  // key, a token, the record button, the staff panel opening over it) lifts the probe, or the
  // scene would go on scraping at the last place for the whole visit.
  const bool attract = session_.mode() == SessionMode::kAttract && !session_.staff_panel_open();
  if (!options_.attract_stroke || !attract) {
    passive_started_ns_ = -1;
    LiftPassiveProbe(now_ns);
    return;
  }
  if (passive_started_ns_ < 0) passive_started_ns_ = now_ns;
  const double t_s = static_cast<double>(now_ns - passive_started_ns_) * 1e-9;
  const double cycle_s = kPassiveBurstS + kPassiveGapS;
  const double in_cycle_s = std::fmod(t_s, cycle_s);
  // A quiet gap first, so the attract screen starts in silence after a visit.
  const bool down = in_cycle_s >= kPassiveGapS;
  if (!down) {
    LiftPassiveProbe(now_ns);
    return;
  }
  // Back and forth across the middle of the picture along a gentle wave: the whole burst covers
  // kPassiveSpeedMmS * kPassiveBurstS of the surface at a steady speed.
  const double pitch_mm = surface::DisplayGeometry{}.pixel_pitch_mm();
  const double sw = options_.screen_width_px, sh = options_.screen_height_px;
  const double span_px = 0.5 * sw;
  const double travelled_px = (in_cycle_s - kPassiveGapS) * kPassiveSpeedMmS / pitch_mm;
  const double leg = std::fmod(travelled_px, 2.0 * span_px);
  const double along = leg < span_px ? leg : 2.0 * span_px - leg;
  platform::PenReading pen;
  pen.time_ns = now_ns;
  pen.x_px = 0.25 * sw + along;
  pen.y_px = 0.5 * sh + 0.08 * sh * std::sin(2.0 * 3.14159265358979 * along / span_px);
  pen.pressure = kPassivePressure;
  pen.tip_down = true;
  double fx = 0.0, fy = 0.0;
  ScreenToField(pen.x_px, pen.y_px, &fx, &fy);
  const double pitch_m = current_field_->pitch_m();
  synth::ProbeCommand command;
  command.tip_down = true;
  command.x_m = fx * pitch_m;
  command.y_m = fy * pitch_m;
  if (passive_down_) {
    const double dx = command.x_m - last_passive_command_.x_m;
    const double dy = command.y_m - last_passive_command_.y_m;
    const double distance = std::hypot(dx, dy);
    const double dt_s = std::max(1e-3, static_cast<double>(now_ns - passive_pen_.time_ns) * 1e-9);
    command.velocity_mps = distance / dt_s;
    if (distance > 1e-12) {
      command.direction_x = dx / distance;
      command.direction_y = dy / distance;
    }
  } else if (const int slot = player_->control().current_slot(); slot >= 0) {
    // The burst's level: the texture's own, this far down (a visitor's touch sets it anew).
    const double gain = std::pow(10.0, kPassiveGainDb / 20.0);
    player_->control().scene(slot).SetStrokeGains(gain, gain, kStrokeRampS);
  }
  // No tilt: the passive probe strokes with the texture's own probe.
  ApplyPenReading(pen, current_relief_m_, UntiltedProbe(session_.surface()), {}, mapping_, command);
  player_->control().Probe(now_ns, command);
  passive_down_ = true;
  passive_pen_ = pen;
  last_passive_command_ = command;
}

bool KioskEngine::AmbientListening() const {
  if (player_->control().clip_playing() || passive_down_) return false;
  return static_cast<double>(last_now_ns_ - passive_quiet_since_ns_) * 1e-9 >= kPassiveRingOutS;
}

}  // namespace sas::kiosk
