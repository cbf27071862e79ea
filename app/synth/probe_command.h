#pragma once
// What the control side tells the audio thread about the stylus, once per input event. Small POD
// so it crosses the SPSC queue by copy (DESIGN.md §5.4). The scene splits its block at
// `frame_offset` so the command takes effect on the exact sample it belongs to.

#include <cstdint>

namespace sas::synth {

enum class ProbeStyle : std::uint8_t {
  kScrape,  // small width, impact-dominated
  kRub,     // large width, friction-dominated
  kRoll,    // a ball of radius r follows the envelope of the profile
};

struct ProbeCommand {
  std::uint32_t frame_offset = 0;  // sample index within the block being processed
  bool tip_down = false;           // pen touching the surface
  double x_m = 0.0;                // position on the surface (height-field coordinates)
  double y_m = 0.0;
  double velocity_mps = 0.0;       // tangential speed along the stroke (>= 0)
  double normal_force_n = 0.0;     // from pen pressure
  double width_mm = 0.5;           // averaging window on the profile (tilt: upright = small)
  double penetration_m = 0.0;      // threshold above which the profile is felt (paper §4)
  ProbeStyle style = ProbeStyle::kScrape;
};

}  // namespace sas::synth
