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
// The staff's own textures: <staff_dir>/textures (outside the package: upgrades and reinstalls
// keep them, a purge removes them with the rest of the staff's files). "" when staff_dir is "".
inline constexpr const char* kStaffTexturesFolder = "textures";
std::string StaffTexturesDir(const std::string& staff_dir);

// What a token shows: the texture file for its configured name (a staff texture of that name
// first, then a shipped one), and the shipped texture of the token's place to fall back on when
// that one does not load ("" when it is itself the shipped one).
struct TokenTexture {
  std::string path;      // "" when no folder holds the name (the fallback is then used)
  std::string fallback;  // the shipped texture of the token's place
  bool staff = false;    // path is a staff texture
};
// One per token, for `token_textures` (KioskConfig [textures]) and `staff_dir`.
std::vector<TokenTexture> ResolveTokenTextures(const std::vector<std::string>& token_textures,
                                               const std::string& staff_dir);

// <data>/cues: $SAS_DATA_DIR/cues, the build's cue folder, the installed one; "" when none exists.
std::string FindCuesDir();
// <data>/strings (the language tables, strings.h), the same search order; "" when none has en.toml.
std::string FindStringsDir();

}  // namespace sas::kiosk
