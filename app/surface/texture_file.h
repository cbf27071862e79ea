#pragma once
// A kiosk texture's description file, textures/<name>/texture.toml (written by the texture
// generator; see docs/engineering.md, "Surfaces and the four textures"). It names the picture and
// the true height map next to it, the material (a file in textures/materials/), the gains, the
// probe defaults, the one-sentence description the kiosk speaks, and for bubble wrap the bubble
// layout and pop force:
//
//   name = "bubble wrap"                 description = "One sentence."
//   material = "bubble_wrap"             # bubble_wrap | glass | wood | dry_soil
//   picture = "picture.png"              height_map = "height.png"
//   height_scale_mm = 4.0                # height.png value 65535 = this many millimetres
//   relief_mm = 0.5                      # height of the strongest ridge in the picture's field
//   [gains]  sound_gain_db = 0.0   haptic_gain_db = 0.0   # -60..80: loudness-matching gains,
//            calibrated by the generator (calibration/texture_levels.h), added to the kiosk's gains
//   [levels] scrape_widths_mm = [0.3, 0.9, 1.9]   rub_widths_mm = [2.1, 4.0, 6.0]   # optional
//            speeds_mm_s = [40.0, 80.0, 160.0, 350.0]   pressures = [0.3, 0.45, 0.6]
//            scrape_sound_lufs = [...]   scrape_haptic_rms_db = [...]   rub_sound_lufs = [...]
//            rub_haptic_rms_db = [...]   # widths x speeds x pressures values each, width-major:
//            the texture's measured stroke levels at its [gains] (levels/stroke_gain.h)
//            roll_widths_mm, roll_sound_lufs, roll_haptic_rms_db: optional, all three or none
//   [probe]  width_mm = 0.5   penetration_mm = 0.02   style = "scrape"   # scrape | rub | roll
//   [bubbles]  pop_force_n = 3.0  layout = "hexagonal"  pitch_px  radius_px  origin_x_px
//   origin_y_px
// A curator's texture (`sketch-a-scratch texture new`) may also hold:
//   relief_from = "edges"                # edges (default: the paper's gray-level change) |
//                                        # brightness (the picture's luminance is the height: scans)
//   scan = "scan.csv"                    # the scan it was made from (checked, not read by the kiosk)
//   [names]  de = "..."  fr = "..."      # the name and the description in other languages
//   [descriptions]  de = "..."           # (two lower-case letters; English is name/description)
// and its material may be any material file's name (the texture's folder is searched first).
//
// Every key is checked: unknown keys, missing keys, wrong types and out-of-range values are
// LoadErrors of the form "<file>:<line>:<col>: <key>: <why>".

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "surface/bubble_wrap.h"
#include "synth/probe_command.h"

namespace sas::surface {

struct TextureGains {
  double sound_gain_db = 0.0;
  double haptic_gain_db = 0.0;
  // Added to the sound after the per-stroke matching (levels/stroke_gain.h), which would undo a
  // change of sound_gain_db: for what the calibration grid leaves out (bubble wrap's pops), so the
  // texture's median visitor stroke still matches the others'. Optional in the file, 0 dB.
  double sound_trim_db = 0.0;
  // The same for the transducer (the vibration's matching, skin-weighted). Optional, 0 dB.
  double haptic_trim_db = 0.0;
};

// The texture's loudness (ch 1, LUFS) and vibration strength (ch 2, dB RMS) at its [gains] over a
// grid of strokes: style (scrape, rub) x pen speed x pen pressure, measured by the texture
// generator (calibration/texture_levels.h); the kiosk's per-stroke gains are computed from it
// (levels/stroke_gain.h). Values are [style][width][speed][pressure], flattened in that order.
struct StrokeLevelTable {
  static constexpr int kMaxStyles = 3;   // 0 scrape, 1 rub, 2 roll (optional)
  std::vector<double> scrape_widths_mm;  // probe widths of each style, strictly increasing, > 0;
  std::vector<double> rub_widths_mm;     // as many as the scrape's
  std::vector<double>
      roll_widths_mm;               // any number; empty: no roll rows (a roll reads the scrape's)
  std::vector<double> speeds_mm_s;  // strictly increasing, > 0
  std::vector<double> pressures;    // strictly increasing, in (0, 1]
  std::vector<double> sound_lufs;   // styles() x widths x speeds x pressures
  std::vector<double> haptic_rms_db;

  int styles() const { return roll_widths_mm.empty() ? 2 : 3; }
  const std::vector<double>& widths_mm(int style) const {
    return style == 0 ? scrape_widths_mm : style == 1 ? rub_widths_mm : roll_widths_mm;
  }
  std::size_t Index(int style, std::size_t width, std::size_t speed, std::size_t pressure) const {
    // Widths of the styles before this one: the blocks follow each other, style-major.
    std::size_t before = 0;
    for (int s = 0; s < style; ++s) before += widths_mm(s).size();
    return ((before + width) * speeds_mm_s.size() + speed) * pressures.size() + pressure;
  }
  bool SameGrid(const StrokeLevelTable& other) const {
    return scrape_widths_mm == other.scrape_widths_mm && rub_widths_mm == other.rub_widths_mm &&
           roll_widths_mm == other.roll_widths_mm && speeds_mm_s == other.speeds_mm_s &&
           pressures == other.pressures;
  }
};

struct TextureProbeDefaults {
  double width_mm = 0.5;
  double penetration_mm = 0.02;
  synth::ProbeStyle style = synth::ProbeStyle::kScrape;
};

struct BubbleSettings {
  double pop_force_n = 3.0;
  BubbleLayout layout;
};

struct TextureFile {
  std::string name;
  std::string description;   // one sentence, spoken by the kiosk
  std::string material;      // a material file's name: bubble_wrap | glass | wood | dry_soil | ...
  std::string picture_path;  // absolute or relative to the working directory (resolved)
  std::string height_map_path;
  double height_scale_mm = 1.0;
  double relief_mm = 0.5;
  TextureGains gains;
  std::optional<StrokeLevelTable> levels;  // absent: no per-stroke matching for this texture
  TextureProbeDefaults probe;
  std::optional<BubbleSettings> bubbles;  // bubble wrap only
  bool relief_from_brightness = false;    // relief_from = "brightness"
  std::string scan_path;                  // "" when not made from a scan (resolved)
  std::map<std::string, std::string> names;         // language code -> name, besides English
  std::map<std::string, std::string> descriptions;  // language code -> one sentence
};

// Parses and validates; relative file names are resolved against the texture file's folder.
TextureFile LoadTextureFile(const std::string& path);
TextureFile ParseTextureFile(const std::string& text, const std::string& path);

}  // namespace sas::surface
