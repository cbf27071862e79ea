// The fault matrix: every way into the program, each row a bad input (or a fault) with the outcome
// we promise and the check that nothing was lost. Rows are grouped by input surface, one table per
// surface; each table is one test case that runs every row and names the row in any failure.
// The data files and the commands' arguments are in test_fault_matrix_inputs.cpp; devices lost and
// back and the signals in test_fault_matrix_devices.cpp (the real binary's half of the signals in
// tests/e2e/kiosk_faults_e2e.sh).
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "files/counters_file.h"
#include "files/kiosk_config.h"
#include "kiosk/kiosk_engine.h"
#include "fault_matrix_support.h"
#include "platform/log/log.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;
using sas::kiosk::KioskEngine;
using sas::kiosk::KioskEngineOptions;
using sas::kiosk::UsageCounters;

namespace {

using sas::test::ReadAll;

void WriteAll(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

// ---------------------------------------------------------------------------------------------
// Surface: the usage counters file (state folder). Before each row the kiosk saved a history;
// then the file is damaged, the kiosk starts, one visit with one stroke happens and it stops.
// Promise: no count is lower than before the damage, a damaged file is kept aside byte for byte
// (never overwritten), and one journal line says what happened.

const std::vector<std::string> kKeys = {"wooden_board"};

UsageCounters History() {
  UsageCounters counters;
  counters.sessions = 5000;
  counters.recordings = 40;
  counters.failed_recordings = 3;
  counters.voice_strokes = 7;
  counters.strokes_per_texture = {12000};
  return counters;
}

struct CountersRow {
  const char* name;
  std::function<void(const std::string& path)> damage;
  bool damaged;  // the file is not whole: expect it kept aside and one journal line
  std::uint64_t floor_sessions = 5000;  // the least "sessions" may be after the visit
};

std::vector<CountersRow> CountersRows() {
  const auto edit = [](std::function<std::string(std::string)> change) {
    return [change](const std::string& path) { WriteAll(path, change(ReadAll(path))); };
  };
  return {
      {"inline comment after a value", edit([](std::string t) {
         return t.replace(t.find("sessions = 5000"), 15, "sessions = 5000  # after the refit");
       }), false},
      {"CRLF line endings (edited on Windows)", edit([](std::string t) {
         std::string out;
         for (char c : t) out += c == '\n' ? std::string("\r\n") : std::string(1, c);
         return out;
       }), false},
      {"hand-written [strokes] table", edit([](std::string t) {
         t.erase(t.find("strokes.wooden_board"));
         return t + "[strokes]\nwooden_board = 12000\n";
       }), false},
      {"one unknown key", edit([](std::string t) { return t + "colour = 3\n"; }), true},
      {"a bad value", edit([](std::string t) {
         return t.replace(t.find("recordings = 40"), 15, "recordings = lots");
       }), true},
      {"a negative value", edit([](std::string t) {
         return t.replace(t.find("recordings = 40"), 15, "recordings = -40");
       }), true},
      {"a key given twice", edit([](std::string t) { return t + "sessions = 1\n"; }), true},
      {"truncated inside the last number", edit([](std::string t) {
         return t.substr(0, t.size() - 4);  // "strokes.wooden_board = 12000\n" -> "= 12"
       }), true},
      {"truncated to half", edit([](std::string t) { return t.substr(0, t.size() / 2); }), true},
      {"binary junk instead of text", edit([](std::string t) {
         for (std::size_t i = 0; i < t.size(); ++i) t[i] = static_cast<char>((i * 151 + 7) & 0xff);
         return t;
       }), true},
      {"binary junk appended", edit([](std::string t) {
         return t + std::string("\x00\xff\xfe garbage \x01", 14);
       }), true},
      {"NUL bytes inside a line", edit([](std::string t) {
         t[t.find("voice_strokes") + 3] = '\0';
         return t;
       }), true},
      {"empty file (zero bytes)", [](const std::string& path) { WriteAll(path, ""); }, true},
      {"the largest 64-bit count", edit([](std::string t) {
         return t.replace(t.find("sessions = 5000"), 15, "sessions = 18446744073709551615");
       }), true, 0x7fffffffffffffffULL},
      {"a directory where the file was", [](const std::string& path) {
         fs::remove(path);
         fs::create_directory(path);
       }, true},
      {"the file deleted (its backup remains)", [](const std::string& path) { fs::remove(path); },
       false},
  };
}

// The first entry of `dir` whose name starts with `prefix`, or "".
std::string FindEntry(const fs::path& dir, const std::string& prefix) {
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) == 0) return entry.path().string();
  }
  return "";
}

}  // namespace

