#pragma once
// Where the kiosk's data lives: the four kiosk textures, the spoken cues and the language tables,
// each searched in $SAS_DATA_DIR, the source tree and the installed share/sketch-a-scratch, in
// that order (the cues also in the build's own tree).

#include <string>
#include <vector>

namespace sas::kiosk {

// The four kiosk textures in token order (bubble wrap, broken glass, wooden board, cracked ground:
// the paper's §5.2 order), from the first of $SAS_DATA_DIR/textures, the source tree and the
// installed share/sketch-a-scratch/textures that holds them. Throws std::runtime_error when none.
std::vector<std::string> FindTextureFiles();
// The kiosk textures' names in token order ("bubble_wrap", "broken_glass", ...).
std::vector<std::string> KioskTextureNames();

// textures/<name>/texture.toml for kiosk texture `name`, from the first data folder holding it
// (the order above); "" when `name` is no kiosk texture or no folder holds it.
std::string FindTextureFile(const std::string& name);
// <data>/cues: $SAS_DATA_DIR/cues, the build's cue folder, the installed one; "" when none exists.
std::string FindCuesDir();
// <data>/strings (the language tables, strings.h), the same search order; "" when none has en.toml.
std::string FindStringsDir();

}  // namespace sas::kiosk
