// Driving the kiosk engine on its virtual clock (see virtual_visit.h).
#include "kiosk/virtual_visit.h"

#include <algorithm>
#include <cmath>

namespace sas::kiosk {

PenScript StraightStroke(const PenStroke& stroke, double t0_s, int width_px, int height_px) {
  return [stroke, t0_s, width_px, height_px](double t_s) -> std::optional<ScriptedPen> {
    const double since_touch_s = t_s - t0_s - stroke.hover_s;
    const double u =
        std::clamp(since_touch_s / stroke.duration_s, -stroke.hover_s / stroke.duration_s, 1.0);
    platform::PenReading pen;
    pen.origin = platform::PenOrigin::kTablet;
    pen.x_px = (stroke.x0 + (stroke.x1 - stroke.x0) * u) * width_px;
    pen.y_px = (stroke.y0 + (stroke.y1 - stroke.y0) * u) * height_px;
    pen.tip_down = since_touch_s >= 0.0 && since_touch_s < stroke.duration_s;
    pen.in_proximity = true;
    pen.pressure = pen.tip_down ? stroke.pressure : 0.0;
    pen.tilt_x_deg = stroke.tilt_deg;
    return ScriptedPen{pen, stroke.style};
  };
}

PenScript GesturePenScript(Gesture gesture, const KioskEngine& engine, double t0_s,
                           std::optional<synth::ProbeStyle> style) {
  return [gesture = std::move(gesture), engine = &engine, t0_s,
          style](double t_s) -> std::optional<ScriptedPen> {
    const double since_s = t_s - t0_s;
    if (since_s < 0.0) return std::nullopt;
    const GestureSample at = GestureAt(gesture, since_s);
    const double pitch_mm = engine->current_field()->pitch_m() * 1e3;
    platform::PenReading pen;
    pen.origin = platform::PenOrigin::kTablet;
    engine->FieldToScreen(at.x_mm / pitch_mm, at.y_mm / pitch_mm, &pen.x_px, &pen.y_px);
    pen.tip_down = since_s < gesture.duration_s() && at.pressure > kGesturePenUpPressure;
    pen.in_proximity = true;
    pen.pressure = pen.tip_down ? at.pressure : 0.0;
    pen.tilt_x_deg = at.tilt_deg;
    return ScriptedPen{pen, style};
  };
}

VirtualVisit::VirtualVisit(KioskEngine& engine, Hooks hooks, bool keep_output, double pen_rate_hz)
    : engine_(engine),
      hooks_(std::move(hooks)),
      keep_output_(keep_output),
      pen_period_ns_(std::floor(1e9 / pen_rate_hz)),
      fs_hz_(engine.config().sample_rate_hz),
      block_frames_(engine.config().buffer_frames),
      core_(engine.audio()),
      block_(static_cast<std::size_t>(block_frames_) * 2) {
  engine_.SetAudioRunning(true);  // the callback core below is the audio thread
}

void VirtualVisit::SetVoice(std::vector<float> voice) {
  voice_ = std::move(voice);
  voice_pos_ = 0;
}

void VirtualVisit::FeedMicrophone() {
  if (microphone_ == nullptr || !microphone_->recorder().Recording()) return;
  const std::size_t n =
      std::min<std::size_t>(static_cast<std::size_t>(block_frames_), voice_left());
  mic_block_.assign(static_cast<std::size_t>(block_frames_), 0.0f);  // room tone: silence
  std::copy_n(voice_.begin() + static_cast<std::ptrdiff_t>(voice_pos_), n, mic_block_.begin());
  voice_pos_ += n;
  microphone_->Feed(mic_block_.data(), mic_block_.size());
}

void VirtualVisit::Advance(double seconds, const PenScript& pen) {
  const auto block_ns = static_cast<std::int64_t>(std::llround(block_frames_ * 1e9 / fs_hz_));
  const std::int64_t end_ns = now_ns_ + static_cast<std::int64_t>(seconds * 1e9);
  while (now_ns_ < end_ns) {
    if (pen) {
      while (next_pen_ns_ < now_ns_) {
        if (auto scripted = pen(static_cast<double>(next_pen_ns_) * 1e-9)) {
          scripted->reading.time_ns = next_pen_ns_;
          engine_.OnPen(scripted->reading, scripted->style);
          if (hooks_.on_pen) hooks_.on_pen(scripted->reading);
        }
        next_pen_ns_ += static_cast<std::int64_t>(pen_period_ns_);
      }
    } else {
      next_pen_ns_ = now_ns_;
    }
    auto actions = engine_.Tick(now_ns_);
    if (hooks_.on_tick) hooks_.on_tick(std::move(actions));
    FeedMicrophone();
    if (hooks_.before_render) hooks_.before_render();
    core_.Run(block_.data(), block_frames_, 2, false);
    if (keep_output_) output_.insert(output_.end(), block_.begin(), block_.end());
    now_ns_ += block_ns;
    if (hooks_.on_block) hooks_.on_block(block_);
  }
}

}  // namespace sas::kiosk
