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
// A picture (any format surface::LoadGrayImage reads) maps luminance linearly to height: white =
// kImageReliefM, black = 0, one pixel per 0.153 mm. This is the simple placeholder; the surface
// layer's edge-based image pipeline (paper §2) can replace LoadProfile's image branch.

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
inline constexpr double kImageReliefM = 0.2e-3;

std::vector<std::string> BuiltinProfileNames();
std::optional<surface::HeightField> MakeBuiltinProfile(const std::string& name);

// A built-in name, or else a picture file. Throws ProfileError naming the file (or listing the
// built-ins when the argument is neither).
surface::HeightField LoadProfile(const std::string& name_or_path);

// Largest minus smallest height of a field (m): the relief the pen can feel.
double ReliefM(const surface::HeightField& field);

}  // namespace sas::kiosk
