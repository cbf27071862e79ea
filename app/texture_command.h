#pragma once
// `sketch-a-scratch texture new | check | preview | install`: a curator's own texture, from a
// photograph or a scan to a calibrated, spoken texture the kiosk shows on a token.
//
//   new      a photo (PNG or JPEG, any size: cropped to the display's aspect from the middle and
//            scaled to 1920 x 1080), a height map (a grey 8- or 16-bit PNG, its brightness the
//            relief, cropped and scaled alike) or a scan (CSV of heights in mm: one line of a
//            profilometer or vibration scan, or a grid; the paper's scan -> profile), a material (a shipped
//            one's name or a material file, copied into the folder), the name and description in
//            every language the kiosk speaks -> a texture folder: texture.toml, picture.png,
//            height.png (the relief the kiosk derives), its [gains] and [levels] calibrated as the
//            shipped textures' are (calibration/texture_levels.h), then a trim that puts its
//            median over the visitor population at the shipped textures' mean (population_levels.h;
//            the shipped textures' medians come from a cache when it holds them: population_cache.h),
//            and cues/<language>/<name>_name.wav and _description.wav (espeak-ng with the
//            language's voice, or the curator's recordings with --cues-from).
//   check    every problem as "<file>:<line>: <key>: <what>" (exit 1), else the figures a curator
//            looks at: the level against the shipped textures, how the sound follows the hand,
//            and how much of the relief a pen feels.
//   preview  a few visitor strokes through the kiosk engine: WAVs and PNGs with the dent.
//   install  check, then copy the folder to <staff_dir>/textures/<name>/ (atomically: a bad
//            folder installs nothing) and, with --token N, point token N of kiosk.toml at it.
// Exit status: 0 ok, 1 a problem (every one printed), 2 usage error.

#include <cstdio>
#include <string>
#include <vector>

namespace sas::app {

int RunTextureCommand(const std::vector<std::string>& args, std::FILE* out, std::FILE* err);

// The problems of a texture folder for a kiosk speaking `languages`, each "<file>:<line>: <key>:
// <what>" (empty: none). Also used by install.
std::vector<std::string> CheckTextureFolder(const std::string& folder,
                                            const std::vector<std::string>& languages);

// A scan's heights (mm): rows of numbers separated by commas, semicolons or blanks; '#' starts a
// comment. Every row as long as the first. Problems are "<file>:<line>: height: <what>".
struct ScanGrid {
  std::vector<std::vector<double>> rows;
};
ScanGrid ReadScanCsv(const std::string& path, std::vector<std::string>* problems);

}  // namespace sas::app
