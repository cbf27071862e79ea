#pragma once
// Surface reader: the profile height the probe feels at a point of a height field (paper §4,
// "sliding parameters"). Chain: box average of the field over the probe width (summed-area table,
// O(1), exact integral of the piecewise-constant field over a fractional window, so the result
// moves continuously with the probe) -> style (scrape/rub: the averaged profile; roll: the envelope
// traced by the bottom of a ball of radius r rolling over it) -> penetration threshold (only what
// rises above h_max - penetration is felt: felt = max(h - (h_max - penetration), 0)).
// Styles also set how much of the normal force the friction sees ("friction share"): roll = 0
// (rolling does not slide), rub = 1, scrape = 0.3 rising to 1 as the width grows to 8 mm — the
// paper's tilt control blends scratching into rubbing by width.

#include <vector>

#include "synth/height_field_view.h"
#include "synth/probe_command.h"

namespace sas::synth {

class SurfaceReader {
 public:
  // Scans the field once for its highest point and the highest point of each kTile x kTile tile.
  // Not real-time (allocates the tile table).
  void Prepare(const HeightFieldView& field);

  // Mean height (m) over a square window of side width_m centred at (x_m, y_m); positions outside
  // the field are clamped to its edge; a one-row field is averaged along x only.
  double BoxMean(double x_m, double y_m, double width_m) const;

  // Felt profile under the probe for this style (see above), >= 0.
  double Felt(double x_m, double y_m, double width_m, double penetration_m, ProbeStyle style,
              double ball_radius_m, double direction_x, double direction_y) const;

  // The same value as Felt, bit for bit, for the audio thread's sample-by-sample walk: a rolling
  // ball keeps the box means it read at the last position and skips the points that cannot reach
  // the maximum now (see the .cpp). Not thread-safe (it updates that record).
  double FeltTracked(double x_m, double y_m, double width_m, double penetration_m, ProbeStyle style,
                     double ball_radius_m, double direction_x, double direction_y);

  static double FrictionShare(ProbeStyle style, double width_mm);

  double max_height_m() const { return max_height_m_; }

 private:
  double Integral(double px, double py) const;  // ∫∫ over [0,px]×[0,py] (pixel units)
  // Highest field value any box window centred in [x_lo, x_hi] x [y_lo, y_hi] (metres) can
  // read, from the tile table (an upper bound of every BoxMean there, up to its rounding).
  // `memo` (FeltTracked's): the tile range last scanned and its maximum, reused while the range
  // stays the same (a ball moves a few um a sample, a tile is 8 pixels): the same value.
  struct CeilingMemo {
    int tx0 = -1, tx1 = -1, ty0 = -1, ty1 = -1;
    float highest = 0.0f;
  };
  double CeilingOver(double x_lo, double x_hi, double y_lo, double y_hi, double half_px,
                     CeilingMemo* memo = nullptr) const;

  // A rolling ball's points and the bound on what they read (Felt's comment).
  struct RollGeometry {
    double r = 0.0, ds = 0.0, dx = 0.0, dy = 0.0;  // radius, point spacing, unit direction
    int half_count = 0;                            // points k = 0 .. half_count on each side
  };
  RollGeometry Roll(double width_m, double ball_radius_m, double direction_x,
                    double direction_y) const;
  // Highest box mean along the track of a ball centred at (x_m, y_m), plus BoxMean's rounding.
  double RollCeiling(double x_m, double y_m, double width_m, const RollGeometry& g,
                     CeilingMemo* memo = nullptr) const;

  // The roll's points along the ball: k = 0 .. half_count (<= 64) on each side of the centre.
  static constexpr int kMaxRollPoints = 129;
  // What FeltTracked knew at the last position of a rolling ball: each point's box mean when it
  // was last read (+inf: not read) and the drift when it was, the drift being the most any box
  // mean can have moved since (the field's height range times the travel over the window width).
  struct RollTrack {
    bool valid = false;
    double x_m = 0.0, y_m = 0.0;  // the centre it was at
    double width_m = 0.0, radius_m = 0.0, direction_x = 0.0, direction_y = 0.0;  // the inputs
    RollGeometry geometry{};  // Roll's for them (hypot and divisions once, not every sample)
    double drift = 0.0;
    CeilingMemo ceiling{};
    double lift[kMaxRollPoints / 2 + 1] = {};  // each point's lift, sqrt(r² - s²) - r
    int best = -1;  // the point that gave the maximum there (-1: none)
    double value[kMaxRollPoints] = {};
    double drift_at[kMaxRollPoints] = {};
  };

  static constexpr int kTile = 8;   // pixels per side of a tile of the ceiling table
  HeightFieldView field_{};
  std::vector<float> tile_max_;  // highest value of each tile, row-major
  int tiles_x_ = 0, tiles_y_ = 0;
  double max_height_m_ = 0.0;
  double height_range_m_ = 0.0;  // highest minus lowest point of the field
  RollTrack roll_{};
  double inv_pitch_ = 0.0;  // 1 / pitch (the per-sample lookups multiply)
};

}  // namespace sas::synth
