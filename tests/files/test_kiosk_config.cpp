// Configuration validation: every problem names file, line and key; nothing half-applied.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "files/kiosk_config.h"
#include "levels/output_gains.h"
#include "sas/version.h"
#include "support/temp_dir.h"

using sas::kiosk::ConfigError;
using sas::kiosk::KioskConfig;
using sas::kiosk::LoadKioskConfig;
using sas::kiosk::ParseKioskConfig;

TEST_CASE("an empty configuration gives the built-in defaults", "[kiosk]") {
  const KioskConfig config = ParseKioskConfig("", "empty.toml");
  const KioskConfig defaults;
  CHECK(config.sample_rate_hz == defaults.sample_rate_hz);
  CHECK(config.buffer_frames == 128);
  CHECK(config.idle_timeout_s == 60.0);
}

TEST_CASE("values in a configuration file are applied", "[kiosk]") {
  sas::test::TempDir dir;
  const auto path = dir.Write("kiosk.toml",
                              "[audio]\noutput_device = \"hw:CARD=Speaker\"\nbuffer_frames = 256\n"
                              "[gains]\nsound_gain_db = 18.5\n[session]\nidle_timeout_s = 90\n");
  const KioskConfig config = LoadKioskConfig(path);
  CHECK(config.output_device == "hw:CARD=Speaker");
  CHECK(config.buffer_frames == 256);
  CHECK(config.sound_gain_db == 18.5);
  CHECK(config.idle_timeout_s == 90.0);
}

TEST_CASE("an unknown key is an error naming file, line and key", "[kiosk]") {
  const std::string text = "[audio]\nbuffer_frames = 128\n\n[gains]\nsound_gian_db = 3\n";
  CHECK_THROWS_WITH(ParseKioskConfig(text, "k.toml"), Catch::Contains("k.toml:5") &&
                                                          Catch::Contains("gains.sound_gian_db") &&
                                                          Catch::Contains("unknown key"));
}

TEST_CASE("wrong types, out-of-range values and syntax errors are reported with their line",
          "[kiosk]") {
  CHECK_THROWS_WITH(ParseKioskConfig("[audio]\nbuffer_frames = \"big\"\n", "k.toml"),
                    Catch::Contains("k.toml:2") && Catch::Contains("expected an integer"));
  CHECK_THROWS_WITH(ParseKioskConfig("[session]\nidle_timeout_s = 1.0\n", "k.toml"),
                    Catch::Contains("k.toml:2") && Catch::Contains("out of range"));
  CHECK_THROWS_WITH(ParseKioskConfig("[gains]\nsound_gain_db = nan\n", "k.toml"),
                    Catch::Contains("finite"));
  CHECK_THROWS_WITH(ParseKioskConfig("[gains\nsound_gain_db = 1\n", "k.toml"),
                    Catch::Contains("k.toml:1") && Catch::Contains("syntax error"));
  CHECK_THROWS_AS(LoadKioskConfig("/nonexistent/kiosk.toml"), ConfigError);
}

