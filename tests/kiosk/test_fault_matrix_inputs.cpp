// The fault matrix, continued (see test_fault_matrix.cpp): the data files the renderer and the
// kiosk load at start (materials, textures, pictures, spoken cues, gestures) and every command's
// arguments. Each table is one test case; a failure names its row. The promise per surface:
//   data files   the loader refuses the file with a message naming it (and the key where there is
//                one); nothing half-loaded is used. Cues are the exception by design: a bad cue is
//                left out with one problem line, the others still play.
//   arguments    a bad argument form is a usage error: exit 2, one message naming the option, and
//                nothing run; --help exits 0. The kiosk with no display exits 1 writing nothing.
#include <sys/resource.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "fault_matrix_support.h"
#include "headless_demo.h"
#include "tools/builtin_profiles.h"
#include "tools/command_line.h"
#include "files/counters_file.h"
#include "kiosk/gesture.h"
#include "tools/impact_command.h"
#include "kiosk/kiosk_engine.h"
#include "files/material_file.h"
#include "tools/render_command.h"
#include "live_kiosk.h"
#include "platform/log/log.h"
#include "support/file_size_limit.h"
#include "support/temp_dir.h"
#include "surface/cue_library.h"
#include "surface/image_surface.h"

namespace fs = std::filesystem;

namespace {

using sas::test::ReadAll;

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

// A mono 32-bit float WAV written byte by byte: WriteWav refuses NaN and infinities, and a damaged
// file is exactly what these rows need.
void WriteRawFloatWav(const std::string& path, const std::vector<float>& samples) {
  const auto u32 = [](std::uint32_t v) {
    return std::string(reinterpret_cast<const char*>(&v), 4);
  };
  const auto u16 = [](std::uint16_t v) {
    return std::string(reinterpret_cast<const char*>(&v), 2);
  };
  const auto data_bytes = static_cast<std::uint32_t>(samples.size() * sizeof(float));
  std::string bytes = "RIFF" + u32(36 + data_bytes) + "WAVEfmt " + u32(16) + u16(3) + u16(1) +
                      u32(48000) + u32(48000 * 4) + u16(4) + u16(32) + "data" + u32(data_bytes);
  bytes.append(reinterpret_cast<const char*>(samples.data()), data_bytes);
  std::ofstream(path, std::ios::binary) << bytes;
}

std::vector<float> Tone(float amplitude) {
  std::vector<float> samples(4800);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    samples[i] = amplitude * static_cast<float>(std::sin(0.05 * static_cast<double>(i)));
  }
  return samples;
}

// One data-file row: `make` writes the bad file into the folder and returns its path; the loader
// must throw a message holding that path and `message`.
struct FileRow {
  const char* name;
  std::function<std::string(const sas::test::TempDir&)> make;
  const char* message;
};

void CheckRefused(const char* surface, const std::vector<FileRow>& rows,
                  const std::function<void(const std::string&)>& load) {
  for (const auto& row : rows) {
    INFO("row: " << surface << ", " << row.name);
    sas::test::TempDir dir;
    const std::string path = row.make(dir);
    std::string message;
    try {
      load(path);
    } catch (const std::exception& error) {
      message = error.what();
    }
    CHECK_THAT(message, Catch::Contains(path) && Catch::Contains(row.message));
  }
}

const std::string kSource = kSasSourceDir;

}  // namespace

TEST_CASE("fault matrix: material files - a damaged file is refused naming file and key",
          "[kiosk][faults]") {
  const std::string wood = ReadAll(kSource + "/textures/materials/wood.toml");
  const auto edit = [&wood](std::string from, std::string to) {
    return [&wood, from, to](const sas::test::TempDir& dir) {
      return dir.Write("wood.toml", Replace(wood, from, to));
    };
  };
  const std::vector<FileRow> rows = {
      {"a NaN mode frequency", edit("frequency_hz = 323", "frequency_hz = nan"), "frequency_hz"},
      {"a mode mass of 1e30", edit("mass_kg = 0.417", "mass_kg = 1e30"), "mass_kg"},
      {"a misspelt key", edit("modes = [", "modez = ["), "modez"},
      {"empty file", [](const sas::test::TempDir& dir) { return dir.Write("wood.toml", ""); }, ""},
      {"binary junk",
       [](const sas::test::TempDir& dir) {
         return dir.Write("wood.toml", std::string("\x7f"
                                                   "ELF\x02\x01\x00\xff\xfe",
                                                   9));
       },
       ""},
      {"a directory named like the file",
       [](const sas::test::TempDir& dir) {
         fs::create_directory(dir.file("wood.toml"));
         return dir.file("wood.toml");
       },
       ""},
  };
  CheckRefused("material file", rows,
               [](const std::string& path) { (void)sas::kiosk::LoadMaterialFile(path); });
  CHECK(rows.size() == 6);
}

