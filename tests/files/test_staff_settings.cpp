// The staff panel's volume/vibration/low-vibration settings kept in the state folder: round trip,
// steps and limits, and a damaged file kept aside with the defaults in use.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "files/staff_settings.h"
#include "support/temp_dir.h"

using sas::kiosk::LoadStaffSettings;
using sas::kiosk::SaveStaffSettings;
using sas::kiosk::StaffSettings;

namespace {

std::string Read(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::filesystem::path> Aside(const sas::test::TempDir& dir) {
  std::vector<std::filesystem::path> found;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    if (entry.path().filename().string().find(".damaged-") != std::string::npos) {
      found.push_back(entry.path());
    }
  }
  return found;
}

}  // namespace

TEST_CASE("staff settings: what is saved is what loads, and a missing file is the defaults",
          "[kiosk]") {
  sas::test::TempDir dir;
  const auto path = dir.file("staff.toml");
  const auto none = LoadStaffSettings(path);
  CHECK(none.settings == StaffSettings{});
  CHECK(none.report.empty());
  StaffSettings settings;
  settings.volume_db = -9.0;
  settings.vibration_db = 3.0;
  settings.low_vibration = true;
  std::string error;
  REQUIRE(SaveStaffSettings(path, settings, &error));
  const auto loaded = LoadStaffSettings(path);
  CHECK(loaded.settings == settings);
  CHECK(loaded.report.empty());
}

TEST_CASE("staff settings: steps are 3 dB and stop at the limits", "[kiosk]") {
  CHECK(sas::kiosk::StepStaffDb(0.0, 1) == 3.0);
  CHECK(sas::kiosk::StepStaffDb(0.0, -2) == -6.0);
  CHECK(sas::kiosk::StepStaffDb(3.0, 5) == sas::kiosk::kStaffMaxDb);
  CHECK(sas::kiosk::StepStaffDb(-21.0, -3) == sas::kiosk::kStaffMinDb);
}

TEST_CASE("staff settings: a damaged file is kept aside, reported once, and the defaults used",
          "[kiosk]") {
  struct Row {
    const char* what;
    const char* text;
    const char* reported;
  };
  const Row rows[] = {
      {"truncated", "volume_db = -6.0\nvibration_db = ", "staff.toml:2"},
      {"binary junk", "\x01\x02\xff\xfe", "staff.toml"},
      {"out of range", "volume_db = 40.0\n", "volume_db"},
      {"wrong type", "low_vibration = 3\n", "low_vibration"},
      {"unknown key", "volume = 3.0\n", "unknown key"},
      {"empty", "", "empty"},
  };
  for (const auto& row : rows) {
    DYNAMIC_SECTION(row.what) {
      sas::test::TempDir dir;
      const auto path = dir.Write("staff.toml", row.text);
      const auto load = LoadStaffSettings(path);
      CHECK(load.settings == StaffSettings{});
      CHECK(load.may_save);
      CHECK_THAT(load.report, Catch::Contains(row.reported) && Catch::Contains("kept as") &&
                                  Catch::Contains("defaults"));
      // Never lost: the damaged bytes are kept under the name the report gives.
      const auto aside = Aside(dir);
      REQUIRE(aside.size() == 1);
      CHECK(Read(aside.front()) == row.text);
      CHECK_THAT(load.report, Catch::Contains(aside.front().string()));
      CHECK_FALSE(std::filesystem::exists(path));
      // The next save writes a whole new file and leaves the kept one alone.
      StaffSettings settings;
      settings.volume_db = -3.0;
      std::string error;
      REQUIRE(SaveStaffSettings(path, settings, &error));
      CHECK(LoadStaffSettings(path).settings == settings);
      CHECK(Read(aside.front()) == row.text);
    }
  }
}
