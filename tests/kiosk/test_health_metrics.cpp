// The fleet's health metrics (kiosk/health_metrics.h): the text exposition format, and a writer
// whose failed write leaves node-exporter's folder as it was.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "kiosk/health_metrics.h"
#include "support/file_size_limit.h"
#include "support/temp_dir.h"

using sas::kiosk::FormatHealthMetrics;
using sas::kiosk::HealthMetricsWriter;
using sas::kiosk::HealthSnapshot;
using sas::platform::DeviceState;

namespace {

constexpr std::int64_t kS = 1'000'000'000;

HealthSnapshot Sample() {
  HealthSnapshot s;
  s.version = "9.8.7";
  s.box_name = "hall \"B\"\\east";  // quote and backslash must be escaped in the label
  s.start_time_s = 1.7e9;
  s.uptime_s = 42.5;
  sas::platform::DeviceStatus pen;
  pen.device = "pen";
  pen.state = DeviceState::kLost;
  sas::platform::DeviceStatus out;
  out.device = "audio_out";
  out.state = DeviceState::kOk;
  s.devices = {out, pen};
  s.xruns = 3;
  s.audio_callback_age_s = 0.004;
  s.counters.sessions = 11;
  s.counters.recordings = 2;
  s.counters.failed_recordings = 5;
  s.counters.voice_strokes = 6;
  s.counters.strokes_per_texture = {7, 0, 123456789012ULL};
  s.texture_keys = {"wooden_board", "bubble_wrap", "broken_glass"};
  s.speaker_leq_last_hour_dbfs = -31.25;
  s.texture_shown = "broken_glass";
  s.config_accepted = false;
  return s;
}

// Every sample line as "name{labels}" -> value text.
std::map<std::string, std::string> Samples(const std::string& text) {
  std::map<std::string, std::string> samples;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto space = line.rfind(' ');
    samples[line.substr(0, space)] = line.substr(space + 1);
  }
  return samples;
}

std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::set<std::string> Entries(const std::filesystem::path& folder) {
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    names.insert(entry.path().filename().string());
  }
  return names;
}

}  // namespace