TEST_CASE("fault matrix: texture files - a damaged texture is refused naming the file",
          "[kiosk][faults]") {
  // A copy of a shipped texture folder, then one thing in it damaged.
  const auto texture = [](std::function<void(const fs::path&)> damage) {
    return [damage](const sas::test::TempDir& dir) {
      fs::copy(kSource + "/textures/broken_glass", dir.path() / "glass");
      damage(dir.path() / "glass");
      return (dir.path() / "glass" / "texture.toml").string();
    };
  };
  const auto edit = [](std::string from, std::string to) {
    return [from, to](const fs::path& folder) {
      const std::string file = (folder / "texture.toml").string();
      const std::string text = Replace(ReadAll(file), from, to);
      std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
    };
  };
  const std::vector<FileRow> rows = {
      {"height map missing", texture([](const fs::path& f) { fs::remove(f / "height.png"); }),
       "height.png"},
      {"height map not a PNG",
       texture([](const fs::path& f) { std::ofstream(f / "height.png") << "not a picture"; }),
       "height.png"},
      {"height_scale_mm NaN", texture(edit("height_scale_mm = 2.0", "height_scale_mm = nan")),
       "height_scale_mm"},
      {"height_scale_mm 1e30", texture(edit("height_scale_mm = 2.0", "height_scale_mm = 1e30")),
       "height_scale_mm"},
      {"an unknown key", texture(edit("relief_mm = 0.3", "relief_mm = 0.3\ncolour = 1")), "colour"},
      {"empty texture.toml",
       texture([](const fs::path& f) { std::ofstream(f / "texture.toml", std::ios::trunc); }), ""},
  };
  CheckRefused("texture file", rows,
               [](const std::string& path) { (void)sas::kiosk::LoadProfile(path); });
  CHECK(rows.size() == 6);
}

TEST_CASE("fault matrix: pictures - a damaged picture is refused naming the file",
          "[kiosk][faults]") {
  const std::string png = ReadAll(kSource + "/textures/broken_glass/picture.png");
  const auto bytes = [](std::string contents) {
    return [contents](const sas::test::TempDir& dir) { return dir.Write("p.png", contents); };
  };
  const std::vector<FileRow> rows = {
      {"zero bytes", bytes(""), ""},
      {"text named .png", bytes("this is not a picture\n"), ""},
      {"a PNG cut in half", bytes(png.substr(0, png.size() / 2)), ""},
      {"only the PNG signature", bytes(png.substr(0, 8)), ""},
      {"a directory named .png",
       [](const sas::test::TempDir& dir) {
         fs::create_directory(dir.file("p.png"));
         return dir.file("p.png");
       },
       ""},
  };
  CheckRefused("picture", rows,
               [](const std::string& path) { (void)sas::surface::HeightFieldFromImageFile(path); });
  CHECK(rows.size() == 5);
}

TEST_CASE("fault matrix: gesture files - a damaged gesture is refused naming file and line",
          "[kiosk][faults]") {
  const auto csv = [](std::string contents) {
    return [contents](const sas::test::TempDir& dir) { return dir.Write("g.csv", contents); };
  };
  const std::string head = "t,x,y,pressure,tilt\n0,10,20,0.5,10\n";
  const std::vector<FileRow> rows = {
      {"NaN pressure", csv(head + "0.1,12,20,nan,10\n"), ":3"},
      {"x of 1e30", csv(head + "0.1,1e30,20,0.5,10\n"), ":3"},
      {"time going backwards", csv(head + "0.2,12,20,0.5,10\n0.1,14,20,0.5,10\n"), ":4"},
      {"a missing column", csv(head + "0.1,12,20,0.5\n"), ":3"},
      {"empty file", csv(""), ""},
      {"header only", csv("t,x,y,pressure,tilt\n"), ""},
  };
  CheckRefused("gesture file", rows,
               [](const std::string& path) { (void)sas::kiosk::LoadGestureCsv(path); });
  CHECK(rows.size() == 6);
}

