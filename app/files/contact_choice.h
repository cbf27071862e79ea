#pragma once
// The contact policy the kiosk takes from its own benchmark: contact_bench --choose measures, for
// every shipped material, the cheapest scheme and sub-step policy that meet the kiosk's error
// budget (calibration/contact_budget.h, docs/contact-budget.md) and writes them to
// contact_choices.inc, compiled in here. A material file asking for `scheme = "benchmark"` gets its
// row, if the row was measured on the parameters the file holds (probe mass, k, μ, α); otherwise
// (an edited or a new material) the default scheme with its built-in policy, and the description
// says so.

#include <span>
#include <string>
#include <string_view>

#include "synth/material_params.h"

namespace sas::kiosk {

inline constexpr std::string_view kBenchmarkSchemeName = "benchmark";

struct ContactChoice {
  const char* material;
  // The parameters the row was measured on.
  double probe_mass_kg, stiffness, dissipation_s_per_m, shape_alpha;
  synth::ContactScheme scheme;
  double target_contact_samples;
  int sustained_substeps;
  int oversample;  // > 0: this many sub-steps on every contact sample (then the two above are 0)
  bool pressed_floor;  // the held count is also a pressed, rubbing contact's fewest
  // false: no policy met the error budget within the tool's cost ceiling, and this one is the
  // first as close to the fine-step reference as the built-in policy (docs/contact-budget.md).
  bool budget_met;
};
std::span<const ContactChoice> ContactChoices();

// The row for `name` measured on these parameters, or null.
const ContactChoice* FindContactChoice(std::string_view name, const synth::MaterialParams& params);
// Sets params' scheme and policy from the row (automatic oversampling) and returns the row; null
// (and the default scheme with its built-in policy) when there is none.
const ContactChoice* ApplyContactChoice(std::string_view name, synth::MaterialParams& params);

// One line naming the contact scheme and sub-steps a material runs, e.g. "discrete_gradient,
// adaptive 1-4 sub-steps (12 per contact at 1 m/s, 4 held), chosen by contact_bench"; with
// `budget_met` false, "... chosen by contact_bench, as close as the built-in (budget not met)".
std::string ContactPolicyText(const synth::MaterialParams& params, bool from_benchmark,
                              bool budget_met = true);

}  // namespace sas::kiosk
