// Texture files: the four committed ones load; every kind of mistake is reported with
// file:line:col and the key.
#include <catch2/catch.hpp>
#include <filesystem>

#include "surface/image_loader.h"
#include "surface/texture_file.h"

using sas::surface::LoadError;
using sas::surface::ParseTextureFile;

namespace {

const std::string kValid = R"(name = "test"
description = "A test texture."
material = "wood"
picture = "picture.png"
height_map = "height.png"
height_scale_mm = 1.0
relief_mm = 0.2

[gains]
sound_gain_db = 0.0
haptic_gain_db = -3.0

[probe]
width_mm = 0.5
penetration_mm = 0.01
style = "rub"
)";

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("the four kiosk texture files load with their materials and files in place",
          "[surface]") {
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"bubble_wrap", "bubble_wrap"},
      {"broken_glass", "glass"},
      {"wooden_board", "wood"},
      {"cracked_ground", "dry_soil"}};
  for (const auto& [folder, material] : expected) {
    const auto t = sas::surface::LoadTextureFile(std::string(SAS_TEXTURES_DIR) + "/" + folder +
                                                 "/texture.toml");
    CHECK(t.material == material);
    CHECK(std::filesystem::is_regular_file(t.picture_path));
    CHECK(std::filesystem::is_regular_file(t.height_map_path));
    CHECK(std::filesystem::is_regular_file(std::string(SAS_TEXTURES_DIR) + "/materials/" +
                                           material + ".toml"));
    CHECK(t.bubbles.has_value() == (material == "bubble_wrap"));
    CHECK(t.description.back() == '.');
  }
}

TEST_CASE("a valid texture file parses into its values", "[surface]") {
  const auto t = ParseTextureFile(kValid, "/x/texture.toml");
  CHECK(t.name == "test");
  CHECK(t.picture_path == "/x/picture.png");
  CHECK(t.gains.haptic_gain_db == -3.0);
  CHECK(t.gains.sound_trim_db == 0.0);  // optional: absent is no trim
  CHECK(t.gains.haptic_trim_db == 0.0);
  CHECK(ParseTextureFile(Replace(kValid, "haptic_gain_db = -3.0\n",
                                 "haptic_gain_db = -3.0\nsound_trim_db = -1.5\n"),
                         "/x/texture.toml")
            .gains.sound_trim_db == -1.5);
  CHECK(ParseTextureFile(Replace(kValid, "haptic_gain_db = -3.0\n",
                                 "haptic_gain_db = -3.0\nhaptic_trim_db = 2.25\n"),
                         "/x/texture.toml")
            .gains.haptic_trim_db == 2.25);
  CHECK(t.probe.style == sas::synth::ProbeStyle::kRub);
  CHECK(t.probe.width_mm == 0.5);
  CHECK_FALSE(t.bubbles.has_value());
}

