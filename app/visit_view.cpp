// What the visitor sees (see visit_view.h).
#include "visit_view.h"

#include <algorithm>
#include <cmath>

#include "ui/overlay.h"
#include "ui/palette.h"
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
  for (std::size_t i = 0; i < engine.textures().size(); ++i) {
    if (engine.textures()[i].loaded.bubbles) bubble_texture_ = static_cast<int>(i);
  }
  current_ = pictures_.at(static_cast<std::size_t>(engine.surface().texture));
  view_.ShowPicture(current_, 0.0, false);
}

std::shared_ptr<const ui::ImageRgba> VisitView::PoppedPicture() const {
  const auto& texture = engine_->textures()[static_cast<std::size_t>(bubble_texture_)];
  const auto* state = engine_->bubbles();
  const auto& original = *pictures_[static_cast<std::size_t>(bubble_texture_)];
  auto picture = std::make_shared<ui::ImageRgba>(original);
  if (state == nullptr || !texture.loaded.file.bubbles) return picture;
  // Field samples -> screen pixels: the inverse of the cover fit (KioskEngine::ScreenToField).
  const auto& field = *texture.loaded.field;
  const double scale = std::max(static_cast<double>(width_) / field.width(),
                                static_cast<double>(height_) / field.height());
  const double crop_x = (field.width() * scale - width_) / 2.0;
  const double crop_y = (field.height() * scale - height_) / 2.0;
  const double radius = texture.loaded.file.bubbles->layout.radius_px * scale;
  for (int b = 0; b < state->bubble_count(); ++b) {
    if (!state->popped(b)) continue;
    const double cx = state->centres()[static_cast<std::size_t>(b)].first * scale - crop_x;
    const double cy = state->centres()[static_cast<std::size_t>(b)].second * scale - crop_y;
    // The film between the bubbles, a little darker: a flat, crumpled patch where the dome was.
    double sum[3] = {0, 0, 0};
    int n = 0;
    for (int k = 0; k < 32; ++k) {
      const double a = 2.0 * 3.14159265358979 * k / 32.0;
      const int x = static_cast<int>(cx + 1.2 * radius * std::cos(a));
      const int y = static_cast<int>(cy + 1.2 * radius * std::sin(a));
      if (x < 0 || y < 0 || x >= width_ || y >= height_) continue;
      const auto p = original.at(x, y);
      sum[0] += p.r;
      sum[1] += p.g;
      sum[2] += p.b;
      ++n;
    }
    if (n == 0) continue;
    for (int y = std::max(0, static_cast<int>(cy - radius));
         y < std::min(height_, static_cast<int>(cy + radius) + 1); ++y) {
      for (int x = std::max(0, static_cast<int>(cx - radius));
           x < std::min(width_, static_cast<int>(cx + radius) + 1); ++x) {
        const double dx = x - cx, dy = y - cy;
        const double r = std::hypot(dx, dy) / radius;
        if (r > 1.0) continue;
        // Creases: a few radial folds, darker towards the middle.
        const double fold = 0.5 + 0.5 * std::cos(7.0 * std::atan2(dy, dx) + 3.0 * r);
        const double shade = 0.78 + 0.12 * r - 0.08 * fold * (1.0 - r);
        picture->set(x, y,
                     {static_cast<std::uint8_t>(std::clamp(sum[0] / n * shade, 0.0, 255.0)),
                      static_cast<std::uint8_t>(std::clamp(sum[1] / n * shade, 0.0, 255.0)),
                      static_cast<std::uint8_t>(std::clamp(sum[2] / n * shade, 0.0, 255.0)), 255});
      }
    }
  }
  return picture;
}

void VisitView::SyncBubbles(double now_s) {
  if (bubble_texture_ < 0) return;
  const int popped = engine_->popped_bubbles();
  if (popped == shown_popped_) return;
  shown_popped_ = popped;
  const auto surface = engine_->surface();
  if (surface.voice || surface.texture != bubble_texture_) return;
  current_ = popped == 0 ? pictures_[static_cast<std::size_t>(bubble_texture_)] : PoppedPicture();
  view_.ShowPicture(current_, now_s, false);  // a pop is instant
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
        } else if (action.surface.texture == bubble_texture_ && engine_->popped_bubbles() > 0) {
          current_ = PoppedPicture();
          shown_popped_ = engine_->popped_bubbles();
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
        // The spoken friendly messages also show on screen (a banner with a coloured edge) for a
        // while.
        switch (action.cue) {
          case kiosk::Cue::kTextureName:
            // A visit's start or a token: the texture's name, as it is spoken.
            message_ = "texture_name";
            message_text_ = engine_->TextureName(action.surface.texture);
            message_color_ = ui::kBlue;
            break;
          case kiosk::Cue::kRecordingTooQuiet:
            message_ = "too_quiet";
            message_color_ = ui::kBlue;
            break;
          case kiosk::Cue::kRecordingTooLoud:
            message_ = "too_loud";
            message_color_ = ui::kAmber;
            break;
          case kiosk::Cue::kRecordingUnavailable:
            message_ = "no_microphone";
            message_color_ = ui::kGrey;
            break;
          case kiosk::Cue::kVoiceReady:
            message_ = "voice_ready";
            message_color_ = ui::kGreen;
            break;
          default:
            continue;
        }
        if (action.cue != kiosk::Cue::kTextureName) message_text_.clear();
        message_until_s_ = now_s + kMessageS;
        break;
      default:
        break;
    }
  }
}

