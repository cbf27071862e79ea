// Texture set loading (see texture_set.h).
#include "surface/texture_set.h"

#include <future>

#include "surface/image_surface.h"

namespace sas::surface {

LoadedTexture LoadTexture(const std::string& path, const TextureLoadOptions& options) {
  LoadedTexture t;
  t.file = LoadTextureFile(path);
  ReliefOptions relief;
  relief.relief_mm = t.file.relief_mm;
  // A scan's picture is its heights as brightness (texture new --scan): read as such, not as
  // the edges of a photograph.
  if (t.file.relief_from_brightness) relief.source = ReliefSource::kLuminance;
  if (options.pixel_pitch_mm > 0.0) relief.pixel_pitch_mm = options.pixel_pitch_mm;
  HeightField field =
      SurfaceFromImage(LoadGrayImage(t.file.picture_path, options.limits), relief).field;
  t.field = std::make_shared<const HeightField>(std::move(field));
  if (t.file.bubbles)
    t.bubbles.emplace(t.file.bubbles->layout, t.file.bubbles->pop_force_n, t.field);
  return t;
}

std::vector<LoadedTexture> LoadTextures(const std::vector<std::string>& paths,
                                        const TextureLoadOptions& options) {
  std::vector<std::future<LoadedTexture>> pending;
  pending.reserve(paths.size());
  for (const auto& path : paths) {
    pending.push_back(
        std::async(std::launch::async, [&path, &options] { return LoadTexture(path, options); }));
  }
  std::vector<LoadedTexture> out;
  out.reserve(paths.size());
  for (auto& p : pending) out.push_back(p.get());  // rethrows the first failure
  return out;
}

}  // namespace sas::surface
