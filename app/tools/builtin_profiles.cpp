// Built-in height fields and the picture -> height field placeholder (see builtin_profiles.h).
#include "tools/builtin_profiles.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "surface/image_loader.h"
#include "surface/image_surface.h"
#include "surface/texture_file.h"

namespace sas::kiosk {
namespace {

constexpr int kW = kBuiltinProfileWidth;
constexpr int kH = kBuiltinProfileHeight;
constexpr double kPi = std::numbers::pi;

// SplitMix64 finaliser (Steele, Lea & Flood, OOPSLA 2014): a well-mixed hash of an integer, so a
// "random" field is a pure function of its seed and indices, identical on every platform.
std::uint64_t Mix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// Uniform in [0, 1) from (seed, i, j).
double Uniform(std::uint64_t seed, std::uint64_t i, std::uint64_t j = 0) {
  const std::uint64_t bits = Mix(Mix(Mix(seed) ^ i) ^ (j * 0x632be59bd9b4e019ULL));
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

std::size_t Index(int x, int y) {
  return static_cast<std::size_t>(y) * static_cast<std::size_t>(kW) + static_cast<std::size_t>(x);
}

double SmoothStep(double u) {
  return u * u * (3.0 - 2.0 * u);
}

// Scales `heights` linearly so that they span [0, relief_m].
void Normalise(std::vector<double>& heights, double relief_m) {
  const auto [lo, hi] = std::minmax_element(heights.begin(), heights.end());
  const double low = *lo;
  const double span = *hi - *lo;
  for (double& h : heights) h = span > 0.0 ? (h - low) / span * relief_m : 0.0;
}

surface::HeightField ToField(const std::vector<double>& heights) {
  std::pmr::vector<float> out(heights.size());
  std::transform(heights.begin(), heights.end(), out.begin(),
                 [](double h) { return static_cast<float>(h); });
  return surface::HeightField(kW, kH, kProfilePitchM, std::move(out));
}

surface::HeightField Grating() {
  constexpr double kPeriodM = 2e-3;
  constexpr double kRidgeWidthM = 0.6e-3;
  constexpr double kRidgeHeightM = 0.1e-3;
  std::vector<double> heights(static_cast<std::size_t>(kW) * kH, 0.0);
  for (int x = 0; x < kW; ++x) {
    // Distance from the nearest ridge centre; ridges are raised cosines, so the profile has no
    // steps that only the sampling grid would decide.
    const double phase_m = std::fmod(x * kProfilePitchM, kPeriodM) - 0.5 * kPeriodM;
    const double d = std::abs(phase_m) / (0.5 * kRidgeWidthM);
    const double h = d < 1.0 ? kRidgeHeightM * 0.5 * (1.0 + std::cos(kPi * d)) : 0.0;
    for (int y = 0; y < kH; ++y) heights[Index(x, y)] = h;
  }
  return ToField(heights);
}

surface::HeightField Rough() {
  constexpr std::uint64_t kSeed = 0x5a5;
  std::vector<double> heights(static_cast<std::size_t>(kW) * kH, 0.0);
  // Value noise at cell sizes 2..32 samples, amplitude proportional to cell size (a 1/f-like
  // spectrum: coarse undulation with fine grit on it).
  for (int octave = 0; octave < 5; ++octave) {
    const int cell = 2 << octave;
    const double amplitude = static_cast<double>(cell);
    for (int y = 0; y < kH; ++y) {
      const int cy = y / cell;
      const double v = SmoothStep(static_cast<double>(y % cell) / cell);
      for (int x = 0; x < kW; ++x) {
        const int cx = x / cell;
        const double u = SmoothStep(static_cast<double>(x % cell) / cell);
        const auto corner = [&](int i, int j) {
          return Uniform(kSeed + static_cast<std::uint64_t>(octave),
                         static_cast<std::uint64_t>(cx + i), static_cast<std::uint64_t>(cy + j));
        };
        const double top = corner(0, 0) + u * (corner(1, 0) - corner(0, 0));
        const double bottom = corner(0, 1) + u * (corner(1, 1) - corner(0, 1));
        heights[Index(x, y)] += amplitude * (top + v * (bottom - top));
      }
    }
  }
  Normalise(heights, 0.1e-3);
  return ToField(heights);
}

surface::HeightField Bumps() {
  constexpr std::uint64_t kSeed = 0xb0b;
  constexpr int kCount = 80;
  constexpr double kHeightM = 0.15e-3;
  std::vector<double> heights(static_cast<std::size_t>(kW) * kH, 0.0);
  for (int b = 0; b < kCount; ++b) {
    const auto i = static_cast<std::uint64_t>(b);
    const double cx = Uniform(kSeed, i, 0) * kW;
    const double cy = Uniform(kSeed, i, 1) * kH;
    const double radius = (0.8e-3 + 1.2e-3 * Uniform(kSeed, i, 2)) / kProfilePitchM;
    const int x0 = std::max(0, static_cast<int>(cx - radius));
    const int x1 = std::min(kW - 1, static_cast<int>(cx + radius) + 1);
    const int y0 = std::max(0, static_cast<int>(cy - radius));
    const int y1 = std::min(kH - 1, static_cast<int>(cy + radius) + 1);
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const double d = std::hypot(x - cx, y - cy) / radius;
        if (d < 1.0) {
          const double h = kHeightM * 0.5 * (1.0 + std::cos(kPi * d));
          heights[Index(x, y)] = std::max(heights[Index(x, y)], h);  // overlapping bumps merge
        }
      }
    }
  }
  return ToField(heights);
}

surface::HeightField Cracks() {
  constexpr std::uint64_t kSeed = 0xc7ac;
  constexpr int kPlates = 40;
  constexpr double kPlateHeightM = 0.2e-3;
  constexpr double kCrackWidthM = 0.4e-3;
  double px[kPlates];
  double py[kPlates];
  for (int p = 0; p < kPlates; ++p) {
    px[p] = Uniform(kSeed, static_cast<std::uint64_t>(p), 0) * kW;
    py[p] = Uniform(kSeed, static_cast<std::uint64_t>(p), 1) * kH;
  }
  std::vector<double> heights(static_cast<std::size_t>(kW) * kH, 0.0);
  const double crack_px = kCrackWidthM / kProfilePitchM;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      // Distance to the nearest and second-nearest plate centre; their difference is (twice)
      // the distance to the Voronoi edge, where the ground has cracked.
      double d1 = 1e30;
      double d2 = 1e30;
      for (int p = 0; p < kPlates; ++p) {
        const double d = std::hypot(x - px[p], y - py[p]);
        if (d < d1) {
          d2 = d1;
          d1 = d;
        } else if (d < d2) {
          d2 = d;
        }
      }
      const double edge = std::clamp((d2 - d1) / crack_px, 0.0, 1.0);
      heights[Index(x, y)] = kPlateHeightM * SmoothStep(edge);
    }
  }
  return ToField(heights);
}

