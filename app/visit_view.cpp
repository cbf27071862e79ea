// What the visitor sees (see visit_view.h).
#include "visit_view.h"

#include <algorithm>
#include <cmath>

#include "ui/overlay.h"
#include "ui/picture_io.h"
#include "ui/text.h"

namespace sas::app {
namespace {

constexpr double kMessageS = 4.0;
constexpr double kAttractFps = 12.0;  // the attract animation is slow: a few frames a second do

}  // namespace

VisitView::VisitView(const kiosk::KioskEngine& engine, int width, int height)
    : engine_(&engine), width_(width), height_(height), view_(width, height) {
  for (const auto& texture : engine.textures()) {
    pictures_.push_back(std::make_shared<const ui::ImageRgba>(
        ui::ResizeToCover(ui::LoadPicture(texture.loaded.file.picture_path), width, height)));
  }
  current_ = pictures_.at(static_cast<std::size_t>(engine.surface().texture));
  view_.ShowPicture(current_, 0.0, false);
}

void VisitView::Apply(const std::vector<kiosk::SessionAction>& actions, double now_s) {
  using Kind = kiosk::SessionAction::Kind;
  for (const auto& action : actions) {
    switch (action.kind) {
      case Kind::kShowSurface:
        if (action.surface.voice) {
          if (const auto* gray = engine_->voice_image()) {
            current_ = std::make_shared<const ui::ImageRgba>(
                ui::ResizeToCover(ui::FromGrayImage(*gray), width_, height_));
          }
        } else {
          current_ = pictures_.at(static_cast<std::size_t>(action.surface.texture));
        }
        view_.ShowPicture(current_, now_s, true);
        break;
      case Kind::kResetTextures:
        view_.ResetDeformation();
        break;
      case Kind::kEnterAttract:
        attract_ = true;
        attract_since_s_ = now_s;
        break;
      case Kind::kLeaveAttract:
        attract_ = false;
        break;
      case Kind::kSpeak:
        // The spoken friendly messages also show on screen (a coloured banner) for a while.
        switch (action.cue) {
          case kiosk::Cue::kRecordingTooQuiet:
            message_ = "too quiet: try again a little louder";
            message_color_ = {40, 110, 220, 220};
            break;
          case kiosk::Cue::kRecordingTooLoud:
            message_ = "too loud: try again a little further away";
            message_color_ = {240, 140, 30, 220};
            break;
          case kiosk::Cue::kRecordingUnavailable:
            message_ = "recording is not available right now";
            message_color_ = {120, 120, 120, 220};
            break;
          default:
            continue;
        }
        message_until_s_ = now_s + kMessageS;
        break;
      default:
        break;
    }
  }
}

void VisitView::OnStylus(const ui::StylusSample& sample) {
  view_.OnStylus(sample);
}

bool VisitView::Advance(double now_s, bool staff_panel_open, ui::Overlays staff_extra) {
  ui::Overlays overlays;
  const auto& session = engine_->session();
  if (attract_) {
    // A gentle invitation: the screen breathes (a veil fading in and out every 4 s) and a soft
    // frame pulses around it. Quantised in time so an idle kiosk draws only a few frames a second.
    const double t = std::floor((now_s - attract_since_s_) * kAttractFps) / kAttractFps;
    const double breath = 0.5 - 0.5 * std::cos(2.0 * 3.14159265358979 * t / 4.0);
    overlays.push_back(
        {{0, 0, width_, height_}, {0, 0, 0, static_cast<std::uint8_t>(40 + 70 * breath)}});
    const int thickness = 6 + static_cast<int>(10 * breath);
    ui::AddFrame(overlays, {0, 0, width_, height_}, thickness,
                 {255, 255, 255, static_cast<std::uint8_t>(60 + 100 * breath)});
    const int scale = std::max(2, width_ / 320);
    const char* invite = "TOUCH THE PICTURE WITH THE PEN";
    ui::AddText(overlays, (width_ - ui::TextWidth(invite, scale)) / 2, height_ / 2 - 4 * scale,
                scale, invite, {255, 255, 255, static_cast<std::uint8_t>(150 + 100 * breath)});
  }
  if (session.mode() == kiosk::SessionMode::kCountdown) {
    const double left = session.SecondsLeft(now_s);
    ui::AddCountdownBar(overlays, width_, height_, static_cast<float>(left / 3.0));
    ui::AddLevelMeter(overlays, width_, height_, engine_->mic_level());
  } else if (session.mode() == kiosk::SessionMode::kRecording) {
    ui::AddRecordingDot(overlays, width_, height_);
    ui::AddLevelMeter(overlays, width_, height_, engine_->mic_level());
  }
  if (!message_.empty() && now_s < message_until_s_) {
    const int banner_h = std::max(24, height_ / 10);
    overlays.push_back({{0, height_ - banner_h, width_, banner_h}, message_color_});
    const int scale = std::max(2, banner_h / 14);
    ui::AddText(overlays, (width_ - ui::TextWidth(message_, scale)) / 2,
                height_ - banner_h + (banner_h - 7 * scale) / 2, scale, message_,
                {255, 255, 255, 255});
  } else {
    message_.clear();
  }
  if (staff_panel_open) {
    ui::AddStaffPanelFrame(overlays, width_, height_);
    overlays.insert(overlays.end(), staff_extra.begin(), staff_extra.end());
  }
  view_.SetOverlays(std::move(overlays));
  return view_.Advance(now_s);
}

}  // namespace sas::app