const std::string& VisitView::MessageText() const {
  return message_text_.empty() ? engine_->strings().Screen(message_) : message_text_;
}

void VisitView::OnStylus(const platform::PenReading& sample) {
  view_.OnStylus(sample);
}

const char* MeterWordKey(float level) {
  const double db = 20.0 * std::log10(std::max(static_cast<double>(level), 1e-6));
  if (db < kMeterLouderBelowDbfs) return "meter_louder";
  if (db > kMeterTooLoudAboveDbfs) return "meter_too_loud";
  return "meter_good";
}

int CountShown(const kiosk::SessionConfig& config, double seconds_left) {
  const double tone_at = std::max(0.0, config.countdown_s - config.tone_s);
  const double step = std::min(config.count_step_s, tone_at / 4.0);
  const double elapsed = config.countdown_s - seconds_left;
  if (elapsed < tone_at - 3.0 * step || elapsed >= tone_at) return 0;
  return std::clamp(3 - static_cast<int>(std::floor((elapsed - (tone_at - 3.0 * step)) / step)), 1,
                    3);
}

ui::PixelRect VisitView::AddPlate(ui::Overlays& overlays, const std::vector<PlateLine>& lines,
                                  int centre_x, int centre_y) {
  // Dark, nearly opaque, under every line: white text on it stays above 7:1 over any picture
  // (even pure white under the plate: 14:1).
  std::vector<std::shared_ptr<const ui::TextMask>> masks;
  int w = 0, h = 0;
  for (const auto& line : lines) {
    for (const auto& wrapped : text_.Wrap(line.text, line.size_px, width_ * 8 / 10, line.bold)) {
      auto mask = text_.Render(wrapped, line.size_px, line.bold);
      if (!mask) continue;
      w = std::max(w, mask->w);
      h += mask->h;
      masks.push_back(std::move(mask));
    }
  }
  if (masks.empty()) return {};
  const int pad = std::max(8, height_ / 60);
  const ui::PixelRect plate{centre_x - w / 2 - 2 * pad, centre_y - h / 2 - pad, w + 4 * pad,
                            h + 2 * pad};
  overlays.push_back({plate, kPlateColor});
  int y = plate.y + pad;
  for (const auto& mask : masks) {
    overlays.push_back({{centre_x - mask->w / 2, y, mask->w, mask->h}, kTextColor, mask});
    y += mask->h;
  }
  return plate;
}

ui::PixelRect VisitView::AddRecordingSign(ui::Overlays& overlays, int size_px) {
  // A red dot in a red ring, the sign on every recorder, and the word beside it, on a dark plate
  // at the top-left (the level meter has the right edge, the words the middle).
  const auto word = text_.Available()
                        ? text_.Render(engine_->strings().Screen("recording_sign"), size_px, true)
                        : nullptr;
  const int d = word ? word->h : std::max(16, height_ / 24);
  if (!sign_ring_ || sign_ring_->w != d) {
    sign_ring_ = ui::CircleMask(d, std::max(2, d / 12));
    sign_dot_ = ui::CircleMask(d * 3 / 5);
  }
  const int margin = std::max(8, height_ / 40);
  const int pad = std::max(8, height_ / 60);
  const int gap = word ? d / 3 : 0;
  const ui::PixelRect plate{margin, margin, 2 * pad + d + gap + (word ? word->w : 0), 2 * pad + d};
  overlays.push_back({plate, ui::kPlate});
  const int x = plate.x + pad, y = plate.y + pad;
  overlays.push_back({{x, y, d, d}, ui::kRed, sign_ring_});
  const int inset = (d - sign_dot_->w) / 2;
  overlays.push_back({{x + inset, y + inset, sign_dot_->w, sign_dot_->w}, ui::kRed, sign_dot_});
  if (word) overlays.push_back({{x + d + gap, y, word->w, word->h}, ui::kInk, word});
  return word ? plate : ui::PixelRect{};
}

