#pragma once
// The exhibit's colours, the one place they are defined: white B612 text on near-black plates
// over the textures, and a few muted accents that carry meaning (red: recording or clipping,
// amber: a warning, green: good, blue: information and the staff panel's buttons). Accents are
// used as small marks (a dot, a stripe, a meter segment), never as large saturated areas; the
// text over them always sits on a plate, which keeps it at 7:1 or more whatever is under it.

#include "ui/image_rgba.h"

namespace sas::ui {

inline constexpr Rgba kPlate{12, 12, 12, 235};        // under every line of visitor text
inline constexpr Rgba kInk{255, 255, 255, 255};       // visitor text
inline constexpr Rgba kVeil{0, 0, 0, 255};            // the attract screen's breathing veil
inline constexpr Rgba kPanel{16, 20, 28, 210};        // the staff panel's plate
inline constexpr Rgba kPanelInk{235, 235, 235, 255};  // staff panel text
inline constexpr Rgba kFrameLine{230, 230, 230, 255};
inline constexpr Rgba kRed{214, 45, 40, 255};     // recording, a clipping level
inline constexpr Rgba kAmber{250, 190, 60, 255};  // warnings, a level close to clipping
inline constexpr Rgba kGreen{92, 178, 112, 255};  // a good level, the voice is ready
inline constexpr Rgba kBlue{88, 140, 214, 255};   // information (speak louder)
inline constexpr Rgba kGrey{150, 150, 150, 255};  // not available
inline constexpr Rgba kButton{40, 62, 100, 255};  // staff buttons (white on it: 8.9:1)

// `c` at opacity `alpha` (0..255).
constexpr Rgba WithAlpha(Rgba c, int alpha) {
  return {c.r, c.g, c.b, static_cast<std::uint8_t>(alpha < 0 ? 0 : alpha > 255 ? 255 : alpha)};
}

}  // namespace sas::ui
