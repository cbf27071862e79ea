#pragma once
// Surfaces for the offline renderer and tests: a few deterministic built-in height fields, or a
// picture turned into one. All built-ins are 512 x 256 samples at the panel's 0.153 mm pitch
// (78 x 39 mm), heights >= 0 in metres:
//   grating  regular ridges across x: 2 mm period, 0.6 mm wide raised-cosine ridges, 0.1 mm high
//            (a ribbed surface: scraping it gives a pitched buzz at v / 2 mm)
//   rough    seeded multi-scale value noise, 0.1 mm peak to peak (sandpaper-like, no period)
//   bumps    80 seeded raised-cosine bumps, radius 0.8..2 mm, 0.15 mm high (bubble wrap, studs)
//   cracks   seeded Voronoi plates 0.2 mm high separated by 0.4 mm wide cracks (dry ground)
//   flat     all zero (the material alone)
// "Seeded" means a fixed seed and our own integer hashing: the same field on every machine.
//
// Anything else is a file: a kiosk texture description (textures/<name>/texture.toml) gives its
// true height map; a picture (PNG, JPEG, BMP) goes through the surface layer's picture -> height
// field pipeline (paper §2: regions of maximal gray-level change become ridges, even regions stay
// flat; surface/image_surface.h, default options: 0.5 mm relief, panel pitch 0.153 mm).

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "surface/height_field.h"

namespace sas::kiosk {

class ProfileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline constexpr int kBuiltinProfileWidth = 512;
inline constexpr int kBuiltinProfileHeight = 256;
inline constexpr double kProfilePitchM = 0.153e-3;

std::vector<std::string> BuiltinProfileNames();
std::optional<surface::HeightField> MakeBuiltinProfile(const std::string& name);

// A built-in name, a texture.toml or a picture file. Throws ProfileError naming the file and
// listing the built-ins.
surface::HeightField LoadProfile(const std::string& name_or_path);

// The material a texture file names ("wood" for textures/wooden_board/texture.toml); empty for
// built-ins and pictures.
std::string ProfileMaterial(const std::string& name_or_path);

}  // namespace sas::kiosk
