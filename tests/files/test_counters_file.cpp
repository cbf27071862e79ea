// Usage counters survive a round trip, damage is reported, and a full disk never loses the last
// good file (the write is atomic).
#include <sys/resource.h>
#include <catch2/catch.hpp>
#include <csignal>
#include <fstream>
#include <sstream>

#include "files/atomic_file.h"
#include "files/counters_file.h"
#include "support/file_size_limit.h"
#include "support/temp_dir.h"

using sas::kiosk::UsageCounters;

namespace {

const std::vector<std::string> kNames = {"bubble_wrap", "broken_glass", "wooden_board",
                                         "cracked_ground"};

std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

UsageCounters Sample() {
  UsageCounters counters;
  counters.strokes_per_texture = {12, 0, 7, 123456789012ULL};
  counters.voice_strokes = 4;
  counters.recordings = 3;
  counters.failed_recordings = 1;
  counters.sessions = 9;
  return counters;
}

using sas::test::FileSizeLimit;

}  // namespace

TEST_CASE("usage counters survive a save and load round trip", "[kiosk]") {
  sas::test::TempDir dir;
  const auto path = dir.file("counters.toml");
  std::string error;
  REQUIRE(sas::kiosk::SaveCounters(path, Sample(), kNames, &error));
  UsageCounters loaded;
  REQUIRE(sas::kiosk::LoadCounters(path, kNames, &loaded, &error));
  CHECK(loaded == Sample());
}

TEST_CASE("a missing counters file starts from zero and a damaged one is reported and salvaged",
          "[kiosk]") {
  sas::test::TempDir dir;
  UsageCounters loaded;
  std::string error;
  REQUIRE(sas::kiosk::LoadCounters(dir.file("none.toml"), kNames, &loaded, &error));
  CHECK(loaded.sessions == 0);
  CHECK(loaded.strokes_per_texture.size() == 4);
  const auto damaged = dir.Write("bad.toml", "sessions = 3\nrecordings = lots\n");
  CHECK_FALSE(sas::kiosk::LoadCounters(damaged, kNames, &loaded, &error));
  CHECK_THAT(error, Catch::Contains("bad.toml:2"));
  CHECK(loaded.sessions == 3);  // the intact line is kept
  CHECK(loaded.recordings == 0);
}

TEST_CASE("counters are salvaged line by line and each fault is named with its line", "[kiosk]") {
  const auto salvage = sas::kiosk::SalvageCounters(
      "sessions = 12\nrecordings = lots\ncolour = 3\nvoice_strokes = 18446744073709551616\n"
      "strokes.bubble_wrap = 9\nstrokes.gone_texture = 4\nfailed_recordings = 7",
      kNames, "c.toml");
  CHECK(salvage.counters.sessions == 12);
  CHECK(salvage.counters.strokes_per_texture.at(0) == 9);
  CHECK(salvage.counters.voice_strokes == sas::kiosk::kMaxUsageCount);  // clamped, not wrapped
  CHECK(salvage.counters.failed_recordings == 0);  // last line cut off: not trusted
  CHECK_FALSE(salvage.found.at(1));                // recordings
  REQUIRE(salvage.problems.size() == 5);
  CHECK_THAT(salvage.problems[1], Catch::Contains("c.toml:2") && Catch::Contains("recordings"));
  CHECK_THAT(salvage.problems[2], Catch::Contains("c.toml:3") && Catch::Contains("unknown key"));
}

TEST_CASE("a count at the largest value stays there instead of wrapping to zero", "[kiosk]") {
  std::uint64_t count = sas::kiosk::kMaxUsageCount - 1;
  sas::kiosk::CountOne(count);
  CHECK(count == sas::kiosk::kMaxUsageCount);
  sas::kiosk::CountOne(count);
  CHECK(count == sas::kiosk::kMaxUsageCount);
}

TEST_CASE("a full disk while saving leaves the previous counters file intact", "[kiosk]") {
  sas::test::TempDir dir;
  const auto path = dir.file("counters.toml");
  std::string error;
  REQUIRE(sas::kiosk::SaveCounters(path, Sample(), kNames, &error));
  const std::string before = ReadAll(path);
  UsageCounters bigger = Sample();
  bigger.sessions = 10;
  bool saved = true;
  {
    FileSizeLimit limit(16);  // far smaller than the file
    saved = sas::kiosk::SaveCounters(path, bigger, kNames, &error);
  }
  CHECK_FALSE(saved);
  CHECK_THAT(error, Catch::Contains("counters.toml"));
  CHECK(ReadAll(path) == before);
  // No temporary file is left behind: only the file and its backup.
  int entries = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    ++entries;
  }
  CHECK(entries == 2);
  CHECK(ReadAll(path + ".backup") == before);
}

TEST_CASE("atomic write replaces the whole file and reports an unwritable directory", "[kiosk]") {
  sas::test::TempDir dir;
  const auto path = dir.Write("f.txt", "old contents that are longer than the new ones");
  std::string error;
  REQUIRE(sas::kiosk::AtomicWriteFile(path, "new", &error));
  CHECK(ReadAll(path) == "new");
  CHECK_FALSE(sas::kiosk::AtomicWriteFile(dir.file("missing-dir/f.txt"), "x", &error));
  CHECK_THAT(error, Catch::Contains("missing-dir"));
}

TEST_CASE("an unsynced atomic write still replaces the whole file, mode 0644, no temporary left",
          "[kiosk]") {
  sas::test::TempDir dir;
  const auto path = dir.Write("m.prom", "old contents that are longer than the new ones");
  std::string error;
  REQUIRE(sas::kiosk::AtomicWriteFile(path, "new", &error, sas::kiosk::Durability::kReadersOnly));
  CHECK(ReadAll(path) == "new");
  const auto perms = std::filesystem::status(path).permissions();
  CHECK((perms & std::filesystem::perms::others_read) != std::filesystem::perms::none);
  int entries = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    ++entries;
  }
  CHECK(entries == 1);
  CHECK_FALSE(sas::kiosk::AtomicWriteFile(dir.file("missing-dir/m.prom"), "x", &error,
                                          sas::kiosk::Durability::kReadersOnly));
  CHECK_THAT(error, Catch::Contains("missing-dir"));
}

TEST_CASE(
    "the start-up load removes the temporaries a kill left next to the counters or the backup",
    "[kiosk]") {
  sas::test::TempDir dir;
  const auto path = dir.file("counters.toml");
  std::string error;
  REQUIRE(sas::kiosk::SaveCounters(path, Sample(), kNames, &error));
  const auto main_temp = dir.Write(".counters.toml.a1B2c3", "sessions = 1\n");
  const auto backup_temp = dir.Write(".counters.toml.backup.Zz9yX8", "sessions = 1\n");
  const auto unrelated = dir.Write(".counters.toml.notes", "keep me\n");
  const auto recovery = sas::kiosk::RecoverCounters(path, kNames);
  CHECK(recovery.counters == Sample());
  CHECK_FALSE(std::ifstream(main_temp).good());
  CHECK_FALSE(std::ifstream(backup_temp).good());
  CHECK(ReadAll(unrelated) == "keep me\n");  // not mkstemp's six-character suffix
}
