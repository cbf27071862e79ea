#pragma once
// Picture -> height field (paper §2–§3): "the exploration of a surface has its salient points in
// the regions of maximal change [...] in brightness [...], which may represent tangible
// discontinuities such as ridges. In the same way, the evenly-coloured parts of the image
// represent flat parts of the surface." Chain, run once at load time (never per frame):
//   luminance -> Gaussian smoothing (sigma) -> Sobel gradient (magnitude, direction)
//   -> height = relief * clamp((|grad| - noise_floor) / (|grad|_sat - noise_floor), 0, 1)
// so the strongest gray-level changes become ridges `relief_mm` high and anything below the noise
// floor (film grain, sensor noise, even colour) is exactly flat. |grad|_sat is a high percentile of
// the picture's own gradients, so a low-contrast photo still spans the full relief.
//
// Sound images (sound_image.h) use ReliefSource::kLuminance instead: their luminance *is* the
// signal, and taking the gradient would halve a tone's period (|d/dx sin| repeats twice per
// cycle) and split each click into two ridges.
//
// Pixels map to millimetres through the display's physical size (DisplayGeometry), so a stroke of
// 10 mm on the glass crosses 10 mm of surface.

#include <memory_resource>
#include <vector>

#include "surface/height_field.h"
#include "surface/image_loader.h"

namespace sas::surface {

// Physical size of the panel the picture is shown on; default is the paper's 13.3-inch 1080p
// Cintiq.
struct DisplayGeometry {
  double diagonal_in = 13.3;
  int width_px = 1920;
  int height_px = 1080;
  // Square pixels assumed: pitch = diagonal / diagonal in pixels (≈ 0.1534 mm for the default).
  double pixel_pitch_mm() const;
};

enum class ReliefSource { kGrayLevelChange, kLuminance };

struct ReliefOptions {
  ReliefSource source = ReliefSource::kGrayLevelChange;
  double smoothing_sigma_px = 1.0;      // Gaussian before differentiating; 0 = none
  double relief_mm = 0.5;               // height of the strongest ridge (or of white, kLuminance)
  double noise_floor_per_px = 0.012;    // luminance change per pixel that still counts as flat
  double saturation_percentile = 0.99;  // |grad| at this quantile maps to the full relief
  double pixel_pitch_mm = DisplayGeometry{}.pixel_pitch_mm();
  bool keep_gradient = false;  // also return magnitude and direction (overlays, tests)
};

// The height field plus what the detector saw, for overlays and for the accuracy report.
struct ImageSurface {
  HeightField field;  // metres
  // Only with ReliefOptions::keep_gradient (kGrayLevelChange), else empty:
  std::vector<float> gradient_magnitude;      // luminance per pixel, after smoothing
  std::vector<float> gradient_direction_rad;  // direction of increasing luminance, [0, 2π)
};

// Throws std::invalid_argument for an empty image or options out of range. The field's buffers
// come from `memory` (the gradients from the default resource).
ImageSurface SurfaceFromImage(const GrayImage& image, const ReliefOptions& options = {},
                              std::pmr::memory_resource* memory = std::pmr::get_default_resource());

// Convenience: load `path` (image_loader.h) and derive its height field.
HeightField HeightFieldFromImageFile(const std::string& path, const ReliefOptions& options = {},
                                     const ImageLoadLimits& limits = {});

// A 16-bit true height map (as written by the texture generator): value v -> v / 65535 * scale_mm.
HeightField LoadHeightMapPng(const std::string& path, double full_scale_mm, double pixel_pitch_mm,
                             const ImageLoadLimits& limits = {});

// One row of a field as a 1-D profile (a field one row high), e.g. the probe's path along x.
HeightField RowProfile(const HeightField& field, int row);

}  // namespace sas::surface
