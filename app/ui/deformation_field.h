#pragma once
// The local image deformation at the stylus tip (paper §4: "a local image deformation is applied
// at the point of interaction to mimic superficial vertical and lateral forces exerted by the
// stylus"; §5.2.2: visitors "popped" the virtual bubble wrap with it).
//
// Model. The screen shows an elastic skin. Under the tip it is pushed in by a dent of depth D and
// dragged along by friction by a vector q, both over a compact triweight footprint
// g(r) = (1 - r²/R²)³ (r < R, zero outside, so nothing beyond R ever changes; its slope also
// vanishes at R, so the shaded rim blends into the picture without a seam):
//   - vertical force: D follows pressure^γ · max_depth with a first-order lag (fast when
//     pressing, slower when relaxing after lift), exact exponential update for any frame time;
//   - lateral force: q is the skin's stretch. Each step it gains follow · (D/max_depth) · Δtip
//     (the skin sticks to the tip in proportion to the normal force) and relaxes elastically with
//     exp(-dt/τ); |q| is capped (beyond it the skin slips), which keeps the map invertible.
// Rendering is a backward map plus shading: the pixel at p shows the picture at
//   s = p + pinch·(D/R)·g(r)·(p - c) - q·g(r)
// (the skin is drawn into the dent, and the material under the tip came from behind it), and is
// multiplied by a Lambert shade of the relief h = -D·g + ridge·(q·(p - c))/R·g (a pile-up ahead of
// a dragged tip, a trough behind) under light from the upper left, with a little occlusion on the
// dent floor. Only pixels within R of the centre are recomputed: a ~120 px patch per frame.
//
// Pure CPU code with no SDL: the window uploads the patch, the software compositor blits it, and
// the tests check the geometry directly.

#include "platform/pen/pen_reading.h"
#include "ui/image_rgba.h"

namespace sas::ui {

struct DeformationConfig {
  float radius_px = 56.0f;         // footprint R
  float max_depth_px = 12.0f;      // D at full pressure
  float pressure_exponent = 0.7f;  // γ < 1: light touches already show a dent
  float press_time_s = 0.02f;      // lag of D towards a deeper target
  float release_time_s = 0.12f;    // lag of D towards a shallower one (the skin springs back)
  float drag_follow = 0.6f;        // fraction of tip travel the skin follows at full depth
  float drag_relax_s = 0.06f;      // elastic relaxation time of the stretch q
  float max_drag_fraction = 0.4f;  // |q| <= this · R (slip), keeps s(p) one-to-one
  float pinch = 0.6f;              // radial pull-in at full depth
  float ridge = 0.6f;              // pile-up ahead of / trough behind a dragged tip
  float relief_gain = 2.0f;        // slope exaggeration for the shading (visibility)
  float occlusion = 0.22f;         // darkening of the dent floor at full depth
  float rest_px = 0.05f;           // below this D and |q| count as zero: no more frames
};

// Where a pixel samples the undeformed picture, and how it is shaded (1 = unchanged).
struct DeformSample {
  float src_x = 0.0f;
  float src_y = 0.0f;
  float shade = 1.0f;
};

// The undeformed picture the patch samples: `picture`, or during a cross-fade
// fade_from · (1 - weight) + picture · weight (the formula CrossFade and the window use).
struct PictureSource {
  const ImageRgba* picture = nullptr;
  const ImageRgba* fade_from = nullptr;
  float weight = 1.0f;
};

class DeformationField {
 public:
  explicit DeformationField(const DeformationConfig& config = {});

  // Latest stylus reading; takes effect at the next Advance.
  void SetTip(const platform::PenReading& sample);
  // Moves the model to `now_s` (monotonic seconds). Returns true when the picture changed since
  // the previous call (so a new frame is due); false once everything is at rest.
  bool Advance(double now_s);
  // Back to the flat skin at once (idle reset).
  void Reset();

  bool active() const { return depth_px_ > 0.0f || drag_x_px_ != 0.0f || drag_y_px_ != 0.0f; }
  float depth_px() const { return depth_px_; }
  float drag_x_px() const { return drag_x_px_; }
  float drag_y_px() const { return drag_y_px_; }
  float centre_x_px() const { return centre_x_; }
  float centre_y_px() const { return centre_y_; }
  const DeformationConfig& config() const { return config_; }

  // The map at pixel (x, y) (pixel centres at integer coordinates).
  DeformSample At(float x, float y) const;
  // Pixels that may differ from the picture, clipped to a width x height screen; empty at rest.
  PixelRect AffectedRect(int width, int height) const;
  // Writes the deformed pixels of `rect` (screen coordinates) into `out` (reshaped to rect's size).
  void RenderPatch(const PictureSource& source, PixelRect rect, ImageRgba& out) const;

 private:
  DeformationConfig config_;
  platform::PenReading tip_{};
  bool have_time_ = false;
  bool was_down_ = false;
  double last_s_ = 0.0;
  float centre_x_ = 0.0f, centre_y_ = 0.0f;  // dent centre: the tip while down, stays on lift
  float depth_px_ = 0.0f;
  float drag_x_px_ = 0.0f, drag_y_px_ = 0.0f;
};

}  // namespace sas::ui
