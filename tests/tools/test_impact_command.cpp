// The `impact` calibration command: its JSON carries the engine's measurement next to the closed
// form, and bad arguments are refused with a message naming the option.
#include <catch2/catch.hpp>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "tools/impact_command.h"

namespace {

// The number after "<section>": {... "<key>": in the report.
double Field(const std::string& json, const std::string& section, const std::string& key) {
  const auto section_at = json.find("\"" + section + "\"");
  REQUIRE(section_at != std::string::npos);
  const auto key_at = json.find("\"" + key + "\": ", section_at);
  REQUIRE(key_at != std::string::npos);
  return std::stod(json.substr(key_at + key.size() + 4));
}

std::string Capture(const std::vector<std::string>& args, int* exit_code) {
  std::FILE* out = std::tmpfile();
  std::FILE* err = std::tmpfile();
  *exit_code = sas::kiosk::RunImpactCommand(args, out, err);
  std::string text;
  for (std::FILE* stream : {out, err}) {
    std::rewind(stream);
    char buffer[512];
    std::size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, stream)) > 0) text.append(buffer, n);
    std::fclose(stream);
  }
  return text;
}

}  // namespace

TEST_CASE("impact command reports the engine's exit velocity within 1e-4 of the closed form",
          "[kiosk]") {
  int exit_code = -1;
  const std::string json = Capture({"--mass", "0.01", "--k", "1e6", "--mu", "0.5", "--alpha", "1.5",
                                    "--v-in", "1", "--phase", "0.37"},
                                   &exit_code);
  INFO(json);
  REQUIRE(exit_code == 0);
  // Closed-form values (Lambert-W form, computed independently; m = 10 g, α = 1.5).
  CHECK(Field(json, "closed_form", "restitution") == Approx(0.748434931597).epsilon(1e-9));
  CHECK(Field(json, "closed_form", "contact_time_s") == Approx(2.106292e-3).epsilon(3e-6));
  CHECK(Field(json, "measured", "exit_velocity_mps") == Approx(0.748434931597).epsilon(1e-4));
  CHECK(Field(json, "relative_error", "exit_velocity") < 1e-4);
  CHECK(Field(json, "measured", "samples_per_contact") ==
        Approx(2.106292e-3 * 48000).epsilon(1e-2));
  CHECK(json.find("\"energy_gained\": false") != std::string::npos);
}

TEST_CASE("impact command refuses bad arguments naming the option", "[kiosk]") {
  int exit_code = -1;
  auto text = Capture({"--k", "soft"}, &exit_code);
  CHECK(exit_code == 2);
  CHECK_THAT(text, Catch::Contains("--k") && Catch::Contains("not a number"));
  text = Capture({"--alpha", "7"}, &exit_code);
  CHECK(exit_code == 2);
  CHECK_THAT(text, Catch::Contains("out of range"));
  text = Capture({"--scheme", "runge-kutta"}, &exit_code);
  CHECK(exit_code == 2);
  CHECK_THAT(text, Catch::Contains("discrete_gradient"));
  text = Capture({"--mass"}, &exit_code);
  CHECK(exit_code == 2);
  CHECK_THAT(text, Catch::Contains("--mass") && Catch::Contains("missing"));
}

