// texture_generator: makes the four kiosk textures of the installation (paper §5.2.1, figure 6:
// bubble wrap, broken glass, wooden board, cracked ground): paints each (texture_painting.h: the
// true height map in millimetres, then the "macro photograph" rendered from it), writes it, and
// calibrates its gains.
// Outputs, per texture, in <out>/<name>/: picture.png (1920 x 1080 BGR), height.png (16-bit,
// 65535 = height_scale_mm) and texture.toml (see app/surface/texture_file.h), whose [gains] are
// calibrated last: the kiosk engine loads the written files as the kiosk does and plays a set of
// visitor strokes (scrape and rub, slow to fast) on them, and the gains bring their loudness and
// vibration strength to common targets (calibration/texture_levels.h), so the four textures are
// matched in level for what visitors do.
//
// Deterministic: every random number comes from cv::RNG (a documented multiply-with-carry
// generator) seeded per texture, OpenCV runs single-threaded, and PNG compression settings are
// fixed, so running it again reproduces the committed bytes (tests/surface checks this).
//
// Usage: texture_generator <out_dir> [--only <name>] [--size <w> <h>] (--help: the options)

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "calibration/texture_levels.h"
#include "texture_painting.h"
#include "tools/command_line.h"

namespace {

using sas::textures::Canvas;
using sas::textures::kPitchMm;
using sas::textures::TextureOut;

// a blank-free block of rows per width.
std::string LevelsToml(const sas::surface::StrokeLevelTable& levels) {
  const auto list = [](const std::vector<double>& values, std::size_t from, std::size_t count,
                       std::size_t per_row) {
    std::string out = "[";
    char number[32];
    for (std::size_t i = 0; i < count; ++i) {
      if (i > 0) out += i % per_row == 0 ? ",\n  " : ", ";
      std::snprintf(number, sizeof number, "%.2f", values[from + i] + 0.0);
      out += number;
    }
    return out + "]\n";
  };
  const std::size_t widths = levels.scrape_widths_mm.size();
  const std::size_t speeds = levels.speeds_mm_s.size(), pressures = levels.pressures.size();
  std::string out =
      "\n[levels]\n# This texture's stroke levels at the gains above, measured on the grid below "
      "(levels/stroke_gain.h):\n# per style, per probe width one block of rows, one row per speed, "
      "one value per pressure.\n# The kiosk corrects each stroke towards the median of the loaded "
      "textures' levels for it.\n";
  out += "scrape_widths_mm = " + list(levels.scrape_widths_mm, 0, widths, widths);
  out += "rub_widths_mm = " + list(levels.rub_widths_mm, 0, widths, widths);
  const std::size_t rolls = levels.roll_widths_mm.size();
  if (levels.styles() > 2)
    out += "roll_widths_mm = " + list(levels.roll_widths_mm, 0, rolls, rolls);
  out += "speeds_mm_s = " + list(levels.speeds_mm_s, 0, speeds, speeds);
  out += "pressures = " + list(levels.pressures, 0, pressures, pressures);
  const char* names[] = {"scrape", "rub", "roll"};
  for (int style = 0; style < levels.styles(); ++style) {
    const std::size_t from = levels.Index(style, 0, 0, 0);
    const std::size_t per_style = levels.widths_mm(style).size() * speeds * pressures;
    out += std::string(names[style]) +
           "_sound_lufs = " + list(levels.sound_lufs, from, per_style, pressures);
    out += std::string(names[style]) +
           "_haptic_rms_db = " + list(levels.haptic_rms_db, from, per_style, pressures);
  }
  return out;
}

void Write(const TextureOut& t, const std::filesystem::path& root, const Canvas& c) {
  const auto folder = root / t.folder;
  std::filesystem::create_directories(folder);
  cv::Mat height16(t.height_mm.rows, t.height_mm.cols, CV_16UC1);
  for (int y = 0; y < t.height_mm.rows; ++y) {
    for (int x = 0; x < t.height_mm.cols; ++x) {
      const double v = std::clamp(t.height_mm(y, x) / t.height_scale_mm, 0.0, 1.0);
      height16.at<std::uint16_t>(y, x) = static_cast<std::uint16_t>(std::lround(v * 65535.0));
    }
  }
  const std::vector<int> png = {cv::IMWRITE_PNG_COMPRESSION, 6, cv::IMWRITE_PNG_STRATEGY,
                                cv::IMWRITE_PNG_STRATEGY_DEFAULT};
  if (!cv::imwrite((folder / "picture.png").string(), t.picture, png) ||
      !cv::imwrite((folder / "height.png").string(), height16, png)) {
    throw std::runtime_error("cannot write PNGs into " + folder.string());
  }
  const auto write_toml = [&](const sas::surface::TextureGains& gains, const std::string& note,
                              const std::string& levels) {
    std::ofstream toml(folder / "texture.toml", std::ios::binary);
    char text[160];
    std::snprintf(text, sizeof text, "sound_gain_db = %.2f\nhaptic_gain_db = %.2f\n",
                  gains.sound_gain_db, gains.haptic_gain_db);
    std::string trim;
    if (t.sound_trim_db != 0.0 && !levels.empty()) {
      char line[64];
      std::snprintf(line, sizeof line, "sound_trim_db = %.2f\n", t.sound_trim_db);
      trim = t.sound_trim_why + line;
    }
    if (t.haptic_trim_db != 0.0 && !levels.empty()) {
      char line[64];
      std::snprintf(line, sizeof line, "haptic_trim_db = %.2f\n", t.haptic_trim_db);
      trim += t.haptic_trim_why + line;
    }
    toml << "# " << t.folder << ": generated by textures/texture_generator (" << c.width << " x "
         << c.height << " px at " << kPitchMm << " mm/px); edit the generator, not this file.\n"
         << t.toml << "\n[gains]\n"
         << note << text << trim << levels << t.toml_tail;
    if (!toml) throw std::runtime_error("cannot write texture.toml into " + folder.string());
  };
  // Loudness matching: the texture file first goes out with 0 dB gains and no [levels]
  // so the kiosk engine can play the calibration strokes on exactly what the kiosk loads
  // (material, picture as written); then the measured gains and stroke levels are written.
  write_toml({}, "", "");
  const std::string path = (folder / "texture.toml").string();
  const sas::kiosk::TextureCalibration calibration = sas::kiosk::CalibrateTexture(path);
  const sas::kiosk::CalibrationGrid grid;
  char note[400];
  std::snprintf(
      note, sizeof note,
      "# Loudness-matched through the kiosk engine (calibration/texture_levels.h): the mean of "
      "%zu visitor\n# strokes (the [levels] grid, each at %d places) at %.1f LUFS (ch 1, "
      "K-weighted) and %.1f dB RMS\n# (ch 2, skin-weighted).\n",
      sas::kiosk::CalibrationStrokes().size(), grid.places, sas::kiosk::kTargetSoundLufs,
      sas::kiosk::kTargetHapticRmsDb);
  write_toml(calibration.gains, note, LevelsToml(calibration.levels));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Paints the four kiosk textures (picture, true height map, texture.toml) into "
      "<out_dir>/<name>/ and calibrates their gains.",
      "texture_generator"};
  std::string out_dir;
  std::string only;
  std::vector<int> size;
  app.add_option("out_dir", out_dir, "folder to write the textures' folders into")->required();
  app.add_option("--only", only, "make only this texture (e.g. wooden_board)");
  app.add_option("--size", size, "picture size in pixels (default 1920 1080)")
      ->expected(2)
      ->check(CLI::Range(64, 8192));
  if (const int code = sas::kiosk::ParseProgramCommandLine(app, argc, argv); code >= 0) return code;
  cv::setNumThreads(1);
  cv::setRNGSeed(1);
  const std::filesystem::path root = out_dir;
  Canvas canvas;
  if (size.size() == 2) {
    canvas.width = size[0];
    canvas.height = size[1];
    canvas.scale = canvas.width / 1920.0;
  }
  const std::vector<std::pair<std::string, std::function<TextureOut(const Canvas&)>>> makers = {
      {"bubble_wrap", sas::textures::BubbleWrap},
      {"broken_glass", sas::textures::BrokenGlass},
      {"wooden_board", sas::textures::WoodenBoard},
      {"cracked_ground", sas::textures::CrackedGround}};
  bool any = false;
  for (const auto& [name, make] : makers) {
    if (!only.empty() && only != name) continue;
    any = true;
    try {
      Write(make(canvas), root, canvas);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
      return 1;
    }
    std::printf("wrote %s\n", (root / name).string().c_str());
  }
  if (!any) {
    std::fprintf(stderr, "texture_generator: no texture named '%s'\n", only.c_str());
    return 2;
  }
  return 0;
}