TEST_CASE(
    "fault matrix: counters file - no damage lowers a count and the damaged file is kept aside",
    "[kiosk][faults]") {
  auto& log = sas::platform::DefaultLogger();
  log.SetEchoToStderr(false);
  int rows = 0;
  for (const auto& row : CountersRows()) {
    ++rows;
    INFO("row: counters file, " << row.name);
    sas::test::TempDir dir;
    const std::string path = dir.file("counters.toml");
    std::string error;
    const UsageCounters before = History();
    REQUIRE(sas::kiosk::SaveCounters(path, before, kKeys, &error));
    row.damage(path);
    const bool was_directory = fs::is_directory(path);
    const std::string damaged_bytes = was_directory ? "" : ReadAll(path);

    log.Clear();
    KioskEngineOptions options;
    options.virtual_clock = true;
    options.cues_dir = "/nonexistent";
    options.texture_paths = {sas::test::TexturePath("wooden_board")};
    options.counters_path = path;
    {
      KioskEngine engine(options);
      sas::test::OneStroke(engine);
      engine.SaveCounters(&error);
    }
    int warnings = 0;
    for (const auto& line : log.Recent()) {
      if (line.component == "counters" && line.level >= sas::platform::LogLevel::kWarn) ++warnings;
    }

    // Nothing lost: read back what the kiosk left (its file, else the copy it kept aside).
    UsageCounters after;
    sas::kiosk::LoadCounters(path, kKeys, &after, &error);
    CHECK(after.sessions >= row.floor_sessions);
    CHECK(after.sessions > 0);
    if (row.floor_sessions == before.sessions) {
      CHECK(after.sessions >= before.sessions + 1);
      CHECK(after.recordings >= before.recordings);
      CHECK(after.failed_recordings >= before.failed_recordings);
      CHECK(after.voice_strokes >= before.voice_strokes);
      CHECK(after.strokes_per_texture.at(0) >= before.strokes_per_texture.at(0) + 1);
    }
    if (row.damaged) {
      // Kept aside byte for byte and said once in the journal.
      const std::string aside = FindEntry(dir.path(), "counters.toml.damaged-");
      CHECK(aside != "");
      if (!aside.empty() && !was_directory) CHECK(ReadAll(aside) == damaged_bytes);
      CHECK(warnings == 1);
    }
  }
  CHECK(rows == 16);
}

// ---------------------------------------------------------------------------------------------
// Surface: the configuration file (--config, /etc/sketch-a-scratch/kiosk.toml). Promise: a bad
// file is refused with a message naming the file (and line and key where there is one), the
// kiosk starts on the last good copy, and that copy is never replaced by the bad file.

namespace {

struct ConfigRow {
  const char* name;
  std::function<std::string(const sas::test::TempDir&)> make;  // returns the --config path
  const char* message;                                          // expected in the problem
};

std::vector<ConfigRow> ConfigRows() {
  const auto text = [](std::string contents) {
    return [contents](const sas::test::TempDir& dir) { return dir.Write("kiosk.toml", contents); };
  };
  return {
      {"a directory given as the file",
       [](const sas::test::TempDir& dir) {
         fs::create_directory(dir.file("conf.d"));
         return dir.file("conf.d");
       },
       "is a directory"},
      {"a missing file", [](const sas::test::TempDir& dir) { return dir.file("none.toml"); },
       "cannot open"},
      {"an unknown default_texture", text("[session]\ndefault_texture = \"wodden_board\"\n"),
       "default_texture"},
      {"a syntax error", text("[audio\nsample_rate_hz = 48000\n"), "syntax error"},
      {"an unknown table", text("[colours]\nred = 1\n"), "unknown key"},
      {"an unknown key", text("[audio]\nsample_rat_hz = 48000\n"), "unknown key"},
      {"a top-level key", text("sample_rate_hz = 48000\n"), "top-level"},
      {"a string for a number", text("[audio]\nsample_rate_hz = \"fast\"\n"), "integer"},
      {"an integer out of range", text("[audio]\nbuffer_frames = 1\n"), "out of range"},
      {"a real out of range", text("[gains]\nsound_gain_db = 90.0\n"), "out of range"},
      {"nan", text("[gains]\nsound_gain_db = nan\n"), "finite"},
      {"inf", text("[gains]\nhaptic_gain_db = inf\n"), "finite"},
      {"an unknown switches backend", text("[switches]\nbackend = \"serial\"\n"), "not one of"},
      {"four GPIO lines instead of five", text("[switches]\ngpio_lines = [\"1\",\"2\",\"3\",\"4\"]\n"),
       "list of 5"},
      {"ambient minimum above maximum",
       text("[gains]\nambient_min_db = 20.0\nambient_max_db = 10.0\n"), "must not exceed"},
      {"binary junk", text(std::string("\x7f\x45\x4c\x46\x02\x01\x01\x00\xff\xfe", 10)), ""},
      {"an empty key name", text("[audio]\n\"\" = 1\n"), "unknown key"},
      {"2 MiB of valid TOML (comments)",
       text("[audio]\nbuffer_frames = 256\n" + std::string(2 << 20, '#') + "\n"),
       "too large for a configuration file"},
  };
}

}  // namespace

TEST_CASE("fault matrix: configuration - a bad file is refused and the last good copy kept",
          "[kiosk][faults]") {
  int rows = 0;
  for (const auto& row : ConfigRows()) {
    ++rows;
    INFO("row: configuration, " << row.name);
    sas::test::TempDir dir;
    const std::string last_good =
        dir.Write("last-good.toml", "[session]\ndefault_texture = \"bubble_wrap\"\n");
    const std::string before = ReadAll(last_good);
    const std::string path = row.make(dir);
    const auto result = sas::kiosk::LoadKioskConfigWithFallback(path, last_good);
    CHECK(result.source == sas::kiosk::ConfigLoadResult::Source::kLastGood);
    CHECK(result.config.default_texture == "bubble_wrap");
    CHECK_THAT(result.problem, Catch::Contains(path) && Catch::Contains(row.message));
    CHECK(ReadAll(last_good) == before);
  }
  CHECK(rows == 18);
}