TEST_CASE(
    "impact command runs every contact scheme by name and each stays within its accuracy of "
    "the closed form without gaining energy",
    "[kiosk]") {
  struct Case {
    const char* name;      // as typed on the command line ('-' or '_')
    const char* reported;  // as the JSON names it
    double accuracy;       // the scheme's accuracy at automatic oversampling (k 1e6, 10 g)
  };
  const Case cases[] = {
      {"explicit-passive", "explicit_passive", 1e-3},
      {"trapezoid_newton", "trapezoid_newton", 1e-4},
      {"discrete-gradient", "discrete_gradient", 1e-4},
      {"energy-quadratised", "energy_quadratised", 1e-4},
  };
  double exits[4];
  int i = 0;
  for (const auto& c : cases) {
    int exit_code = -1;
    const std::string json = Capture({"--mass", "0.01", "--k", "1e6", "--mu", "0.5", "--alpha",
                                      "1.5", "--v-in", "1", "--phase", "0.37", "--scheme", c.name},
                                     &exit_code);
    INFO(json);
    REQUIRE(exit_code == 0);
    CHECK(json.find(std::string("\"scheme\": \"") + c.reported + "\"") != std::string::npos);
    CHECK(Field(json, "relative_error", "exit_velocity") < c.accuracy);
    CHECK(json.find("\"energy_gained\": false") != std::string::npos);
    // One step per sample: the schemes are distinct methods, so their results differ.
    const std::string coarse =
        Capture({"--mass", "0.01", "--k", "1e8", "--mu", "1", "--alpha", "1.5", "--v-in", "1",
                 "--phase", "0.37", "--scheme", c.name, "--oversample", "1"},
                &exit_code);
    REQUIRE(exit_code == 0);
    CHECK(Field(coarse, "input", "oversample") == 1.0);
    exits[i++] = Field(coarse, "measured", "exit_velocity_mps");
  }
  for (int a = 0; a < 4; ++a) {
    for (int b = a + 1; b < 4; ++b) CHECK(exits[a] != exits[b]);
  }
}

TEST_CASE("impact command writes valid JSON with null where the closed form has no value",
          "[kiosk]") {
  // Steep contacts (alpha 3-4) at low speed: the closed form's contact-time quadrature gives inf
  // (printed as a bare `inf` before, which no JSON reader accepts).
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"--alpha", "3", "--v-in", "0.0001", "--mass", "0.0001", "--k",
                                 "1e6", "--mu", "0.5"},
        std::vector<std::string>{"--alpha", "4", "--v-in", "1", "--mass", "1", "--k", "1", "--mu",
                                 "0.5", "--fs", "8000"}}) {
    int exit_code = -1;
    const std::string text = Capture(args, &exit_code);
    INFO(text);
    REQUIRE(exit_code == 0);
    nlohmann::json json;
    REQUIRE_NOTHROW(json = nlohmann::json::parse(text));
    CHECK(json["closed_form"]["contact_time_s"].is_null());
    CHECK(json["measured"]["exit_velocity_mps"].is_number());
  }
}

TEST_CASE("impact command flags energy gain only beyond its stated tolerance", "[kiosk]") {
  int exit_code = -1;
  // No damping: the exact restitution is 1 and round-off leaves e a few 1e-9 above it.
  const std::string text = Capture(
      {"--mu", "0", "--k", "1e12", "--mass", "0.0001", "--v-in", "10", "--alpha", "1"}, &exit_code);
  REQUIRE(exit_code == 0);
  const auto json = nlohmann::json::parse(text);
  CHECK(json["energy_gain_tolerance"].get<double>() == sas::kiosk::kEnergyGainTolerance);
  CHECK(json["measured"]["restitution"].get<double>() <= 1.0 + sas::kiosk::kEnergyGainTolerance);
  CHECK(json["energy_gained"] == false);
}

TEST_CASE("impact command stops at its wall-time cap with exit 1 and answers --help with 0",
          "[kiosk]") {
  int exit_code = -1;
  // Uncapped, this contact (k = 1 N/m at 384 kHz x 1024) runs for hours, so ending at all with
  // exit 1 and the cap's message shows the cap; how long it took is the host's business.
  auto text = Capture(
      {"--fs", "384000", "--oversample", "1024", "--mu", "0", "--k", "1", "--max-wall-s", "0.5"},
      &exit_code);
  CHECK(exit_code == 1);
  CHECK_THAT(text, Catch::Contains("--max-wall-s") && Catch::Contains("stopped after"));
  text = Capture({"--help"}, &exit_code);
  CHECK(exit_code == 0);
  CHECK_THAT(text, Catch::Contains("--mass") && Catch::Contains("--max-wall-s"));
}
