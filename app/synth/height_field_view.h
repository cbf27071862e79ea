#pragma once
// A read-only view of a surface's height field, the contract between app/surface (which builds
// height fields at load time from images, sounds and scans) and the synth's surface reader (which
// samples them under the probe). A 1-D profile is a field one row high.
//
// The summed-area table lets the reader average the field over any probe width in O(1) per
// sample, so nothing is filtered per block (paper §4: probe width = averaging window).

#include <cstddef>

namespace sas::synth {

struct HeightFieldView {
  const float* height_m = nullptr;      // row-major, width * height samples, metres; 0 = flat
  const double* summed_area = nullptr;  // (width + 1) * (height + 1) prefix sums of height_m
  int width = 0;
  int height = 0;
  double pitch_m = 0.153e-3;  // spacing of neighbouring samples (13.3" 1080p panel)

  bool empty() const { return height_m == nullptr || width <= 0 || height <= 0; }
  std::size_t size() const {
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  }
};

}  // namespace sas::synth