TEST_CASE("texture file mistakes are reported with file, line and key", "[surface]") {
  // Unknown key, at the top level and inside a table.
  CHECK_THROWS_WITH(
      ParseTextureFile("colour = \"red\"\n" + kValid, "t.toml"),
      Catch::Contains("t.toml:1:1") && Catch::Contains("colour") && Catch::Contains("unknown key"));
  CHECK_THROWS_WITH(ParseTextureFile(kValid + "colour = \"red\"\n", "t.toml"),  // lands in [probe]
                    Catch::Contains("t.toml:17") && Catch::Contains("probe.colour"));
  CHECK_THROWS_WITH(
      ParseTextureFile(Replace(kValid, "style = \"rub\"", "style = \"rub\"\nangle = 3"), "t.toml"),
      Catch::Contains("t.toml:17") && Catch::Contains("probe.angle"));
  // Missing key.
  CHECK_THROWS_WITH(ParseTextureFile(Replace(kValid, "haptic_gain_db = -3.0\n", ""), "t.toml"),
                    Catch::Contains("gains.haptic_gain_db") && Catch::Contains("missing"));
  // Out of range, wrong type, bad enumerations.
  CHECK_THROWS_WITH(ParseTextureFile(Replace(kValid, "haptic_gain_db = -3.0\n",
                                             "haptic_gain_db = -3.0\nsound_trim_db = 40\n"),
                                     "t.toml"),
                    Catch::Contains("t.toml:12") && Catch::Contains("gains.sound_trim_db") &&
                        Catch::Contains("outside"));
  CHECK_THROWS_WITH(ParseTextureFile(Replace(kValid, "haptic_gain_db = -3.0\n",
                                             "haptic_gain_db = -3.0\nhaptic_trim_db = -13\n"),
                                     "t.toml"),
                    Catch::Contains("t.toml:12") && Catch::Contains("gains.haptic_trim_db") &&
                        Catch::Contains("outside"));
  CHECK_THROWS_WITH(ParseTextureFile(Replace(kValid, "width_mm = 0.5", "width_mm = 500"), "t.toml"),
                    Catch::Contains("t.toml:14") && Catch::Contains("probe.width_mm") &&
                        Catch::Contains("outside"));
  CHECK_THROWS_WITH(
      ParseTextureFile(Replace(kValid, "relief_mm = 0.2", "relief_mm = \"high\""), "t.toml"),
      Catch::Contains("t.toml:7") && Catch::Contains("must be a number"));
  // Any material file's name (a curator's texture may bring its own); never a path.
  CHECK(ParseTextureFile(Replace(kValid, "\"wood\"", "\"cheese\""), "t.toml").material ==
        "cheese");
  CHECK_THROWS_WITH(ParseTextureFile(Replace(kValid, "\"wood\"", "\"../wood\""), "t.toml"),
                    Catch::Contains("t.toml:3") && Catch::Contains("no material name"));
  // A curator's texture: names and descriptions per language, a relief from brightness.
  {
    const auto t = ParseTextureFile(
        Replace(kValid, "relief_mm = 0.2", "relief_mm = 0.2\nrelief_from = \"brightness\"") +
            "[names]\nde = \"Test\"\n[descriptions]\nde = \"Ein Test.\"\n",
        "t.toml");
    CHECK(t.relief_from_brightness);
    CHECK(t.names.at("de") == "Test");
    CHECK(t.descriptions.at("de") == "Ein Test.");
  }
  CHECK_THROWS_WITH(ParseTextureFile(kValid + "[names]\nDeutsch = \"Test\"\n", "t.toml"),
                    Catch::Contains("names.Deutsch") && Catch::Contains("language code"));
  CHECK_THROWS_WITH(ParseTextureFile(kValid + "[descriptions]\nde = \"Eins. Zwei.\"\n", "t.toml"),
                    Catch::Contains("descriptions.de") && Catch::Contains("one sentence"));
  CHECK_THROWS_WITH(
      ParseTextureFile(Replace(kValid, "relief_mm = 0.2", "relief_mm = 0.2\nrelief_from = \"x\""),
                       "t.toml"),
      Catch::Contains("t.toml:8") && Catch::Contains("relief_from"));
  CHECK_THROWS_WITH(ParseTextureFile(Replace(kValid, "\"rub\"", "\"poke\""), "t.toml"),
                    Catch::Contains("probe.style"));
  // The spoken description is exactly one sentence.
  CHECK_THROWS_WITH(
      ParseTextureFile(Replace(kValid, "A test texture.", "Two. Sentences."), "t.toml"),
      Catch::Contains("t.toml:2") && Catch::Contains("one sentence"));
  // Bubbles belong to bubble wrap only, and bubble wrap needs them.
  CHECK_THROWS_WITH(ParseTextureFile(kValid + "[bubbles]\npop_force_n = 1.0\n", "t.toml"),
                    Catch::Contains("bubbles"));
  CHECK_THROWS_WITH(ParseTextureFile(Replace(kValid, "\"wood\"", "\"bubble_wrap\""), "t.toml"),
                    Catch::Contains("bubbles") && Catch::Contains("missing"));
  // Syntax errors carry the parser's position.
  CHECK_THROWS_WITH(ParseTextureFile("name = \"x\nmaterial = 3\n", "s.toml"),
                    Catch::Contains("s.toml:1"));
  CHECK_THROWS_AS(sas::surface::LoadTextureFile("/nonexistent/texture.toml"), LoadError);
}