TEST_CASE("fault matrix: cue WAVs - a damaged cue is left out with one problem line, the rest play",
          "[kiosk][faults]") {
  const struct {
    const char* name;
    std::function<void(const std::string&)> damage;
  } rows[] = {
      {"NaN samples",
       [](const std::string& p) {
         auto s = Tone(0.5f);
         s[100] = std::numeric_limits<float>::quiet_NaN();
         WriteRawFloatWav(p, s);
       }},
      {"infinite samples",
       [](const std::string& p) {
         auto s = Tone(0.5f);
         s[200] = std::numeric_limits<float>::infinity();
         WriteRawFloatWav(p, s);
       }},
      {"samples of 1e30", [](const std::string& p) { WriteRawFloatWav(p, Tone(1e30f)); }},
      {"not a WAV", [](const std::string& p) { std::ofstream(p) << "RIFF? no, text\n"; }},
      {"zero bytes", [](const std::string& p) { std::ofstream(p, std::ios::trunc); }},
  };
  // Through the kiosk engine, which loads the cues it plays; one texture, so its two cues and
  // the five message cues.
  const std::vector<std::string> folders = {"wooden_board"};
  const auto expected = sas::surface::ExpectedCueFiles(folders);
  auto& log = sas::platform::DefaultLogger();
  log.SetEchoToStderr(false);
  for (const auto& row : rows) {
    INFO("row: cue WAV, " << row.name);
    sas::test::TempDir dir;
    for (const auto& file : expected) WriteRawFloatWav(dir.file(file), Tone(0.3f));
    row.damage(dir.file("wooden_board_name.wav"));
    log.Clear();
    sas::kiosk::KioskEngineOptions options;
    options.virtual_clock = true;
    options.cues_dir = dir.path().string();
    options.texture_paths = {kSource + "/textures/wooden_board/texture.toml"};
    options.counters_path = dir.file("counters.toml");
    sas::kiosk::KioskEngine engine(options);
    CHECK(engine.cues_loaded() == static_cast<int>(expected.size()) - 1);
    int lines = 0;
    for (const auto& line : log.Recent()) {
      if (line.component == "cues" &&
          line.message.find("wooden_board_name.wav") != std::string::npos)
        ++lines;
    }
    CHECK(lines == 1);
  }
}

namespace {

struct CommandResult {
  int code = -1;
  std::string out;
  std::string err;
};

CommandResult Capture(const std::function<int(std::FILE*, std::FILE*)>& run) {
  std::FILE* out = std::tmpfile();
  std::FILE* err = std::tmpfile();
  REQUIRE(out != nullptr);
  REQUIRE(err != nullptr);
  CommandResult result;
  result.code = run(out, err);
  for (auto [file, text] : {std::pair{out, &result.out}, std::pair{err, &result.err}}) {
    std::rewind(file);
    char buffer[4096];
    std::size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, file)) > 0) text->append(buffer, n);
    std::fclose(file);
  }
  return result;
}

int RunDemoParser(const std::vector<std::string>& args, std::FILE* out, std::FILE* err) {
  sas::app::HeadlessOptions options;
  CLI::App app("demo", "demo");
  sas::app::AddHeadlessOptions(app, options);
  return sas::kiosk::ParseCommandLine(app, args, out, err);
}

}  // namespace

