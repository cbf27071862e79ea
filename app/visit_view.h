#pragma once
// What the visitor sees, driven by the kiosk engine: the screen-sized pictures of the four
// textures and of the voice (its sound image), the TextureView with its cross-fade and tip dent,
// and the overlays (countdown bar, live level meter, recording dot, friendly messages as a
// coloured banner, the attract animation, the staff panel backdrop). Shared by the live kiosk and
// the headless default so both show exactly the same frames (the headless one composes them in
// software and writes PNGs).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "kiosk/kiosk_engine.h"
#include "ui/image_rgba.h"
#include "ui/texture_view.h"

namespace sas::app {

class VisitView {
 public:
  // Loads and fits every texture picture to width x height (set-up; throws PictureError).
  VisitView(const kiosk::KioskEngine& engine, int width, int height);

  // Carries out the UI part of the session's actions (new picture, reset, attract, message).
  void Apply(const std::vector<kiosk::SessionAction>& actions, double now_s);
  void OnStylus(const ui::StylusSample& sample);
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
  const std::string& message() const { return message_; }

 private:
  // Bubble wrap: the picture with the popped bubbles flattened (issue 5, paper §5.2.2).
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
  std::string message_;  // "too quiet" ... while shown
  ui::Rgba message_color_{};
  double message_until_s_ = 0.0;
  ui::Overlays last_overlays_;
};

}  // namespace sas::app