TEST_CASE(
    "a [levels] table parses in style, width, speed, pressure order and its mistakes are reported",
    "[surface]") {
  const std::string levels = R"(
[levels]
scrape_widths_mm = [0.3, 1.9]
rub_widths_mm = [2.1, 6.0]
speeds_mm_s = [40.0, 350.0]
pressures = [0.3, 0.6]
scrape_sound_lufs = [-40.0, -38.0, -30.0, -28.0, -45.0, -43.0, -35.0, -33.0]
scrape_haptic_rms_db = [-41.0, -39.0, -31.0, -29.0, -46.0, -44.0, -36.0, -34.0]
rub_sound_lufs = [-50.0, -48.0, -35.0, -33.0, -55.0, -53.0, -40.0, -38.0]
rub_haptic_rms_db = [-51.0, -49.0, -36.0, -34.0, -56.0, -54.0, -41.0, -39.0]
)";
  const auto t = ParseTextureFile(Replace(kValid, "\n[probe]", levels + "\n[probe]"), "t.toml");
  REQUIRE(t.levels);
  const auto& l = *t.levels;
  CHECK(l.scrape_widths_mm == std::vector<double>{0.3, 1.9});
  CHECK(l.rub_widths_mm == std::vector<double>{2.1, 6.0});
  CHECK(l.widths_mm(1) == l.rub_widths_mm);
  CHECK(l.speeds_mm_s == std::vector<double>{40.0, 350.0});
  CHECK(l.pressures == std::vector<double>{0.3, 0.6});
  CHECK(l.sound_lufs[l.Index(0, 0, 1, 0)] == -30.0);  // scrape, 0.3 mm, 350 mm/s, pressure 0.3
  CHECK(l.sound_lufs[l.Index(0, 1, 1, 1)] == -33.0);  // scrape, 1.9 mm, 350 mm/s, pressure 0.6
  CHECK(l.sound_lufs[l.Index(1, 0, 0, 1)] == -48.0);  // rub, 2.1 mm, 40 mm/s, pressure 0.6
  CHECK(l.haptic_rms_db[l.Index(1, 1, 1, 1)] == -39.0);
  CHECK_FALSE(ParseTextureFile(kValid, "t.toml").levels);  // optional
  const auto fails = [&](const std::string& from, const std::string& to, const std::string& what) {
    const std::string text = Replace(kValid, "\n[probe]", Replace(levels, from, to) + "\n[probe]");
    CHECK_THROWS_WITH(ParseTextureFile(text, "t.toml"), Catch::Contains(what));
  };
  fails("[-40.0, -38.0, -30.0, -28.0, -45.0", "[-40.0, -38.0, -30.0, -45.0", "must hold 8 numbers");
  fails("[40.0, 350.0]", "[350.0, 40.0]", "levels.speeds_mm_s: must be strictly increasing");
  fails("[2.1, 6.0]", "[6.0, 2.1]", "levels.rub_widths_mm: must be strictly increasing");
  fails("[2.1, 6.0]", "[2.1, 4.0, 6.0]", "as many as scrape_widths_mm");
  fails("[0.3, 0.6]", "[0.3, 1.6]", "levels.pressures: value");
  fails("rub_haptic_rms_db", "rub_vibration", "levels.rub_vibration: unknown key");
  fails("scrape_widths_mm = [0.3, 1.9]\n", "", "missing required key");
  CHECK(l.styles() == 2);  // no roll rows: a roll reads the scrape's

  // Roll rows: all three keys or none, any number of widths.
  const std::string roll = R"(roll_widths_mm = [0.3, 6.0]
roll_sound_lufs = [-60.0, -58.0, -50.0, -48.0, -65.0, -63.0, -55.0, -53.0]
roll_haptic_rms_db = [-61.0, -59.0, -51.0, -49.0, -66.0, -64.0, -56.0, -54.0]
)";
  const auto with_roll =
      ParseTextureFile(Replace(kValid, "\n[probe]", levels + roll + "\n[probe]"), "t.toml");
  REQUIRE(with_roll.levels);
  const auto& r = *with_roll.levels;
  CHECK(r.styles() == 3);
  CHECK(r.widths_mm(2) == std::vector<double>{0.3, 6.0});
  CHECK(r.sound_lufs[r.Index(2, 1, 0, 1)] == -63.0);  // roll, 6 mm, 40 mm/s, pressure 0.6
  CHECK(r.haptic_rms_db[r.Index(2, 0, 1, 0)] == -51.0);
  CHECK(r.sound_lufs[r.Index(1, 0, 0, 1)] == -48.0);  // the rub rows are where they were
  CHECK_THROWS_WITH(
      ParseTextureFile(
          Replace(kValid, "\n[probe]", levels + "roll_widths_mm = [0.3, 6.0]\n" + "\n[probe]"),
          "t.toml"),
      Catch::Contains("levels.roll_sound_lufs"));
}