TEST_CASE("the shipped example configuration is valid and equals the built-in defaults",
          "[kiosk]") {
  const KioskConfig shipped = LoadKioskConfig(std::string(sas::kSourceDir) + "/install/kiosk.toml");
  const KioskConfig defaults;
  CHECK(shipped.output_device == defaults.output_device);
  CHECK(shipped.input_device == defaults.input_device);
  CHECK(shipped.sample_rate_hz == defaults.sample_rate_hz);
  CHECK(shipped.buffer_frames == defaults.buffer_frames);
  CHECK(shipped.sound_gain_db == defaults.sound_gain_db);
  CHECK(shipped.haptic_gain_db == defaults.haptic_gain_db);
  CHECK(shipped.idle_timeout_s == defaults.idle_timeout_s);
  CHECK(shipped.staff_panel_timeout_s == defaults.staff_panel_timeout_s);
  CHECK(shipped.language == defaults.language);
  CHECK(shipped.describe_after_rest_s == defaults.describe_after_rest_s);
  CHECK(shipped.attract_passive_stroke == defaults.attract_passive_stroke);
  CHECK(shipped.invitation_interval_s == defaults.invitation_interval_s);
  CHECK(shipped.visitor_languages == defaults.visitor_languages);
  CHECK(shipped.default_texture == defaults.default_texture);
  CHECK(shipped.reopen_backoff_max_s == defaults.reopen_backoff_max_s);
  CHECK(shipped.record_silence_rms_dbfs == defaults.record_silence_rms_dbfs);
  CHECK(shipped.switches_backend == defaults.switches_backend);
  CHECK(shipped.gpio_lines == defaults.gpio_lines);
  CHECK(shipped.mcp2221_path == defaults.mcp2221_path);
  CHECK(shipped.pen_seat == defaults.pen_seat);
  CHECK(shipped.sound_ceiling_db == defaults.sound_ceiling_db);
  CHECK(shipped.haptic_ceiling_db == defaults.haptic_ceiling_db);
  CHECK(shipped.low_vibration_db == defaults.low_vibration_db);
  CHECK(shipped.ambient_adaptive == defaults.ambient_adaptive);
  CHECK(shipped.ambient_min_db == defaults.ambient_min_db);
  CHECK(shipped.ambient_max_db == defaults.ambient_max_db);
  CHECK(shipped.ambient_per_db == defaults.ambient_per_db);
  CHECK(shipped.ambient_quiet_dbfs == defaults.ambient_quiet_dbfs);
  CHECK(shipped.ambient_rate_db_per_s == defaults.ambient_rate_db_per_s);
  CHECK(shipped.staff_chord == defaults.staff_chord);
  CHECK(shipped.staff_chord_hold_s == defaults.staff_chord_hold_s);
  CHECK(shipped.transducer_resonance_hz == defaults.transducer_resonance_hz);
  CHECK(shipped.transducer_q == defaults.transducer_q);
  CHECK(shipped.staff_dir == defaults.staff_dir);
  CHECK(shipped.metrics_file == defaults.metrics_file);
  CHECK(shipped.metrics_interval_s == defaults.metrics_interval_s);
  CHECK(shipped.box_name == defaults.box_name);
}

TEST_CASE("the staff folder is /etc/sketch-a-scratch by default, an absolute path or none",
          "[kiosk]") {
  CHECK(ParseKioskConfig("", "empty.toml").staff_dir == "/etc/sketch-a-scratch");
  CHECK(ParseKioskConfig("[paths]\nstaff_dir = \"/srv/museum\"\n", "k.toml").staff_dir ==
        "/srv/museum");
  CHECK(ParseKioskConfig("[paths]\nstaff_dir = \"\"\n", "k.toml").staff_dir.empty());
  // Relative to the unit's working directory (/) is nowhere anyone meant.
  CHECK_THROWS_WITH(ParseKioskConfig("[paths]\nstaff_dir = \"museum/cues\"\n", "k.toml"),
                    Catch::Contains("k.toml:2: paths.staff_dir: expected an absolute path"));
  CHECK_THROWS_WITH(ParseKioskConfig("[paths]\nstaff_dir = 3\n", "k.toml"),
                    Catch::Contains("paths.staff_dir: expected a string"));
}

