// The `impact` calibration command (see impact_command.h).
#include "tools/impact_command.h"

#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "files/contact_scheme_names.h"
#include "synth/contact.h"
#include "synth/hunt_crossley_closed_form.h"
#include "tools/command_line.h"

namespace sas::kiosk {
namespace {

// A value the closed form does not define (inf, nan) is written as null: JSON has no inf.
nlohmann::json Number(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json RelativeError(double measured, double exact) {
  if (!std::isfinite(measured) || !std::isfinite(exact)) return nullptr;
  return exact == 0.0 ? std::fabs(measured) : std::fabs(measured - exact) / std::fabs(exact);
}

}  // namespace

std::string ImpactReportJson(const ImpactOptions& options) {
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(options.max_wall_s));
  const auto run = synth::SimulateRigidWallImpact(
      options.mass_kg, options.k, options.mu, options.alpha, options.v_in_mps,
      options.sample_rate_hz, options.scheme, options.oversample, options.phase,
      [&] { return Clock::now() < deadline; });
  if (run.stopped) {
    std::ostringstream message;
    message << "stopped after " << options.max_wall_s << " s of wall time (--max-wall-s) at "
            << options.sample_rate_hz << " Hz x " << run.oversample
            << " sub-steps; lower --fs or --oversample, or raise --max-wall-s";
    throw std::runtime_error(message.str());
  }
  const auto exact = synth::HuntCrossleyImpact(options.mass_kg, options.k, options.mu,
                                               options.alpha, options.v_in_mps);
  const double exact_samples = exact.contact_time_s * options.sample_rate_hz;
  nlohmann::ordered_json json;
  json["input"] = {{"mass_kg", options.mass_kg},
                   {"k", options.k},
                   {"mu_s_per_m", options.mu},
                   {"alpha", options.alpha},
                   {"v_in_mps", options.v_in_mps},
                   {"fs_hz", options.sample_rate_hz},
                   {"scheme", ContactSchemeName(options.scheme)},
                   {"oversample", run.oversample},
                   {"phase", options.phase}};
  json["separated"] = run.separated;
  json["measured"] = {{"exit_velocity_mps", Number(run.exit_velocity_mps)},
                      {"restitution", Number(run.exit_velocity_mps / options.v_in_mps)},
                      {"max_compression_m", Number(run.max_compression_m)},
                      {"contact_time_s", Number(run.contact_time_s)},
                      {"samples_per_contact", Number(run.samples_per_contact)}};
  json["closed_form"] = {{"exit_velocity_mps", Number(exact.exit_speed_mps)},
                         {"restitution", Number(exact.restitution)},
                         {"max_compression_m", Number(exact.max_compression_m)},
                         {"contact_time_s", Number(exact.contact_time_s)},
                         {"samples_per_contact", Number(exact_samples)}};
  json["relative_error"] = {
      {"exit_velocity", RelativeError(run.exit_velocity_mps, exact.exit_speed_mps)},
      {"max_compression", RelativeError(run.max_compression_m, exact.max_compression_m)},
      {"contact_time", RelativeError(run.contact_time_s, exact.contact_time_s)}};
  json["energy_gain_tolerance"] = kEnergyGainTolerance;
  json["energy_gained"] = run.exit_velocity_mps > options.v_in_mps * (1.0 + kEnergyGainTolerance);
  // Full precision (nlohmann's default: the shortest text that reads back to the same double).
  return json.dump(2) + "\n";
}

int RunImpactCommand(const std::vector<std::string>& args, std::FILE* out, std::FILE* err) {
  ImpactOptions options;
  CLI::App app(
      "Simulates one probe impact on a rigid wall through the engine's contact code and "
      "prints JSON next to the Hunt-Crossley closed form.",
      "impact");
  AddNumberOption(app, "--mass", options.mass_kg, 1e-4, 1.0, "probe mass, kg (default 0.01)");
  AddNumberOption(app, "--k", options.k, 1.0, 1e12, "contact stiffness, N/m^alpha (default 1e8)");
  AddNumberOption(app, "--mu", options.mu, 0.0, 100.0, "Hunt-Crossley damping, s/m (default 0.5)");
  AddNumberOption(app, "--alpha", options.alpha, 1.0, 4.0, "contact exponent (default 1.5)");
  AddNumberOption(app, "--v-in", options.v_in_mps, 1e-4, 10.0, "impact speed, m/s (default 1)");
  AddNumberOption(app, "--fs", options.sample_rate_hz, 8000.0, 384000.0,
                  "sample rate, Hz (default 48000)");
  app.add_option("--oversample", options.oversample,
                 "sub-steps per sample, 0 = the engine's choice (default 0)")
      ->check(CLI::Range(0, 1024));
  AddNumberOption(app, "--phase", options.phase, 0.0, 0.999999,
                  "sub-sample onset phase (default 0)");
  std::string scheme = ContactSchemeName(options.scheme);
  app.add_option("--scheme", scheme, "contact scheme: " + ContactSchemeChoices())
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            synth::ContactScheme parsed{};
            return ParseContactScheme(text, &parsed)
                       ? ""
                       : "unknown scheme '" + text + "' (one of " + ContactSchemeChoices() + ")";
          },
          "SCHEME"));
  AddNumberOption(app, "--max-wall-s", options.max_wall_s, 0.1, 3600.0,
                  "stop (exit 1) after this much wall time (default 30)");
  if (const int code = ParseCommandLine(app, args, out, err); code >= 0) return code;
  ParseContactScheme(scheme, &options.scheme);
  try {
    std::fputs(ImpactReportJson(options).c_str(), out);
  } catch (const std::exception& e) {
    std::fprintf(err, "sketch-a-scratch impact: %s\n", e.what());
    return kExitRuntimeError;
  }
  return kExitOk;
}

}  // namespace sas::kiosk
