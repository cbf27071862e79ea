// A curator's textures beside the shipped ones (kiosk.toml [textures], <staff_dir>/textures/):
// the engine shows a staff texture on the token kiosk.toml names, with its own names per
// language; a staff texture that does not load (an unreadable texture.toml, a missing picture,
// no [levels]) is refused with a warning in the journal, and its token shows the shipped texture
// of its place instead.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "files/kiosk_config.h"
#include "kiosk/data_dirs.h"
#include "kiosk/kiosk_engine.h"
#include "platform/log/log.h"
#include "sas/version.h"
#include "support/temp_dir.h"

namespace {

namespace fs = std::filesystem;

// A staff texture `key` made of the shipped cracked ground's files (calibrated, [levels] and
// all), with a German name of its own.
void CopyShipped(const fs::path& into, const std::string& key) {
  const fs::path from = fs::path(sas::kSourceDir) / "textures" / "cracked_ground";
  fs::create_directories(into / key);
  fs::copy_file(from / "picture.png", into / key / "picture.png");
  fs::copy_file(from / "height.png", into / key / "height.png");
  std::ifstream in(from / "texture.toml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text += "\n[names]\nde = \"Flussbett\"\n";
  std::ofstream(into / key / "texture.toml") << text;
}

sas::kiosk::KioskEngineOptions Options(const sas::test::TempDir& staff) {
  sas::kiosk::KioskEngineOptions options;
  options.virtual_clock = true;
  options.spoken_cues = false;
  options.config.staff_dir = staff.path().string();
  return options;
}

// Options whose staff folder holds the staff texture "riverbed", shown on token `token` (1-4).
sas::kiosk::KioskEngineOptions OptionsWithRiverbed(const sas::test::TempDir& staff, int token) {
  CopyShipped(staff.path() / "textures", "riverbed");
  auto options = Options(staff);
  options.config.token_textures[static_cast<std::size_t>(token - 1)] = "riverbed";
  return options;
}

bool Warned(const std::string& what) {
  for (const auto& line : sas::platform::DefaultLogger().Recent()) {
    if (line.level == sas::platform::LogLevel::kWarn && line.message.find(what) != std::string::npos)
      return true;
  }
  return false;
}

}  // namespace

TEST_CASE(
    "a staff texture named in kiosk.toml shows on its token, beside the shipped ones, and on the "
    "idle screen when it took the default texture's token",
          "[kiosk]") {
  sas::test::TempDir staff;
  sas::kiosk::KioskEngine engine(OptionsWithRiverbed(staff, 3));
  REQUIRE(engine.textures().size() == 4);
  CHECK(engine.textures()[0].key == "bubble_wrap");
  CHECK(engine.textures()[2].key == "riverbed");
  CHECK(engine.textures()[2].loaded.file.names.at("de") == "Flussbett");
  CHECK(engine.TokenForTexture(2) == 2);
  CHECK(engine.texture_failures().empty());
  // The default texture (wooden board) was token 3's: the idle screen shows what token 3 shows.
  CHECK(engine.default_texture() == 2);
}

TEST_CASE(
    "a staff texture that does not load is refused with a journal warning and its token shows "
    "the shipped texture of its place",
    "[kiosk]") {
  auto& log = sas::platform::DefaultLogger();
  log.SetEchoToStderr(false);
  struct Case {
    const char* name;
    void (*damage)(const fs::path& folder);
    const char* why;
  };
  const Case cases[] = {
      {"texture.toml unreadable",
       [](const fs::path& f) { std::ofstream(f / "texture.toml") << "name = \"x\n"; }, "syntax"},
      {"picture missing", [](const fs::path& f) { fs::remove(f / "picture.png"); }, "picture"},
      {"not calibrated",
       [](const fs::path& f) {
         std::ifstream in(f / "texture.toml");
         std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
         in.close();
         // Everything from [levels] to [probe] goes: the texture has no stroke table.
         const auto from = text.find("\n[levels]"), to = text.find("\n[probe]");
         std::ofstream(f / "texture.toml") << text.substr(0, from) + text.substr(to);
       },
       "[levels]"},
      {"folder without texture.toml", [](const fs::path& f) { fs::remove(f / "texture.toml"); },
       "texture.toml"},
  };
  for (const auto& c : cases) {
    INFO(c.name);
    sas::test::TempDir staff;
    const auto options = OptionsWithRiverbed(staff, 3);
    c.damage(staff.path() / "textures" / "riverbed");
    log.Clear();
    sas::kiosk::KioskEngine engine(options);
    REQUIRE(engine.textures().size() == 4);
    CHECK(engine.textures()[2].key == "wooden_board");
    CHECK(engine.TokenForTexture(2) == 2);
    CHECK(Warned("staff texture"));
    CHECK(Warned("token 3 shows the shipped wooden_board instead"));
    CHECK(Warned(c.why));
  }
}

TEST_CASE(
    "a staff texture named as the default texture shows with no token, and when it is refused "
    "the default is what its token shows instead",
    "[kiosk]") {
  sas::test::TempDir staff;
  auto options = OptionsWithRiverbed(staff, 2);
  options.config.default_texture = "riverbed";
  {
    sas::kiosk::KioskEngine engine(options);
    REQUIRE(engine.textures().size() == 4);
    REQUIRE(engine.textures()[1].key == "riverbed");
    CHECK(engine.default_texture() == 1);
    CHECK(engine.surface().texture == 1);
  }
  // Refused (its picture gone): token 2 shows the shipped broken glass, and so does the idle
  // screen, not the first texture.
  fs::remove(staff.path() / "textures" / "riverbed" / "picture.png");
  sas::platform::DefaultLogger().SetEchoToStderr(false);
  sas::kiosk::KioskEngine engine(options);
  REQUIRE(engine.textures().size() == 4);
  CHECK(engine.textures()[1].key == "broken_glass");
  CHECK(engine.default_texture() == 1);
}

TEST_CASE("a token naming no texture anywhere shows the shipped texture of its place", "[kiosk]") {
  sas::test::TempDir staff;
  const auto tokens = sas::kiosk::ResolveTokenTextures(
      {"bubble_wrap", "no_such_texture", "wooden_board", "cracked_ground"}, staff.path().string());
  REQUIRE(tokens.size() == 4);
  CHECK(tokens[1].path.empty());
  CHECK(fs::path(tokens[1].fallback).parent_path().filename() == "broken_glass");
  auto options = Options(staff);
  options.config.token_textures[1] = "no_such_texture";
  sas::kiosk::KioskEngine engine(options);
  REQUIRE(engine.textures().size() == 4);
  CHECK(engine.textures()[1].key == "broken_glass");
}
