// One string table per language (textures/strings/<code>.toml): every shipped table has every
// cue and screen text, a broken table is refused naming file and key, and the kiosk engine speaks
// the configured language, steps through the visitor's languages and returns to the configured one
// at the idle reset.
#include <toml++/toml.h>

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "files/strings.h"
#include "kiosk/kiosk_engine.h"
#include "sas/version.h"
#include "support/temp_dir.h"

using sas::kiosk::CueEvent;
using sas::kiosk::KioskEngine;
using sas::kiosk::LoadLanguageTable;

namespace {

const std::string kStringsDir = std::string(sas::kSourceDir) + "/textures/strings";
const std::vector<std::string> kTextures = {"bubble_wrap", "broken_glass", "wooden_board",
                                            "cracked_ground"};

// The table's own text for `table.key`, read straight from the file (not through the kiosk).
std::string FromFile(const std::string& code, const std::string& table, const std::string& key) {
  const toml::table root = toml::parse_file(kStringsDir + "/" + code + ".toml");
  return root[table][key].value_or(std::string());
}

}  // namespace

TEST_CASE("every shipped language table has every cue and screen text and the textures' names",
          "[kiosk]") {
  REQUIRE(sas::kiosk::KioskLanguages() == std::vector<std::string>{"en", "de", "fr", "it", "es"});
  for (const auto& code : sas::kiosk::KioskLanguages()) {
    INFO(code);
    const auto table = LoadLanguageTable(kStringsDir, code);
    CHECK(table.cues.size() == sas::kiosk::CueKeys().size());
    CHECK(table.screen.size() == sas::kiosk::ScreenKeys().size());
    CHECK_FALSE(table.language_name.empty());
    for (const auto& key : sas::kiosk::ScreenKeys()) CHECK_FALSE(table.Screen(key).empty());
    // The invitation's parts: each there, and each in the spoken invitation (what a blind
    // visitor hears names what the screen shows).
    REQUIRE(sas::kiosk::InvitationParts() ==
            std::vector<std::string>{"scratch", "rest", "roll", "token", "record", "language"});
    for (const auto& part : sas::kiosk::InvitationParts()) {
      INFO(part);
      const std::string text = FromFile(code, "invitation", part);
      CHECK_FALSE(text.empty());
      CHECK(table.Invitation(part) == text);
      CHECK(table.cues.at("invitation").find(text) != std::string::npos);
    }
    // English names and descriptions are the textures' own files; every other language has its
    // own.
    for (const auto& texture : kTextures) {
      CHECK(table.textures.count(texture + "_name") == (code == "en" ? 0u : 1u));
      CHECK(table.textures.count(texture + "_description") == (code == "en" ? 0u : 1u));
    }
  }
  // Two languages do not share a sentence by mistake (a table copied and left untranslated).
  const auto en = LoadLanguageTable(kStringsDir, "en");
  for (const auto& code : {"de", "fr", "it", "es"}) {
    const auto other = LoadLanguageTable(kStringsDir, code);
    CHECK(other.cues.at("invitation") != en.cues.at("invitation"));
    for (const auto& part : sas::kiosk::InvitationParts()) {
      CHECK(other.Invitation(part) != en.Invitation(part));
    }
  }
}