TEST_CASE(
    "the fleet metrics file is a .prom name in the state folder by default, or none, its "
    "interval 1-300 s, the box name any text",
    "[kiosk]") {
  const KioskConfig defaults = ParseKioskConfig("", "empty.toml");
  CHECK(defaults.metrics_file == "sketch_a_scratch.prom");
  CHECK(defaults.metrics_interval_s == 5.0);
  CHECK(defaults.box_name.empty());
  const KioskConfig set = ParseKioskConfig(
      "[fleet]\nmetrics_file = \"/var/lib/other/box.prom\"\nmetrics_interval_s = 30\n"
      "box_name = \"Hall B\"\n",
      "k.toml");
  CHECK(set.metrics_file == "/var/lib/other/box.prom");
  CHECK(set.metrics_interval_s == 30.0);
  CHECK(set.box_name == "Hall B");
  CHECK(ParseKioskConfig("[fleet]\nmetrics_file = \"\"\n", "k.toml").metrics_file.empty());
  // node-exporter reads only *.prom: any other name would be written for nobody.
  CHECK_THROWS_WITH(
      ParseKioskConfig("[fleet]\nmetrics_file = \"box.txt\"\n", "k.toml"),
      Catch::Contains("k.toml:2: fleet.metrics_file: expected a file name ending in .prom"));
  CHECK_THROWS_WITH(ParseKioskConfig("[fleet]\nmetrics_file = \".prom\"\n", "k.toml"),
                    Catch::Contains("fleet.metrics_file"));
  CHECK_THROWS_WITH(ParseKioskConfig("[fleet]\nmetrics_interval_s = 0.5\n", "k.toml"),
                    Catch::Contains("fleet.metrics_interval_s: 0.5 is out of range"));
  CHECK_THROWS_WITH(ParseKioskConfig("[fleet]\nbox_name = 7\n", "k.toml"),
                    Catch::Contains("fleet.box_name: expected a string"));
}

TEST_CASE("the transducer profile: off by default, 0 or 20-1000 Hz, q 0.3-50", "[kiosk]") {
  const KioskConfig defaults = ParseKioskConfig("", "empty.toml");
  CHECK(defaults.transducer_resonance_hz == 0.0);  // a broadband transducer: nothing compensated
  CHECK(defaults.transducer_q == 1.0);

  const auto lra = ParseKioskConfig("[transducer]\nresonance_hz = 175\nq = 10.0\n", "k.toml");
  CHECK(lra.transducer_resonance_hz == 175.0);
  CHECK(lra.transducer_q == 10.0);
  const auto low = ParseKioskConfig("[transducer]\nresonance_hz = 20.0\nq = 0.3\n", "k.toml");
  CHECK(low.transducer_resonance_hz == 20.0);
  CHECK(low.transducer_q == 0.3);
  const auto high = ParseKioskConfig("[transducer]\nresonance_hz = 1000\nq = 50\n", "k.toml");
  CHECK(high.transducer_resonance_hz == 1000.0);
  CHECK(high.transducer_q == 50.0);
  // 0 switches the compensation off again, whatever q says.
  const auto off = ParseKioskConfig("[transducer]\nresonance_hz = 0\nq = 2\n", "k.toml");
  CHECK(off.transducer_resonance_hz == 0.0);
  CHECK(off.transducer_q == 2.0);

  // Between 0 and the range is not "off": a typo (17 for 170) must not pass silently.
  CHECK_THROWS_WITH(ParseKioskConfig("[transducer]\nq = 2\nresonance_hz = 17\n", "k.toml"),
                    Catch::Contains("k.toml:3: transducer.resonance_hz: 17 is out of range") &&
                        Catch::Contains("(or 0: off)"));
  CHECK_THROWS_WITH(ParseKioskConfig("[transducer]\nresonance_hz = 1200\n", "k.toml"),
                    Catch::Contains("k.toml:2") && Catch::Contains("out of range"));
  CHECK_THROWS_WITH(ParseKioskConfig("[transducer]\nresonance_hz = -60\n", "k.toml"),
                    Catch::Contains("transducer.resonance_hz") && Catch::Contains("out of range"));
  CHECK_THROWS_WITH(ParseKioskConfig("[transducer]\nresonance_hz = \"175 Hz\"\n", "k.toml"),
                    Catch::Contains("expected a number"));
  CHECK_THROWS_WITH(ParseKioskConfig("[transducer]\nresonance_hz = inf\n", "k.toml"),
                    Catch::Contains("finite"));
  CHECK_THROWS_WITH(ParseKioskConfig("[transducer]\nq = 0\n", "k.toml"),
                    Catch::Contains("k.toml:2: transducer.q: 0 is out of range"));
  CHECK_THROWS_WITH(ParseKioskConfig("[transducer]\nq = 51\n", "k.toml"),
                    Catch::Contains("transducer.q") && Catch::Contains("out of range"));
  CHECK_THROWS_WITH(ParseKioskConfig("[transducer]\nqms = 2\n", "k.toml"),
                    Catch::Contains("transducer.qms") && Catch::Contains("unknown key"));
}

