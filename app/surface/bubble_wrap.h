#pragma once
// Bubble wrap is the one stateful texture (paper §5.2.1): bubbles sit on a hexagonal grid
// (the layout is in the texture file, the generator draws the same grid); pressing an intact bubble
// with a normal force at or above pop_force_n pops it. A pop returns a PopEvent (the kiosk turns it
// into a short burst through the contact model) and the bubble is flattened in the height field
// until Reset().
//
// Popping runs on the control thread. It builds a new field (copy + summed-area table, a few ms
// at 1080p) and hands it out as shared_ptr<const HeightField>, so a reader still holding the old
// surface is never torn.

#include <memory>
#include <optional>
#include <vector>

#include "surface/height_field.h"

namespace sas::surface {

struct BubbleLayout {
  double pitch_px = 176.0;    // centre-to-centre distance along a row
  double radius_px = 72.0;    // bubble radius (its rim)
  double origin_x_px = 88.0;  // centre of the first bubble of the first row
  double origin_y_px = 80.0;
  // Hexagonal packing: rows pitch * sqrt(3)/2 apart, odd rows shifted by half a pitch. Every
  // centre inside [0, width) x [0, height) is a bubble. Order: row by row, left to right.
  std::vector<std::pair<double, double>> Centres(int width_px, int height_px) const;
};

struct PopEvent {
  int bubble = -1;
  double x_px = 0.0;  // bubble centre
  double y_px = 0.0;
  double force_n = 0.0;   // the force that popped it
  double strength = 0.0;  // force / threshold, capped at 4: how hard the burst should be
};

class BubbleWrapState {
 public:
  // `intact` is the field with every bubble up (true height map or picture-derived field).
  // Throws std::invalid_argument for a non-positive threshold/radius or an empty field.
  BubbleWrapState(BubbleLayout layout, double pop_force_n, HeightField intact,
                  double flatten_radius_scale = 1.25);
  // Shares an already-built field instead of copying it.
  BubbleWrapState(BubbleLayout layout, double pop_force_n,
                  std::shared_ptr<const HeightField> intact, double flatten_radius_scale = 1.25);

  // A press at (x, y) px with normal force `force_n`: pops the intact bubble under it if the force
  // reaches the threshold. Returns the event, or nothing (no bubble, already popped, too soft).
  std::optional<PopEvent> Press(double x_px, double y_px, double force_n);

  void Reset();  // every bubble intact again, the original field back

  int BubbleAt(double x_px, double y_px) const;  // index, or -1 outside every bubble
  bool popped(int bubble) const { return popped_.at(static_cast<std::size_t>(bubble)); }
  int popped_count() const;
  int bubble_count() const { return static_cast<int>(centres_.size()); }
  const std::vector<std::pair<double, double>>& centres() const { return centres_; }
  double pop_force_n() const { return pop_force_n_; }
  std::shared_ptr<const HeightField> field() const { return current_; }

 private:
  BubbleLayout layout_;
  double pop_force_n_;
  double flatten_radius_px_;
  std::shared_ptr<const HeightField> intact_;
  std::shared_ptr<const HeightField> current_;
  std::vector<std::pair<double, double>> centres_;
  std::vector<bool> popped_;
};

}  // namespace sas::surface
