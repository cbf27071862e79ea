#pragma once
// Loading the kiosk's textures at start-up: each texture file (texture_file.h), its picture turned
// into a height field (image_surface.h, the paper's gray-level-change relief at the texture's
// relief_mm) and, for bubble wrap, its bubble state (bubble_wrap.h). Textures load in parallel,
// one task each, so four 1080p textures are ready well inside the boot budget (boot to
// first interactive frame ≤ 2 s). Set-up only: errors are LoadErrors naming the file.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "surface/bubble_wrap.h"
#include "surface/height_field.h"
#include "surface/image_loader.h"
#include "surface/texture_file.h"

namespace sas::surface {

struct LoadedTexture {
  TextureFile file;
  std::shared_ptr<const HeightField> field;  // picture-derived, metres
  std::optional<BubbleWrapState> bubbles;    // bubble wrap only
};

struct TextureLoadOptions {
  double pixel_pitch_mm = 0.0;  // 0 = DisplayGeometry{} default
  ImageLoadLimits limits{};
};

// Loads every texture file in `paths` (in parallel) and returns them in the same order.
std::vector<LoadedTexture> LoadTextures(const std::vector<std::string>& paths,
                                        const TextureLoadOptions& options = {});

LoadedTexture LoadTexture(const std::string& path, const TextureLoadOptions& options = {});

}  // namespace sas::surface