TEST_CASE("vibration ceiling, low-vibration and ambient gain keys are validated", "[kiosk]") {
  const auto config = ParseKioskConfig(
      "[gains]\nsound_ceiling_db = -3\nhaptic_ceiling_db = -9.5\nlow_vibration_db = 18\n"
      "ambient_adaptive = true\n"
      "ambient_min_db = -3\nambient_max_db = 9\nambient_per_db = 0.75\n"
      "ambient_quiet_dbfs = -55\nambient_rate_db_per_s = 0.5\n",
      "k.toml");
  CHECK(config.sound_ceiling_db == -3.0);
  CHECK(config.haptic_ceiling_db == -9.5);
  CHECK(config.low_vibration_db == 18.0);
  CHECK(config.ambient_adaptive);
  CHECK(config.ambient_min_db == -3.0);
  CHECK(config.ambient_max_db == 9.0);
  CHECK(config.ambient_per_db == 0.75);
  CHECK(config.ambient_quiet_dbfs == -55.0);
  CHECK(config.ambient_rate_db_per_s == 0.5);
  // A ceiling above full scale would not be a ceiling.
  CHECK_THROWS_WITH(ParseKioskConfig("[gains]\nhaptic_ceiling_db = 3\n", "k.toml"),
                    Catch::Contains("k.toml:2") && Catch::Contains("gains.haptic_ceiling_db") &&
                        Catch::Contains("out of range"));
  CHECK_THROWS_WITH(ParseKioskConfig("[gains]\nsound_ceiling_db = 0.5\n", "k.toml"),
                    Catch::Contains("gains.sound_ceiling_db") && Catch::Contains("out of range"));
  CHECK_THROWS_WITH(ParseKioskConfig("[gains]\nlow_vibration_db = -6\n", "k.toml"),
                    Catch::Contains("out of range"));
  CHECK_THROWS_WITH(ParseKioskConfig("[gains]\nambient_adaptive = \"yes\"\n", "k.toml"),
                    Catch::Contains("true or false"));
  CHECK_THROWS_WITH(
      ParseKioskConfig("[gains]\nambient_min_db = 10\nambient_max_db = 4\n", "k.toml"),
      Catch::Contains("k.toml:3") && Catch::Contains("must not exceed"));
  CHECK_THROWS_WITH(ParseKioskConfig("[gains]\nambient_min_db = 20\n", "k.toml"),
                    Catch::Contains("must not exceed"));  // above the default maximum
}

TEST_CASE("kiosk output parameters add configuration, texture and ambient gains in dB", "[kiosk]") {
  sas::kiosk::KioskConfig config;
  config.sound_gain_db = 12.0;
  config.haptic_gain_db = 6.0;
  config.haptic_ceiling_db = -6.0;
  config.low_vibration_db = 20.0;
  sas::surface::TextureGains texture;
  texture.sound_gain_db = 3.0;
  texture.haptic_gain_db = -1.0;
  const auto p = sas::kiosk::KioskOutputParams(config, texture, 2.0);
  CHECK(p.sound_gain == Approx(std::pow(10.0, 17.0 / 20.0)));
  CHECK(p.haptic_gain == Approx(std::pow(10.0, 5.0 / 20.0)));
  CHECK(p.haptic_ceiling == Approx(0.501187).epsilon(1e-5));
  CHECK(p.low_vibration_gain == Approx(0.1));
  CHECK_FALSE(p.low_vibration);
  CHECK(sas::kiosk::KioskOutputParams(config, texture, 2.0, true).low_vibration);
  // The texture's trim lowers its sound only (after the per-stroke matching: stroke_gain.h).
  texture.sound_trim_db = -1.0;
  const auto trimmed = sas::kiosk::KioskOutputParams(config, texture, 2.0);
  CHECK(trimmed.sound_gain == Approx(std::pow(10.0, 16.0 / 20.0)));
  CHECK(trimmed.haptic_gain == Approx(p.haptic_gain));
  CHECK(trimmed.sound_level_cap == Approx(p.sound_level_cap));
}

