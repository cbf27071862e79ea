#pragma once
// A kiosk texture's description file, textures/<name>/texture.toml (written by the texture
// generator; see textures/README section in the project README). It names the picture and the
// true height map next to it, the material (a file in textures/materials/), the gains, the probe
// defaults, the one-sentence description the kiosk speaks, and for bubble wrap the bubble layout
// and pop force:
//
//   name = "bubble wrap"                 description = "One sentence."
//   material = "bubble_wrap"             # bubble_wrap | glass | wood | dry_soil
//   picture = "picture.png"              height_map = "height.png"
//   height_scale_mm = 4.0                # height.png value 65535 = this many millimetres
//   relief_mm = 0.5                      # height of the strongest ridge in the picture's field
//   [gains]  sound_gain_db = 0.0   haptic_gain_db = 0.0   # -60..80: loudness-matching gains,
//            calibrated by the generator (kiosk/texture_levels.h), added to the kiosk's gains
//   [probe]  width_mm = 0.5   penetration_mm = 0.02   style = "scrape"   # scrape | rub | roll
//   [bubbles]  pop_force_n = 3.0  layout = "hexagonal"  pitch_px  radius_px  origin_x_px
//   origin_y_px
//
// Every key is checked: unknown keys, missing keys, wrong types and out-of-range values are
// LoadErrors of the form "<file>:<line>:<col>: <key>: <why>".

#include <optional>
#include <string>

#include "surface/bubble_wrap.h"
#include "synth/probe_command.h"

namespace sas::surface {

struct TextureGains {
  double sound_gain_db = 0.0;
  double haptic_gain_db = 0.0;
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
  std::string material;      // bubble_wrap | glass | wood | dry_soil
  std::string picture_path;  // absolute or relative to the working directory (resolved)
  std::string height_map_path;
  double height_scale_mm = 1.0;
  double relief_mm = 0.5;
  TextureGains gains;
  TextureProbeDefaults probe;
  std::optional<BubbleSettings> bubbles;  // bubble wrap only
};

// Parses and validates; relative file names are resolved against the texture file's folder.
TextureFile LoadTextureFile(const std::string& path);
TextureFile ParseTextureFile(const std::string& text, const std::string& path);

}  // namespace sas::surface
