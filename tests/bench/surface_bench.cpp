// Surface benchmark: loads the four kiosk textures (texture file, picture, true height
// map), derives each picture's height field, and prints the wall time of load + derive for all
// four (target < 1 s together), then the accuracy of each derived field against its true map
// (ridge recall/precision within 2 px, flat share below penetration, correlations).
// Usage: surface_bench [textures_dir]   (default: the source tree's textures/)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

#include "../surface/ridge_metrics.h"
#include "surface/image_surface.h"
#include "surface/texture_set.h"

int main(int argc, char** argv) {
  const std::string root = argc > 1 ? argv[1] : SAS_TEXTURES_DIR;
  const std::vector<std::string> names = {"bubble_wrap", "broken_glass", "wooden_board",
                                          "cracked_ground"};
  std::vector<std::string> paths;
  for (const auto& name : names) paths.push_back(root + "/" + name + "/texture.toml");
  // Best of three runs: the figure is the loader's cost, not whatever else the machine is doing.
  double seconds = 1e9, cpu_seconds = 1e9;
  std::vector<sas::surface::LoadedTexture> textures;
  for (int run = 0; run < 3; ++run) {
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    textures = sas::surface::LoadTextures(paths);
    cpu_seconds =
        std::min(cpu_seconds, static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC);
    seconds = std::min(
        seconds, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::printf(
      "load 4 textures + derive height fields (parallel, best of 3): %.3f s wall, %.3f s CPU "
      "(target < 1 s)\n",
      seconds, cpu_seconds);
  for (const auto& t : textures) {
    std::printf("  %-15s %d x %d, max height %.3f mm\n", t.file.name.c_str(), t.field->width(),
                t.field->height(),
                1e3 * *std::max_element(t.field->heights_m().begin(), t.field->heights_m().end()));
  }
  std::printf("%-15s %8s %9s %8s %10s %10s %9s\n", "texture", "recall", "precision", "flat",
              "r(slope)", "r(height)", "ridge_px");
  for (const auto& t : textures) {
    // Accuracy needs the gradient direction too: derive again with it kept (not timed).
    sas::surface::ReliefOptions options;
    options.relief_mm = t.file.relief_mm;
    options.keep_gradient = true;
    const auto surface =
        sas::surface::SurfaceFromImage(sas::surface::LoadGrayImage(t.file.picture_path), options);
    const auto truth =
        sas::surface::LoadHeightMapPng(t.file.height_map_path, t.file.height_scale_mm,
                                       sas::surface::DisplayGeometry{}.pixel_pitch_mm());
    const auto r = sas::test::CompareWithTruth(surface, truth, t.file.probe.penetration_mm);
    std::printf("%-15s %7.2f%% %8.2f%% %7.2f%% %10.3f %10.3f %9ld\n", t.file.name.c_str(),
                100 * r.recall, 100 * r.precision, 100 * r.flat_below_penetration,
                r.correlation_slope, r.correlation_height, r.true_ridge_px);
  }
  return 0;
}