TEST_CASE("switch, recording and pen keys are validated by type, choice and list length",
          "[kiosk]") {
  const auto config = ParseKioskConfig(
      "[switches]\nbackend = \"mcp2221\"\nactive_low = false\n"
      "gpio_lines = [\"TOKEN1\", \"TOKEN2\", \"TOKEN3\", \"TOKEN4\", \"\"]\n"
      "[pen]\ndevice = \"Wacom\"\n[recording]\nmax_duration_s = 4\n",
      "k.toml");
  CHECK(config.switches_backend == "mcp2221");
  CHECK_FALSE(config.switches_active_low);
  CHECK(config.gpio_lines == std::vector<std::string>{"TOKEN1", "TOKEN2", "TOKEN3", "TOKEN4", ""});
  CHECK(config.pen_device == "Wacom");
  CHECK(config.record_max_duration_s == 4.0);
  CHECK_THROWS_WITH(ParseKioskConfig("[switches]\nbackend = \"usb\"\n", "k.toml"),
                    Catch::Contains("k.toml:2") && Catch::Contains("keyboard"));
  CHECK_THROWS_WITH(ParseKioskConfig("[switches]\ngpio_lines = [\"17\"]\n", "k.toml"),
                    Catch::Contains("list of 5 strings"));
  CHECK_THROWS_WITH(ParseKioskConfig("[switches]\nactive_low = 1\n", "k.toml"),
                    Catch::Contains("true or false"));
  CHECK_THROWS_WITH(ParseKioskConfig("[recording]\nmax_duration_s = 60\n", "k.toml"),
                    Catch::Contains("out of range"));
}

TEST_CASE("a bad configuration falls back to the last good one, else to the defaults, and says so",
          "[kiosk]") {
  sas::test::TempDir dir;
  const auto path = dir.file("kiosk.toml");
  const auto last_good = dir.file("last-good.toml");
  using Source = sas::kiosk::ConfigLoadResult::Source;

  // No file and no backup yet: defaults, with the reason.
  auto result = sas::kiosk::LoadKioskConfigWithFallback(path, last_good);
  CHECK(result.source == Source::kDefaults);
  CHECK_THAT(result.problem, Catch::Contains("kiosk.toml") && Catch::Contains("defaults"));

  // A good file loads and is kept as the last good copy.
  dir.Write("kiosk.toml", "[gains]\nsound_gain_db = 20\n");
  result = sas::kiosk::LoadKioskConfigWithFallback(path, last_good);
  CHECK(result.source == Source::kFile);
  CHECK(result.problem.empty());
  CHECK(result.config.sound_gain_db == 20.0);

  // Staff break the file: the last good values stay in force and the error names the line.
  dir.Write("kiosk.toml", "[gains]\nsound_gain_db = 20\nsound_gain_db_typo = 3\n");
  result = sas::kiosk::LoadKioskConfigWithFallback(path, last_good);
  CHECK(result.source == Source::kLastGood);
  CHECK(result.config.sound_gain_db == 20.0);
  CHECK_THAT(result.problem, Catch::Contains("kiosk.toml:3") && Catch::Contains("last good"));
}