surface::HeightField Flat() {
  return ToField(std::vector<double>(static_cast<std::size_t>(kW) * kH, 0.0));
}

}  // namespace

std::vector<std::string> BuiltinProfileNames() {
  return {"grating", "rough", "bumps", "cracks", "flat"};
}

std::optional<surface::HeightField> MakeBuiltinProfile(const std::string& name) {
  if (name == "grating") return Grating();
  if (name == "rough") return Rough();
  if (name == "bumps") return Bumps();
  if (name == "cracks") return Cracks();
  if (name == "flat") return Flat();
  return std::nullopt;
}

namespace {

bool IsTextureFile(const std::string& path) {
  return path.size() > 5 && path.compare(path.size() - 5, 5, ".toml") == 0;
}

std::string BuiltinList() {
  std::string names;
  for (const auto& n : BuiltinProfileNames()) names += (names.empty() ? "" : ", ") + n;
  return names;
}

}  // namespace

surface::HeightField LoadProfile(const std::string& name_or_path) {
  if (auto builtin = MakeBuiltinProfile(name_or_path)) return std::move(*builtin);
  try {
    if (IsTextureFile(name_or_path)) {
      const surface::TextureFile texture = surface::LoadTextureFile(name_or_path);
      try {
        return surface::LoadHeightMapPng(texture.height_map_path, texture.height_scale_mm,
                                         surface::DisplayGeometry{}.pixel_pitch_mm());
      } catch (const std::exception& error) {
        // The height map's own message names only the PNG; say which texture wanted it.
        throw ProfileError(name_or_path + ": height_map: " + error.what());
      }
    }
    return surface::HeightFieldFromImageFile(name_or_path);
  } catch (const std::exception& error) {
    // LoadError from the loaders, invalid_argument from the pipeline: all name the file.
    throw ProfileError(std::string(error.what()) + " (a profile is a built-in (" + BuiltinList() +
                       "), a texture.toml or a picture file)");
  }
}

std::string ProfileMaterial(const std::string& name_or_path) {
  if (!IsTextureFile(name_or_path)) return "";
  try {
    return surface::LoadTextureFile(name_or_path).material;
  } catch (const std::exception& error) {
    throw ProfileError(error.what());
  }
}

}  // namespace sas::kiosk
