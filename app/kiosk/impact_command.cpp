// The `impact` calibration command (see impact_command.h).
#include "kiosk/impact_command.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "kiosk/contact_scheme_names.h"
#include "synth/contact.h"
#include "synth/hunt_crossley_closed_form.h"

namespace sas::kiosk {
namespace {

double ParseNumber(const std::string& option, const std::string& text) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(value)) {
    throw std::invalid_argument(option + ": '" + text + "' is not a number");
  }
  return value;
}

void RequireRange(const std::string& option, double value, double min, double max) {
  if (value < min || value > max) {
    std::ostringstream message;
    message << option << ": " << value << " is out of range [" << min << ", " << max << "]";
    throw std::invalid_argument(message.str());
  }
}

double RelativeError(double measured, double exact) {
  return exact == 0.0 ? std::fabs(measured) : std::fabs(measured - exact) / std::fabs(exact);
}

}  // namespace

ImpactOptions ParseImpactArgs(const std::vector<std::string>& args) {
  ImpactOptions options;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& option = args[i];
    if (i + 1 >= args.size()) throw std::invalid_argument(option + ": missing value");
    const std::string& value = args[++i];
    if (option == "--mass") {
      options.mass_kg = ParseNumber(option, value);
      RequireRange(option, options.mass_kg, 1e-4, 1.0);
    } else if (option == "--k") {
      options.k = ParseNumber(option, value);
      RequireRange(option, options.k, 1.0, 1e12);
    } else if (option == "--mu") {
      options.mu = ParseNumber(option, value);
      RequireRange(option, options.mu, 0.0, 100.0);
    } else if (option == "--alpha") {
      options.alpha = ParseNumber(option, value);
      RequireRange(option, options.alpha, 1.0, 4.0);
    } else if (option == "--v-in") {
      options.v_in_mps = ParseNumber(option, value);
      RequireRange(option, options.v_in_mps, 1e-4, 10.0);
    } else if (option == "--fs") {
      options.sample_rate_hz = ParseNumber(option, value);
      RequireRange(option, options.sample_rate_hz, 8000.0, 384000.0);
    } else if (option == "--oversample") {
      const double n = ParseNumber(option, value);
      RequireRange(option, n, 0.0, 1024.0);
      if (n != std::floor(n)) throw std::invalid_argument(option + ": must be a whole number");
      options.oversample = static_cast<int>(n);
    } else if (option == "--phase") {
      options.phase = ParseNumber(option, value);
      RequireRange(option, options.phase, 0.0, 0.999999);
    } else if (option == "--scheme") {
      if (!ParseContactScheme(value, &options.scheme)) {
        throw std::invalid_argument(option + ": unknown scheme '" + value + "' (one of " +
                                    ContactSchemeChoices() + ")");
      }
    } else {
      throw std::invalid_argument("unknown option " + option);
    }
  }
  return options;
}

std::string ImpactReportJson(const ImpactOptions& options) {
  const auto run = synth::SimulateRigidWallImpact(
      options.mass_kg, options.k, options.mu, options.alpha, options.v_in_mps,
      options.sample_rate_hz, options.scheme, options.oversample, options.phase);
  const auto exact = synth::HuntCrossleyImpact(options.mass_kg, options.k, options.mu,
                                               options.alpha, options.v_in_mps);
  const double exact_samples = exact.contact_time_s * options.sample_rate_hz;
  std::ostringstream json;
  json.precision(10);
  json << "{\n"
       << "  \"input\": {\"mass_kg\": " << options.mass_kg << ", \"k\": " << options.k
       << ", \"mu_s_per_m\": " << options.mu << ", \"alpha\": " << options.alpha
       << ", \"v_in_mps\": " << options.v_in_mps << ", \"fs_hz\": " << options.sample_rate_hz
       << ", \"scheme\": \"" << ContactSchemeName(options.scheme)
       << "\", \"oversample\": " << run.oversample << ", \"phase\": " << options.phase << "},\n"
       << "  \"separated\": " << (run.separated ? "true" : "false") << ",\n"
       << "  \"measured\": {\"exit_velocity_mps\": " << run.exit_velocity_mps
       << ", \"restitution\": " << run.exit_velocity_mps / options.v_in_mps
       << ", \"max_compression_m\": " << run.max_compression_m
       << ", \"contact_time_s\": " << run.contact_time_s
       << ", \"samples_per_contact\": " << run.samples_per_contact << "},\n"
       << "  \"closed_form\": {\"exit_velocity_mps\": " << exact.exit_speed_mps
       << ", \"restitution\": " << exact.restitution
       << ", \"max_compression_m\": " << exact.max_compression_m
       << ", \"contact_time_s\": " << exact.contact_time_s
       << ", \"samples_per_contact\": " << exact_samples << "},\n"
       << "  \"relative_error\": {\"exit_velocity\": "
       << RelativeError(run.exit_velocity_mps, exact.exit_speed_mps)
       << ", \"max_compression\": " << RelativeError(run.max_compression_m, exact.max_compression_m)
       << ", \"contact_time\": " << RelativeError(run.contact_time_s, exact.contact_time_s)
       << "},\n"
       << "  \"energy_gained\": "
       << (run.exit_velocity_mps > options.v_in_mps * (1.0 + 1e-12) ? "true" : "false") << "\n"
       << "}\n";
  return json.str();
}

int RunImpactCommand(const std::vector<std::string>& args, std::FILE* out, std::FILE* err) {
  ImpactOptions options;
  try {
    options = ParseImpactArgs(args);
  } catch (const std::exception& e) {
    std::fprintf(err,
                 "sketch-a-scratch impact: %s\n"
                 "usage: sketch-a-scratch impact --mass KG --k K --mu S_PER_M --alpha A --v-in "
                 "M_PER_S [--fs HZ] [--scheme %s] [--oversample N] [--phase 0..1]\n",
                 e.what(), ContactSchemeChoices().c_str());
    return 2;
  }
  std::fputs(ImpactReportJson(options).c_str(), out);
  return 0;
}

}  // namespace sas::kiosk
