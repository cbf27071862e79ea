#pragma once
// The four kiosk textures of the installation (paper §5.2.1, figure 6: bubble wrap, broken glass,
// wooden board, cracked ground), painted: each builds its true height map in millimetres, then
// renders the "macro photograph" from it, so the picture's ridges and the map's ridges are the
// same ones. Every random number comes from a cv::RNG seeded per texture: the same canvas gives
// the same bytes.

#include <opencv2/core.hpp>

#include <string>

#include "surface/image_surface.h"

namespace sas::textures {

inline const double kPitchMm = surface::DisplayGeometry{}.pixel_pitch_mm();

struct Canvas {
  int width = 1920;
  int height = 1080;
  double scale = 1.0;  // feature sizes scale with width / 1920 (small test renders)
};

struct TextureOut {
  std::string folder;
  cv::Mat1f height_mm;
  double height_scale_mm = 1.0;
  cv::Mat picture;
  std::string toml;       // texture.toml up to the [gains] table...
  std::string toml_tail;  // ...and after it: the gains are calibrated once the files exist
  double sound_trim_db = 0.0;  // [gains] sound_trim_db (surface/texture_file.h), 0: not written
  std::string sound_trim_why;  // its comment line in texture.toml
  double haptic_trim_db = 0.0;  // [gains] haptic_trim_db, the same for the transducer
  std::string haptic_trim_why;
};

TextureOut BubbleWrap(const Canvas& c);
TextureOut BrokenGlass(const Canvas& c);
TextureOut WoodenBoard(const Canvas& c);
TextureOut CrackedGround(const Canvas& c);

}  // namespace sas::textures