TEST_CASE("fault matrix: command arguments - each bad form exits 2 naming the option",
          "[kiosk][faults]") {
  // The kiosk rows must stop at the parser: with no display SDL is asked for a driver that
  // does not exist, so a row that got past the parser would exit 1, not 2.
  setenv("SDL_VIDEODRIVER", "no-such-driver", 1);
  using Runner = std::function<int(const std::vector<std::string>&, std::FILE*, std::FILE*)>;
  const Runner render = [](const auto& a, auto* o, auto* e) {
    return sas::kiosk::RunRenderCommand(a, o, e);
  };
  const Runner impact = [](const auto& a, auto* o, auto* e) {
    return sas::kiosk::RunImpactCommand(a, o, e);
  };
  const Runner kiosk = [](const auto& a, auto* o, auto* e) { return sas::app::RunKiosk(a, o, e); };
  const Runner demo = RunDemoParser;
  const struct {
    const char* command;
    const Runner* run;
    std::vector<std::string> args;
    const char* named;
  } rows[] = {
      {"render", &render, {"--out", "x.wav", "--fs", "nan"}, "--fs"},
      {"render", &render, {"--out", "x.wav", "--fs", "1e30"}, "--fs"},
      {"render", &render, {"--out", "x.wav", "--tail-s", "-1"}, "--tail-s"},
      {"render", &render, {"--out", "x.wav", "--gain-db", "inf"}, "--gain-db"},
      {"render", &render, {"--out", "x.wav", "--format"}, "--format"},
      {"render", &render, {"--out", "x.wav", "--profile"}, "--profile"},
      {"render", &render, {"--out", "x.wav", "--loud"}, "--loud"},
      {"render", &render, {"--out", "x.wav", "stray"}, "stray"},
      // An unknown option is named even where a required one is missing too (CLI11 alone
      // would only say that --out is required).
      {"render", &render, {"--no-such-flag"}, "--no-such-flag"},
      {"impact", &impact, {"--mass", "nan"}, "--mass"},
      {"impact", &impact, {"--k", "1e30"}, "--k"},
      {"impact", &impact, {"--oversample", "-1"}, "--oversample"},
      {"impact", &impact, {"--scheme", "euler"}, "--scheme"},
      {"impact", &impact, {"--v-in"}, "--v-in"},
      {"kiosk", &kiosk, {"--config"}, "--config"},
      {"kiosk", &kiosk, {"--state-dir"}, "--state-dir"},
      {"kiosk", &kiosk, {"--fullscreen"}, "--fullscreen"},
      {"demo", &demo, {"--out"}, "--out"},
      {"demo", &demo, {"--out", ""}, "--out"},
      {"demo", &demo, {"--quick=maybe"}, "--quick"},
  };
  for (const auto& row : rows) {
    std::string line = row.command;
    for (const auto& arg : row.args) line += " '" + arg + "'";
    INFO("row: arguments, " << line);
    const auto result =
        Capture([&](std::FILE* o, std::FILE* e) { return (*row.run)(row.args, o, e); });
    INFO(result.err);
    CHECK(result.code == 2);
    CHECK_THAT(result.err, Catch::Contains(row.named) && Catch::Contains("--help"));
    CHECK(result.out.empty());
  }
  // A missing value is said to be missing, not an unknown option.
  const auto missing =
      Capture([&](std::FILE* o, std::FILE* e) { return kiosk({"--config"}, o, e); });
  CHECK_THAT(missing.err, Catch::Contains("missing"));
  unsetenv("SDL_VIDEODRIVER");
}

TEST_CASE(
    "fault matrix: command arguments - --help exits 0 on every command, the kiosk with no "
    "display exits 1 and writes nothing",
    "[kiosk][faults]") {
  setenv("SDL_VIDEODRIVER", "no-such-driver", 1);
  for (const char* command : {"render", "impact", "kiosk", "demo"}) {
    INFO("row: arguments, " << command << " --help");
    const auto result = Capture([&](std::FILE* o, std::FILE* e) {
      const std::vector<std::string> help = {"--help"};
      if (std::strcmp(command, "render") == 0) return sas::kiosk::RunRenderCommand(help, o, e);
      if (std::strcmp(command, "impact") == 0) return sas::kiosk::RunImpactCommand(help, o, e);
      if (std::strcmp(command, "kiosk") == 0) return sas::app::RunKiosk(help, o, e);
      return RunDemoParser(help, o, e);
    });
    CHECK(result.code == 0);
    CHECK_THAT(result.out, Catch::Contains("--"));
  }
  {
    INFO("row: arguments, kiosk with no display");
    sas::test::TempDir dir;
    const std::string state = dir.file("state");
    const auto result = Capture([&](std::FILE* o, std::FILE* e) {
      return sas::app::RunKiosk({"--state-dir", state}, o, e);
    });
    CHECK(result.code == 1);
    CHECK_THAT(result.err, Catch::Contains("no display"));
    CHECK_FALSE(fs::exists(state));
  }
  unsetenv("SDL_VIDEODRIVER");
}