TEST_CASE("a language table with a missing or unknown key is refused naming the file and key",
          "[kiosk]") {
  sas::test::TempDir dir;
  std::string text = "[voice]\nlanguage_name = \"X\"\nespeak_voice = \"en\"\n[cues]\n";
  for (const auto& key : sas::kiosk::CueKeys()) {
    if (key != "invitation") text += key + " = \"a\"\n";  // made of [invitation]
  }
  text += "[invitation]\n";
  for (const auto& key : sas::kiosk::InvitationParts()) text += key + " = \"p\"\n";
  text += "[screen]\n";
  for (const auto& key : sas::kiosk::ScreenKeys()) text += key + " = \"b\"\n";
  dir.Write("xx.toml", text);
  CHECK_NOTHROW(LoadLanguageTable(dir.path().string(), "xx"));
  dir.Write("yy.toml", text + "attract_titel = \"c\"\n");
  CHECK_THROWS_WITH(LoadLanguageTable(dir.path().string(), "yy"),
                    Catch::Contains("yy.toml:") && Catch::Contains("screen.attract_titel") &&
                        Catch::Contains("unknown key"));
  std::string missing = text;
  missing.erase(missing.find("count_2 = \"a\"\n"), 14);
  dir.Write("zz.toml", missing);
  CHECK_THROWS_WITH(LoadLanguageTable(dir.path().string(), "zz"),
                    Catch::Contains("cues.count_2: missing"));
  std::string no_roll = text;
  no_roll.erase(no_roll.find("roll = \"p\"\n"), 11);
  dir.Write("ww.toml", no_roll);
  CHECK_THROWS_WITH(LoadLanguageTable(dir.path().string(), "ww"),
                    Catch::Contains("invitation.roll: missing"));
}

#if defined(SAS_CUES_DIR)
TEST_CASE("the language key steps through the visitor's languages, each saying its own name",
          "[kiosk]") {
  sas::kiosk::KioskEngineOptions options;
  options.virtual_clock = true;
  options.cues_dir = SAS_CUES_DIR;
  options.config.language = "de";
  options.config.visitor_languages = {"de", "fr", "en"};
  options.config.idle_timeout_s = 5.0;
  KioskEngine engine(options);
  std::vector<CueEvent> heard;
  engine.SetCueObserver([&](const CueEvent& cue) { heard.push_back(cue); });
  CHECK(engine.language() == "de");
  CHECK(engine.strings().Invitation("scratch") == FromFile("de", "invitation", "scratch"));
  engine.OnToken(1'000'000'000, 0);
  engine.Tick(1'000'000'000);
  REQUIRE(heard.size() == 1);
  CHECK(heard[0].language == "de");
  CHECK(heard[0].key == "bubble_wrap_name");
  CHECK(heard[0].text == FromFile("de", "textures", "bubble_wrap_name"));
  for (const char* expected : {"fr", "en", "de", "fr"}) {
    REQUIRE(engine.NextLanguage(2'000'000'000));
    CHECK(engine.language() == expected);
    CHECK(heard.back().key == "language");
    CHECK(heard.back().language == expected);
    CHECK(heard.back().text == FromFile(expected, "cues", "language"));
  }
  engine.OnToken(2'500'000'000, 1);
  engine.Tick(2'500'000'000);
  CHECK(heard.back().text == FromFile("fr", "textures", "broken_glass_name"));
  engine.Tick(10'000'000'000);  // the idle reset: the next visitor hears the configured language
  CHECK(engine.session().mode() == sas::kiosk::SessionMode::kAttract);
  CHECK(engine.language() == "de");
  // On the attract screen the key takes the language shown (the configured one here: no tick
  // has moved the attract cycle on), then steps on. English names come from the texture's own
  // file.
  REQUIRE(engine.NextLanguage(11'000'000'000));
  CHECK(engine.language() == "de");
  engine.NextLanguage(11'000'000'000);
  engine.NextLanguage(11'000'000'000);
  REQUIRE(engine.language() == "en");
  CHECK(engine.TextureName(2) == "wooden board");
}

TEST_CASE("without visitor languages the language key changes nothing", "[kiosk]") {
  sas::kiosk::KioskEngineOptions options;
  options.virtual_clock = true;
  options.cues_dir = SAS_CUES_DIR;
  options.config.language = "it";
  options.config.visitor_languages = {};
  KioskEngine engine(options);
  CHECK_FALSE(engine.NextLanguage(1'000'000'000));
  CHECK(engine.language() == "it");
  CHECK(engine.session().mode() == sas::kiosk::SessionMode::kAttract);
}
#endif