namespace {

std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Bytes this process has read through read() so far (/proc/self/io "rchar").
std::uint64_t BytesRead() {
  std::ifstream io("/proc/self/io");
  std::string key;
  std::uint64_t value = 0;
  while (io >> key >> value) {
    if (key == "rchar:") return value;
  }
  FAIL("no rchar in /proc/self/io");
  return 0;
}

}  // namespace

TEST_CASE(
    "a configuration file over 1 MiB is refused with the rejected file's fallback, and is not "
    "kept as the last good one, while one of exactly 1 MiB still loads",
    "[kiosk]") {
  using sas::kiosk::kMaxConfigFileBytes;
  using Source = sas::kiosk::ConfigLoadResult::Source;
  sas::test::TempDir dir;
  const auto path = dir.file("kiosk.toml");
  const auto last_good = dir.file("last-good.toml");
  dir.Write("kiosk.toml", "[gains]\nsound_gain_db = 20\n");
  REQUIRE(sas::kiosk::LoadKioskConfigWithFallback(path, last_good).source == Source::kFile);
  const std::string kept = ReadAll(last_good);
  REQUIRE_FALSE(kept.empty());

  // Valid TOML all through: a key, then comment lines up to the size wanted.
  const auto padded = [](std::uintmax_t bytes) {
    std::string text = "[gains]\nsound_gain_db = 6\n";
    while (text.size() + 66 <= bytes) text += "#" + std::string(62, '-') + "\n";
    text += "#" + std::string(bytes - text.size() - 2, '.') + "\n";
    return text;
  };
  REQUIRE(padded(kMaxConfigFileBytes + 1).size() == kMaxConfigFileBytes + 1);
  dir.Write("kiosk.toml", padded(kMaxConfigFileBytes + 1));
  auto result = sas::kiosk::LoadKioskConfigWithFallback(path, last_good);
  CHECK(result.source == Source::kLastGood);
  CHECK(result.config.sound_gain_db == 20.0);
  CHECK(result.problem == path + ": too large for a configuration file (" +
                              std::to_string(kMaxConfigFileBytes + 1) +
                              " bytes; the limit is 1024 KiB) (using the last good configuration)");
  CHECK(ReadAll(last_good) == kept);

  dir.Write("kiosk.toml", padded(kMaxConfigFileBytes));
  result = sas::kiosk::LoadKioskConfigWithFallback(path, last_good);
  CHECK(result.source == Source::kFile);
  CHECK(result.config.sound_gain_db == 6.0);
}

TEST_CASE(
    "a 100 MB configuration file is refused by its size with at most 1 MiB of it read, and falls "
    "back to the defaults when there is no last good one",
    "[kiosk]") {
  sas::test::TempDir dir;
  const auto path = dir.Write("kiosk.toml", "[gains]\nsound_gain_db = 6\n# ");
  constexpr std::uintmax_t kSize = 100ull * 1024 * 1024;
  std::filesystem::resize_file(path, kSize);  // sparse: no 100 MB written to the disk
  const std::uint64_t read_before = BytesRead();
  const auto result = sas::kiosk::LoadKioskConfigWithFallback(path, dir.file("last-good.toml"));
  const std::uint64_t read = BytesRead() - read_before;
  CHECK(result.source == sas::kiosk::ConfigLoadResult::Source::kDefaults);
  CHECK_THAT(result.problem, Catch::StartsWith(path + ": too large for a configuration file (" +
                                               std::to_string(kSize) + " bytes") &&
                                 Catch::EndsWith("(using the built-in defaults)"));
  CHECK(read <= sas::kiosk::kMaxConfigFileBytes);
  CHECK_FALSE(std::filesystem::exists(dir.file("last-good.toml")));
}

