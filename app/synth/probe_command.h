#pragma once
// What the control side tells the audio thread about the stylus, once per input event. Small POD
// so it crosses the SPSC queue by copy. The scene splits its block at
// `frame_offset` so the command takes effect on the exact sample it belongs to.

#include <cstdint>
#include <optional>
#include <string_view>

namespace sas::synth {

enum class ProbeStyle : std::uint8_t {
  kScrape,  // small width, impact-dominated
  kRub,     // large width, friction-dominated
  kRoll,    // a ball of radius r follows the envelope of the profile
};

// The styles' names in files, command lines and reports: "scrape", "rub", "roll".
constexpr std::string_view ProbeStyleName(ProbeStyle style) {
  switch (style) {
    case ProbeStyle::kRub:
      return "rub";
    case ProbeStyle::kRoll:
      return "roll";
    case ProbeStyle::kScrape:
    default:
      return "scrape";
  }
}
constexpr std::optional<ProbeStyle> ParseProbeStyle(std::string_view name) {
  for (const ProbeStyle style : {ProbeStyle::kScrape, ProbeStyle::kRub, ProbeStyle::kRoll}) {
    if (name == ProbeStyleName(style)) return style;
  }
  return std::nullopt;
}

struct ProbeCommand {
  std::uint32_t frame_offset = 0;  // sample index within the block being processed
  bool tip_down = false;           // pen touching the surface
  double x_m = 0.0;                // position on the surface (height-field coordinates)
  double y_m = 0.0;
  double velocity_mps = 0.0;    // tangential speed along the stroke (>= 0)
  double normal_force_n = 0.0;  // from pen pressure
  double width_mm = 0.5;        // averaging window on the profile (tilt: upright = small)
  // Threshold above which the profile is felt (paper §4), as a depth below the field's highest
  // point: the probe feels max(h, h_max - penetration_m), so 0 = only the peaks, a depth larger
  // than the field's relief = the whole profile. Pen pressure maps here.
  double penetration_m = 0.0;
  ProbeStyle style = ProbeStyle::kScrape;
  // Unit vector of the stroke on the surface: between commands the scene advances the probe by
  // velocity_mps · direction · (1 / fs) per sample (paper §4: Δx = v Δt; passive mode = a gesture
  // at a set velocity and no further commands).
  double direction_x = 1.0;
  double direction_y = 0.0;
  // Speed (m/s, >= 0) at which the tip lands on the surface when tip_down goes false -> true
  // (a tap). Ignored while the tip stays down.
  double landing_speed_mps = 0.1;
  // A short burst (e.g. a bubble popping): an impulse (N·s, >= 0) given to the probe towards the
  // surface at this frame. It reaches the resonator only through the contact model, so its
  // spectrum follows the material's stiffness. Works with the tip up too (the probe is then
  // released at the surface, bounces off and is parked again).
  double burst_impulse_n_s = 0.0;
};

}  // namespace sas::synth
