// Where the kiosk's data lives (see data_dirs.h).
#include "kiosk/data_dirs.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "sas/version.h"

namespace sas::kiosk {
namespace {

namespace fs = std::filesystem;

// Token order: the paper's §5.2 order of the four textures.
const std::vector<std::string> kTextureKeys = {"bubble_wrap", "broken_glass", "wooden_board",
                                               "cracked_ground"};

std::vector<std::string> DataDirs(const std::string& sub) {
  std::vector<std::string> dirs;
  if (const char* data = std::getenv("SAS_DATA_DIR"); data != nullptr && *data) {
    dirs.push_back((fs::path(data) / sub).string());
  }
  dirs.push_back((fs::path(kSourceDir) / "textures" / (sub == "textures" ? "" : sub)).string());
  dirs.push_back((fs::path(kInstallPrefix) / "share" / "sketch-a-scratch" / sub).string());
  return dirs;
}

}  // namespace

std::vector<std::string> FindTextureFiles() {
  std::string searched;
  for (const auto& dir : DataDirs("textures")) {
    std::vector<std::string> files;
    for (const auto& key : kTextureKeys) {
      const fs::path file = fs::path(dir) / key / "texture.toml";
      std::error_code error;
      if (fs::is_regular_file(file, error)) files.push_back(file.string());
    }
    if (files.size() == kTextureKeys.size()) return files;
    searched += (searched.empty() ? "" : ", ") + dir;
  }
  throw std::runtime_error("the four kiosk textures were not found (searched " + searched + ")");
}

std::vector<std::string> KioskTextureNames() {
  return kTextureKeys;
}

std::string FindTextureFile(const std::string& name) {
  if (std::find(kTextureKeys.begin(), kTextureKeys.end(), name) == kTextureKeys.end()) return {};
  for (const auto& dir : DataDirs("textures")) {
    const fs::path file = fs::path(dir) / name / "texture.toml";
    std::error_code error;
    if (fs::is_regular_file(file, error)) return file.string();
  }
  return {};
}

std::string StaffTexturesDir(const std::string& staff_dir) {
  return staff_dir.empty() ? std::string() : (fs::path(staff_dir) / kStaffTexturesFolder).string();
}

std::vector<TokenTexture> ResolveTokenTextures(const std::vector<std::string>& token_textures,
                                               const std::string& staff_dir) {
  std::vector<TokenTexture> tokens;
  const std::string staff = StaffTexturesDir(staff_dir);
  for (std::size_t i = 0; i < token_textures.size(); ++i) {
    const std::string& name = token_textures[i];
    TokenTexture token;
    const std::string shipped_here = i < kTextureKeys.size() ? kTextureKeys[i] : kTextureKeys[0];
    const fs::path staff_file = fs::path(staff) / name / "texture.toml";
    std::error_code error;
    if (!staff.empty() && fs::exists(staff_file.parent_path(), error)) {
      // A folder of that name is the staff's choice even when its texture.toml is missing: the
      // load then refuses it, saying so, rather than quietly showing the shipped one.
      token.path = staff_file.string();
      token.staff = true;
    } else {
      token.path = FindTextureFile(name);
    }
    if (token.staff || token.path.empty() || name != shipped_here) {
      token.fallback = FindTextureFile(shipped_here);
    }
    tokens.push_back(token);
  }
  return tokens;
}

std::string FindStringsDir() {
  for (const auto& dir : DataDirs("strings")) {
    std::error_code error;
    if (fs::is_regular_file(fs::path(dir) / "en.toml", error)) return dir;
  }
  return {};
}

std::string FindCuesDir() {
  std::vector<std::string> dirs = DataDirs("cues");
  // The build generates the cues in its own tree (<build>/textures/cues, the binary being
  // <build>/app/sketch-a-scratch).
  std::error_code exe_error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", exe_error);
  if (!exe_error) dirs.push_back((exe.parent_path().parent_path() / "textures" / "cues").string());
  for (const auto& dir : dirs) {
    std::error_code error;
    if (fs::is_directory(dir, error)) return dir;
  }
  return {};
}

}  // namespace sas::kiosk
