#pragma once
// An owned height field: heights in metres on a regular grid plus the summed-area table the
// synth's surface reader uses to average over the probe width in O(1). Built once at load time
// (from a picture, a sound or a scan) and then only read; View() hands the synth a non-owning
// HeightFieldView. A 1-D profile is a field one row high.
//
// The heights and the summed-area table live in the memory resource the heights came with
// (std::pmr; the default one unless a caller chose another): the kiosk builds the visitor's voice
// in memory kept out of core dumps, and the table, which gives the heights back by differencing,
// must stay there too. Moving a field keeps its memory; assigning one into a field made elsewhere
// would copy into that one's memory (std::pmr does not move allocators on assignment), so fields
// in a chosen memory are constructed, never assigned.

#include <memory_resource>
#include <vector>

#include "synth/height_field_view.h"

namespace sas::surface {

class HeightField {
 public:
  HeightField() = default;
  // Takes `heights_m` (row-major, width * height values) and computes the summed-area table in
  // the same memory resource.
  HeightField(int width, int height, double pitch_m, std::pmr::vector<float> heights_m);

  int width() const { return width_; }
  int height() const { return height_; }
  double pitch_m() const { return pitch_m_; }
  bool empty() const { return heights_.empty(); }
  const std::pmr::vector<float>& heights_m() const { return heights_; }
  float at(int x, int y) const {
    return heights_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                    static_cast<std::size_t>(x)];
  }

  // Mean height over the inclusive pixel box [x0, x1] x [y0, y1] (clamped to the field).
  double BoxMean(int x0, int y0, int x1, int y1) const;

  synth::HeightFieldView View() const;

 private:
  int width_ = 0;
  int height_ = 0;
  double pitch_m_ = 0.153e-3;
  std::pmr::vector<float> heights_;
  std::pmr::vector<double> summed_area_;
};

// The field's relief: its highest minus its lowest height (0 for an empty field). The pen's
// full pressure presses this deep, so a texture's pressure range scales with its own relief.
double ReliefM(const HeightField& field);

}  // namespace sas::surface
