// Configuration validation: every problem names file, line and key; nothing half-applied.
#include <catch2/catch.hpp>

#include "kiosk/kiosk_config.h"
#include "kiosk/kiosk_control.h"
#include "platform/device_status.h"
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
  CHECK(shipped.default_texture == defaults.default_texture);
  CHECK(shipped.reopen_backoff_max_s == defaults.reopen_backoff_max_s);
  CHECK(shipped.record_silence_rms_dbfs == defaults.record_silence_rms_dbfs);
  CHECK(shipped.switches_backend == defaults.switches_backend);
  CHECK(shipped.gpio_lines == defaults.gpio_lines);
  CHECK(shipped.mcp2221_path == defaults.mcp2221_path);
  CHECK(shipped.pen_seat == defaults.pen_seat);
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

TEST_CASE(
    "a corrupt configuration at start is one journal line and a staff status naming file, "
    "line, key and the fallback in use",
    "[kiosk]") {
  sas::test::TempDir dir;
  const auto path = dir.Write("kiosk.toml", "[gains]\nsound_gain_db = 12\n");
  const auto last_good = dir.file("last-good.toml");
  sas::platform::Logger log;
  log.SetEchoToStderr(false);
  sas::platform::DeviceStatusBoard board(log);

  // Garbled by an editor: a syntax error on line 3. The copy from the good start is used.
  REQUIRE(sas::kiosk::LoadKioskConfigWithFallback(path, last_good).problem.empty());
  dir.Write("kiosk.toml", "[gains]\nsound_gain_db = 12\nhaptic_gain_db = = 3\n");
  const auto loaded = sas::kiosk::LoadKioskConfigWithFallback(path, last_good);
  sas::kiosk::ReportConfig(board, loaded);
  const auto status = board.Get("config");
  CHECK(status.state == sas::platform::DeviceState::kMissing);
  CHECK_THAT(status.message, Catch::StartsWith("rejected: " + path + ":3:") &&
                                 Catch::Contains("(using the last good configuration)"));
  REQUIRE(log.Recent().size() == 1);
  CHECK_THAT(log.Recent()[0].Text(),
             Catch::StartsWith("warn config: missing: rejected: " + path + ":3:"));
  CHECK_THAT(
      sas::kiosk::ConfigStatusLine(path, loaded),
      Catch::StartsWith("CONFIG: " + path + " BAD, USING THE LAST GOOD ONE: " + path + ":3:"));

  // No last good copy: the built-in defaults, and it says so, key included.
  sas::platform::DeviceStatusBoard fresh(log);
  dir.Write("kiosk.toml", "[session]\nidle_timeout_s = \"soon\"\n");
  const auto defaults = sas::kiosk::LoadKioskConfigWithFallback(path, dir.file("none.toml"));
  CHECK(defaults.source == sas::kiosk::ConfigLoadResult::Source::kDefaults);
  CHECK(defaults.config.idle_timeout_s == sas::kiosk::KioskConfig{}.idle_timeout_s);
  sas::kiosk::ReportConfig(fresh, defaults);
  CHECK_THAT(fresh.Get("config").message,
             Catch::StartsWith("rejected: " + path + ":2: session.idle_timeout_s: ") &&
                 Catch::EndsWith("(using the built-in defaults)"));
  CHECK_THAT(sas::kiosk::ConfigStatusLine(path, defaults),
             Catch::Contains(" NOT USED, DEFAULTS: " + path + ":2: session.idle_timeout_s: "));
}