// ---------------------------------------------------------------------------------------------
// Surface: the state folder (usage counters). A history is saved, the folder then breaks, the
// kiosk starts, one stroke, it saves. Promise: the save fails without harm - the saved history is
// still there byte for byte, no temporary file is left behind, and the failure is said once - and
// the counts go on in memory. A full disk is this process's file-size limit (RLIMIT_FSIZE, with
// SIGXFSZ ignored): it fails writes with EFBIG as a full disk fails them with ENOSPC, and works
// as root, which a read-only folder (chmod) does not.

namespace {

using sas::test::FileSizeLimit;

}  // namespace

TEST_CASE("fault matrix: state folder - a full disk or a broken folder loses no saved history",
          "[kiosk][faults]") {
  auto& log = sas::platform::DefaultLogger();
  log.SetEchoToStderr(false);
  const std::vector<std::string> keys = {"wooden_board"};
  const struct {
    const char* name;
    rlim_t file_size_limit;  // 0: none
    bool folder_is_file;
  } rows[] = {
      {"disk full after 16 bytes", 16, false},
      {"disk full at the first byte", 1, false},
      {"the state folder is a regular file", 0, true},
  };
  for (const auto& row : rows) {
    INFO("row: state folder, " << row.name);
    sas::test::TempDir dir;
    std::string state = dir.file("state");
    fs::create_directory(state);
    std::string path = (fs::path(state) / "counters.toml").string();
    sas::kiosk::UsageCounters before;
    before.sessions = 5000;
    before.strokes_per_texture = {12000};
    std::string error;
    REQUIRE(sas::kiosk::SaveCounters(path, before, keys, &error));
    const std::string saved = ReadAll(path);
    if (row.folder_is_file) {
      // The folder replaced by a file holding the history (a restore gone wrong): the kiosk
      // must neither write into it nor replace it.
      state = dir.Write("state-file", saved);
      path = (fs::path(state) / "counters.toml").string();
    }
    log.Clear();
    sas::kiosk::KioskEngineOptions options;
    options.virtual_clock = true;
    options.cues_dir = "/nonexistent";
    options.texture_paths = {kSource + "/textures/wooden_board/texture.toml"};
    options.counters_path = path;
    const auto listing = [](const std::string& folder) {
      std::set<std::string> names;
      std::error_code ec;
      if (fs::is_directory(folder, ec)) {
        for (const auto& entry : fs::directory_iterator(folder)) {
          names.insert(entry.path().filename().string());
        }
      }
      return names;
    };
    {
      sas::kiosk::KioskEngine engine(options);
      const auto files_at_start = listing(state);  // counters.toml and its backup
      sas::test::OneStroke(engine);
      std::optional<FileSizeLimit> limit;
      if (row.file_size_limit > 0) limit.emplace(row.file_size_limit);
      const bool saved_ok = engine.SaveCounters(&error);
      limit.reset();
      CHECK_FALSE(saved_ok);
      CHECK(ReadAll(row.folder_is_file ? state : path) == saved);
      CHECK(listing(state) == files_at_start);  // no temporary left behind
      CHECK(engine.session().counters().strokes_per_texture.at(0) >= 1);  // counting on
    }
    // The engine saves again on its way out; with room on the disk again nothing is lost.
    if (!row.folder_is_file) {
      sas::kiosk::UsageCounters after;
      sas::kiosk::LoadCounters(path, keys, &after, &error);
      CHECK(after.sessions >= before.sessions + 1);
    } else {
      CHECK(ReadAll(state) == saved);
    }
    int warnings = 0;
    for (const auto& line : log.Recent()) {
      if (line.level >= sas::platform::LogLevel::kWarn) ++warnings;
    }
    CHECK(warnings >= 1);
  }
}