TEST_CASE(
    "health metrics: every sample belongs to a family announced by HELP and TYPE before "
    "it, counters end in _total, and every line is name{labels} value",
    "[kiosk][metrics]") {
  const std::string text = FormatHealthMetrics(Sample());
  REQUIRE(!text.empty());
  CHECK(text.back() == '\n');
  const std::regex name_re("[a-zA-Z_:][a-zA-Z0-9_:]*");
  const std::regex label_re(R"([a-zA-Z_][a-zA-Z0-9_]*="(?:[^"\\\n]|\\.)*")");
  const std::regex sample_re(R"(([a-zA-Z_:][a-zA-Z0-9_:]*)(\{([^}]*)\})? (\S+))");
  std::map<std::string, std::string> types;
  std::set<std::string> helped;
  std::istringstream lines(text);
  std::string line;
  int samples = 0;
  while (std::getline(lines, line)) {
    INFO(line);
    std::smatch m;
    if (line.rfind("# HELP ", 0) == 0) {
      const std::string name = line.substr(7, line.find(' ', 7) - 7);
      CHECK(std::regex_match(name, name_re));
      CHECK(helped.insert(name).second);  // one family, one HELP
    } else if (line.rfind("# TYPE ", 0) == 0) {
      std::istringstream fields(line.substr(7));
      std::string name, type;
      fields >> name >> type;
      CHECK((type == "gauge" || type == "counter"));
      CHECK(helped.count(name) == 1);
      if (type == "counter") CHECK(name.size() > 6);
      if (type == "counter") CHECK(name.substr(name.size() - 6) == "_total");
      CHECK(types.emplace(name, type).second);
    } else {
      REQUIRE(std::regex_match(line, m, sample_re));
      CHECK(m[1].str().rfind("sketch_a_scratch_", 0) == 0);
      CHECK(types.count(m[1].str()) == 1);
      if (m[3].matched) {
        // Labels: name="value" pairs separated by commas (values may hold escaped quotes).
        const std::string labels = m[3].str();
        const std::regex pairs(
            R"(^[a-zA-Z_][a-zA-Z0-9_]*="(?:[^"\\\n]|\\.)*"(,[a-zA-Z_][a-zA-Z0-9_]*="(?:[^"\\\n]|\\.)*")*$)");
        CHECK(std::regex_match(labels, pairs));
      }
      ++samples;
    }
  }
  CHECK(samples > 20);
}

TEST_CASE(
    "health metrics: the snapshot's counts, states, texture and verdict are the samples' "
    "values, the box name escaped in its label",
    "[kiosk][metrics]") {
  const auto samples = Samples(FormatHealthMetrics(Sample()));
  CHECK(samples.at(R"(sketch_a_scratch_info{version="9.8.7",box="hall \"B\"\\east"})") == "1");
  CHECK(samples.at("sketch_a_scratch_uptime_seconds") == "42.5");
  CHECK(samples.at("sketch_a_scratch_start_time_seconds") == "1700000000");
  CHECK(samples.at(R"(sketch_a_scratch_device_state{device="pen",state="lost"})") == "1");
  CHECK(samples.at(R"(sketch_a_scratch_device_state{device="pen",state="ok"})") == "0");
  CHECK(samples.at(R"(sketch_a_scratch_device_state{device="audio_out",state="ok"})") == "1");
  CHECK(samples.at(R"(sketch_a_scratch_device_state{device="audio_out",state="missing"})") == "0");
  CHECK(samples.at("sketch_a_scratch_audio_xruns_total") == "3");
  CHECK(samples.at("sketch_a_scratch_audio_callback_age_seconds") == "0.004");
  CHECK(samples.at("sketch_a_scratch_visits_total") == "11");
  CHECK(samples.at(R"(sketch_a_scratch_strokes_total{texture="wooden_board"})") == "7");
  CHECK(samples.at(R"(sketch_a_scratch_strokes_total{texture="bubble_wrap"})") == "0");
  CHECK(samples.at(R"(sketch_a_scratch_strokes_total{texture="broken_glass"})") == "123456789012");
  CHECK(samples.at(R"(sketch_a_scratch_strokes_total{texture="voice"})") == "6");
  CHECK(samples.at(R"(sketch_a_scratch_recordings_total{result="ok"})") == "2");
  CHECK(samples.at(R"(sketch_a_scratch_recordings_total{result="failed"})") == "5");
  CHECK(samples.at("sketch_a_scratch_speaker_leq_last_hour_dbfs") == "-31.25");
  CHECK(samples.at(R"(sketch_a_scratch_texture_shown{texture="broken_glass"})") == "1");
  CHECK(samples.at(R"(sketch_a_scratch_texture_shown{texture="wooden_board"})") == "0");
  CHECK(samples.at(R"(sketch_a_scratch_texture_shown{texture="voice"})") == "0");
  CHECK(samples.at("sketch_a_scratch_config_accepted") == "0");

  HealthSnapshot fresh = Sample();
  fresh.audio_callback_age_s.reset();
  fresh.speaker_leq_last_hour_dbfs.reset();
  const auto unknown = Samples(FormatHealthMetrics(fresh));
  CHECK(unknown.at("sketch_a_scratch_audio_callback_age_seconds") == "NaN");
  CHECK(unknown.at("sketch_a_scratch_speaker_leq_last_hour_dbfs") == "NaN");
}

TEST_CASE(
    "health metrics writer: a write that fails (disk full, rename refused) leaves the "
    "collector's folder with the last whole file and no temporary",
    "[kiosk][metrics]") {
  sas::test::TempDir dir;
  sas::platform::Logger log;
  log.SetEchoToStderr(false);
  const std::string path = dir.file("sketch_a_scratch.prom");
  HealthMetricsWriter writer(path, 5.0, log);
  const std::string first = FormatHealthMetrics(Sample());
  REQUIRE(writer.Write(0, "a", first));
  REQUIRE(ReadAll(path) == first);

  SECTION("disk full in the middle of the file") {
    // Far more than the limit, so the temporary file is cut in the middle of a line.
    HealthSnapshot bigger = Sample();
    for (int i = 0; i < 200; ++i) {
      sas::platform::DeviceStatus device;
      device.device = "device_" + std::to_string(i);
      bigger.devices.push_back(device);
    }
    const std::string second = FormatHealthMetrics(bigger);
    REQUIRE(second.size() > 4 * first.size());
    {
      sas::test::FileSizeLimit full(first.size());
      CHECK_FALSE(writer.Write(6 * kS, "a", second));
    }
    CHECK(ReadAll(path) == first);
    CHECK(Entries(dir.path()) == std::set<std::string>{"sketch_a_scratch.prom"});
    // And once there is room again, the next write replaces the file whole.
    CHECK(writer.Write(12 * kS, "a", second));
    CHECK(ReadAll(path) == second);
    CHECK(Entries(dir.path()) == std::set<std::string>{"sketch_a_scratch.prom"});
  }
  SECTION("the rename fails (the target became a folder)") {
    std::filesystem::remove(path);
    std::filesystem::create_directories(std::filesystem::path(path) / "in-the-way");
    CHECK_FALSE(writer.Write(6 * kS, "a", first));
    CHECK(Entries(dir.path()) == std::set<std::string>{"sketch_a_scratch.prom"});
    CHECK(std::filesystem::is_directory(path));
  }
  // The failure is one journal line, not one per retry.
  int warnings = 0;
  for (const auto& line : log.Recent()) {
    if (line.component == "metrics" && line.level == sas::platform::LogLevel::kWarn) ++warnings;
  }
  CHECK(warnings == 1);
}

TEST_CASE(
    "health metrics writer: due every interval, and within a second of a state change, "
    "never more than once a second",
    "[kiosk][metrics]") {
  sas::test::TempDir dir;
  sas::platform::Logger log;
  log.SetEchoToStderr(false);
  HealthMetricsWriter writer(dir.file("m.prom"), 5.0, log);
  CHECK(writer.Due(0, "pen=ok"));
  REQUIRE(writer.Write(0, "pen=ok", "x 1\n"));
  CHECK_FALSE(writer.Due(4 * kS, "pen=ok"));
  CHECK(writer.Due(5 * kS, "pen=ok"));
  CHECK_FALSE(writer.Due(kS / 2, "pen=lost"));  // a change, but the last write is too recent
  CHECK(writer.Due(kS, "pen=lost"));
  HealthMetricsWriter off("", 5.0, log);
  CHECK_FALSE(off.enabled());
  CHECK_FALSE(off.Due(100 * kS, "pen=ok"));
}
