#pragma once
// What the visitor sees, driven by the kiosk engine: the screen-sized pictures of the four
// textures and of the voice (its sound image), the TextureView with its cross-fade and tip dent,
// and the overlays (countdown bar, live level meter, recording sign, friendly messages as a
// banner with a coloured edge, the attract animation, the staff panel backdrop). Shared by the live
// kiosk and the headless default so both show exactly the same frames (the headless one composes
// them in software and writes PNGs).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "kiosk/kiosk_engine.h"
#include "ui/image_rgba.h"
#include "ui/palette.h"
#include "ui/texture_view.h"
#include "ui/ttf_text.h"

namespace sas::app {

// The recording's meter in words (the screen table's key): below kMeterLouderBelowDbfs of the
// microphone's level "louder", above kMeterTooLoudAboveDbfs "too loud", else "good".
inline constexpr double kMeterLouderBelowDbfs = -35.0;
inline constexpr double kMeterTooLoudAboveDbfs = -3.0;
const char* MeterWordKey(float level);
// The number the countdown shows (3, 2, 1, as the count is spoken; 0 before and at the tone).
int CountShown(const kiosk::SessionConfig& config, double seconds_left);

// Text is white on a dark plate (never bare on a picture): the palette's (ui/palette.h).
inline constexpr ui::Rgba kPlateColor = ui::kPlate;
inline constexpr ui::Rgba kTextColor = ui::kInk;

class VisitView {
 public:
  // Loads and fits every texture picture to width x height (set-up; throws PictureError).
  VisitView(const kiosk::KioskEngine& engine, int width, int height);

  // Carries out the UI part of the session's actions (new picture, reset, attract, message).
  void Apply(const std::vector<kiosk::SessionAction>& actions, double now_s);
  void OnStylus(const platform::PenReading& sample);
  // Rebuilds the overlays for `now_s` (countdown, meter, messages, attract, staff backdrop) and
  // advances the view; returns whether a frame is due.
  bool Advance(double now_s, bool staff_panel_open, ui::Overlays staff_extra = {});

  ui::TextureView& view() { return view_; }
  // The picture of what is under the pen now (undeformed): tests compare screenshots with it.
  std::shared_ptr<const ui::ImageRgba> current_picture() const { return current_; }
  std::shared_ptr<const ui::ImageRgba> texture_picture(int texture) const {
    return pictures_.at(static_cast<std::size_t>(texture));
  }
  bool attract() const { return attract_; }
  // The screen table's key of the message shown ("too_quiet", "voice_ready"...; "texture_name"
  // and "language" for the texture's and the chosen language's names), "" when none.
  const std::string& message() const { return message_; }
  // The message's words (in the current language).
  const std::string& MessageText() const;
  // The text plates drawn in the last Advance (tests: contrast over what is under them).
  const std::vector<ui::PixelRect>& plates() const { return plates_; }
  ui::TextRenderer& text() { return text_; }

 private:
  struct PlateLine {
    std::string text;
    int size_px;
    bool bold;
  };
  // Lines centred on (centre_x, centre_y) over one dark plate; returns the plate.
  ui::PixelRect AddPlate(ui::Overlays& overlays, const std::vector<PlateLine>& lines, int centre_x,
                         int centre_y);
  // The recording sign (dot, ring and the word) at the top-left; returns its plate (empty
  // without the TrueType font, when it has no word to keep at 7:1).
  ui::PixelRect AddRecordingSign(ui::Overlays& overlays, int size_px);
  // Bubble wrap: the picture with the popped bubbles flattened (paper §5.2.2).
  void SyncBubbles(double now_s);
  std::shared_ptr<const ui::ImageRgba> PoppedPicture() const;

  const kiosk::KioskEngine* engine_;
  int bubble_texture_ = -1;
  int shown_popped_ = 0;
  int width_;
  int height_;
  ui::TextureView view_;
  std::vector<std::shared_ptr<const ui::ImageRgba>> pictures_;
  std::shared_ptr<const ui::ImageRgba> current_;
  bool attract_ = true;
  double attract_since_s_ = 0.0;
  std::string message_;       // "too quiet" ... while shown
  std::string message_text_;  // the words when they are no screen key (a name)
  int language_choices_ = 0;  // the engine's language_choices() last seen
  ui::Rgba message_color_{};
  double message_until_s_ = 0.0;
  ui::Overlays last_overlays_;
  ui::TextRenderer text_;
  std::vector<ui::PixelRect> plates_;
  std::shared_ptr<const ui::TextMask> sign_ring_, sign_dot_;  // made once per size
};

}  // namespace sas::app
