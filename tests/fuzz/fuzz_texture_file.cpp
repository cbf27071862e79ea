// libFuzzer target : arbitrary bytes as a texture description
// (textures/<name>/texture.toml). ParseTextureFile documents LoadError for every bad file; anything
// else escaping is a bug. Only the text is parsed: the picture files it names are not opened.
#include <cstddef>
#include <cstdint>
#include <string>

#include "surface/image_loader.h"  // LoadError
#include "surface/texture_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const sas::surface::TextureFile texture =
        sas::surface::ParseTextureFile(text, "/fuzz/texture/texture.toml");
    if (texture.description.empty() || texture.picture_path.empty()) __builtin_trap();
  } catch (const sas::surface::LoadError&) {
    // documented rejection of a bad file
  }
  return 0;
}