bool VisitView::Advance(double now_s, bool staff_panel_open, ui::Overlays staff_extra) {
  SyncBubbles(now_s);
  if (engine_->language_choices() != language_choices_) {
    // The language key: the chosen language's own name, as it is spoken.
    language_choices_ = engine_->language_choices();
    message_ = "language";
    message_text_ = engine_->strings().language_name;
    message_color_ = ui::kFrameLine;
    message_until_s_ = now_s + kMessageS;
  }
  ui::Overlays overlays;
  plates_.clear();
  const auto& session = engine_->session();
  const auto& strings = engine_->strings();
  const bool ttf = text_.Available();
  // Sizes follow the screen's height: the title's x-height is about 1/28 of it (8 mm on a 13-inch
  // 720p panel, 11 mm on a 24-inch 1080p one), readable from 1.5 m.
  const int title_px = std::max(24, height_ / 14);
  const int body_px = std::max(18, height_ / 24);
  if (attract_) {
    // A gentle invitation: the screen breathes (a veil fading in and out every 4 s) and a soft
    // frame pulses around it. Quantised in time so an idle kiosk draws only a few frames a second.
    const double t = std::floor((now_s - attract_since_s_) * kAttractFps) / kAttractFps;
    const double breath = 0.5 - 0.5 * std::cos(2.0 * 3.14159265358979 * t / 4.0);
    overlays.push_back(
        {{0, 0, width_, height_}, ui::WithAlpha(ui::kVeil, static_cast<int>(40 + 70 * breath))});
    const int thickness = 6 + static_cast<int>(10 * breath);
    ui::AddFrame(overlays, {0, 0, width_, height_}, thickness,
                 ui::WithAlpha(ui::kInk, static_cast<int>(60 + 100 * breath)));
    if (staff_panel_open) {
      // The panel covers the middle: no invitation under its lines.
    } else if (ttf) {
      // The invitation's parts (strings.h): the first as the title, the rest one a line, in the
      // language the attract cycle is showing.
      const auto& parts = kiosk::InvitationParts();
      plates_.push_back(AddPlate(overlays, {{strings.Invitation(parts.front()), title_px, true}},
                                 width_ / 2, height_ * 1 / 4));
      std::vector<PlateLine> lines;
      for (std::size_t i = 1; i < parts.size(); ++i) {
        lines.push_back({strings.Invitation(parts[i]), body_px, false});
      }
      plates_.push_back(AddPlate(overlays, lines, width_ / 2, height_ * 5 / 8));
    } else {
      const int scale = std::max(2, width_ / 320);
      const char* invite = "TOUCH THE PICTURE WITH THE PEN";
      ui::AddText(overlays, (width_ - ui::TextWidth(invite, scale)) / 2, height_ / 2 - 4 * scale,
                  scale, invite, ui::WithAlpha(ui::kInk, static_cast<int>(150 + 100 * breath)));
    }
  }
  if (session.mode() == kiosk::SessionMode::kCountdown) {
    const double left = session.SecondsLeft(now_s);
    ui::AddCountdownBar(overlays, width_, height_,
                        static_cast<float>(left / std::max(session.config().countdown_s, 1e-3)));
    ui::AddLevelMeter(overlays, width_, height_, engine_->mic_level());
    if (ttf) {
      std::vector<PlateLine> lines = {{strings.Screen("countdown"), title_px, true}};
      if (const int count = CountShown(session.config(), left); count > 0) {
        lines.push_back({std::to_string(count), height_ / 4, true});
      }
      plates_.push_back(AddPlate(overlays, lines, width_ / 2, height_ / 2));
    }
  } else if (session.mode() == kiosk::SessionMode::kRecording) {
    const ui::PixelRect sign = AddRecordingSign(overlays, body_px);
    if (!sign.empty()) plates_.push_back(sign);
    ui::AddLevelMeter(overlays, width_, height_, engine_->mic_level());
    if (ttf) {
      plates_.push_back(
          AddPlate(overlays,
                   {{strings.Screen("recording"), title_px, true},
                    {strings.Screen(MeterWordKey(engine_->mic_level())), title_px, false}},
                   width_ / 2, height_ / 2));
    }
  }
  if (!message_.empty() && now_s < message_until_s_) {
    // A dark band across the bottom with an edge in the message's colour (green: the voice is
    // ready, blue: louder, amber: too loud), the words on it: seen at a glance, and a small
    // accent instead of a saturated band over a sixth of the picture.
    const int banner_h = std::max(24, height_ / 8);
    const int edge_h = std::max(3, height_ / 135);
    overlays.push_back({{0, height_ - banner_h, width_, banner_h}, ui::kPlate});
    overlays.push_back({{0, height_ - banner_h, width_, edge_h}, message_color_});
    if (ttf) {
      plates_.push_back(AddPlate(overlays, {{MessageText(), body_px, true}}, width_ / 2,
                                 height_ - (banner_h - edge_h) / 2));
    } else {
      const int scale = std::max(2, banner_h / 14);
      const std::string& text = MessageText();
      ui::AddText(overlays, (width_ - ui::TextWidth(text, scale)) / 2,
                  height_ - banner_h + (banner_h - 7 * scale) / 2, scale, text, ui::kInk);
    }
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