TEST_CASE("the staff chord needs two modifiers and a key, and its hold time is bounded",
          "[kiosk]") {
  const KioskConfig good =
      ParseKioskConfig("[staff]\nchord = \"Ctrl+Shift+F12\"\nchord_hold_s = 2.5\n", "good.toml");
  CHECK(good.staff_chord == "Ctrl+Shift+F12");
  CHECK(good.staff_chord_hold_s == 2.5);
  auto error_for = [](const std::string& text) {
    try {
      ParseKioskConfig(text, "staff.toml");
    } catch (const ConfigError& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  };
  // One modifier is a combination a visitor presses by accident.
  CHECK_THAT(error_for("[staff]\nchord = \"alt+f4\"\n"),
             Catch::Contains("staff.toml:2: staff.chord: expected at least two modifiers"));
  CHECK_THAT(error_for("[staff]\nchord = \"ctrl+meta+s\"\n"),
             Catch::Contains("unknown modifier 'meta'"));
  CHECK_THAT(error_for("[staff]\nchord = \"ctrl+alt+\"\n"),
             Catch::Contains("expected at least two modifiers and a key"));
  CHECK_THAT(error_for("[staff]\nchord_hold_s = 60\n"),
             Catch::Contains("staff.toml:2: staff.chord_hold_s: 60 is out of range"));
}

TEST_CASE("kiosk.toml: the default texture is a shipped one or one a token shows, a staff texture too, else an error at its line",
          "[kiosk]") {
  const KioskConfig staff = ParseKioskConfig(
      "[session]\ndefault_texture = \"river_pebbles\"\n[textures]\ntoken_2 = \"river_pebbles\"\n",
      "k.toml");
  CHECK(staff.default_texture == "river_pebbles");
  // A shipped name stays valid when a staff texture took its token (the idle screen then shows
  // that token's texture).
  CHECK(ParseKioskConfig("[session]\ndefault_texture = \"cracked_ground\"\n[textures]\ntoken_4 = "
                         "\"river_pebbles\"\n",
                         "k.toml")
            .default_texture == "cracked_ground");
  // A staff texture no token shows: the kiosk could not show it with no token.
  CHECK_THROWS_WITH(
      ParseKioskConfig("[textures]\ntoken_2 = \"river_pebbles\"\n\n[session]\ndefault_texture = "
                       "\"sea_stones\"\n",
                       "k.toml"),
      Catch::Contains("k.toml:5: session.default_texture: \"sea_stones\" is no texture the kiosk "
                      "shows"));
  CHECK_THROWS_WITH(ParseKioskConfig("[session]\n\ndefault_texture = \"wodden_board\"\n", "k.toml"),
                    Catch::Contains("k.toml:3: session.default_texture: \"wodden_board\" is no "
                                    "texture the kiosk shows"));
  CHECK_THROWS_WITH(ParseKioskConfig("[session]\ndefault_texture = \"../etc\"\n", "k.toml"),
                    Catch::Contains("k.toml:2: session.default_texture: expected a texture folder "
                                    "name"));
  CHECK_THROWS_WITH(ParseKioskConfig("[session]\ndefault_texture = 3\n", "k.toml"),
                    Catch::Contains("k.toml:2: session.default_texture:"));
}

TEST_CASE("kiosk.toml: the textures table names each token's texture, and a name that could leave the textures folder is an error at its line",
          "[kiosk]") {
  const KioskConfig config =
      ParseKioskConfig("[textures]\ntoken_3 = \"river_pebbles\"\n", "k.toml");
  CHECK(config.token_textures ==
        std::vector<std::string>{"bubble_wrap", "broken_glass", "river_pebbles", "cracked_ground"});
  CHECK_THROWS_WITH(ParseKioskConfig("[textures]\n\ntoken_2 = \"../etc\"\n", "k.toml"),
                    Catch::Contains("k.toml:3: textures.token_2:"));
  CHECK_THROWS_WITH(ParseKioskConfig("[textures]\ntoken_5 = \"wood\"\n", "k.toml"),
                    Catch::Contains("k.toml:2: textures.token_5: unknown key"));
  CHECK(LoadKioskConfig(std::string(sas::kSourceDir) + "/install/kiosk.toml").token_textures ==
        KioskConfig{}.token_textures);
}
