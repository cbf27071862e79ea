// The benchmark's contact choices (see contact_choice.h).
#include "files/contact_choice.h"

#include <cstdio>

#include "files/contact_scheme_names.h"
#include "synth/contact.h"

namespace sas::kiosk {
namespace {

using synth::ContactScheme;
constexpr ContactChoice kChoices[] = {
#include "files/contact_choices.inc"
};

}  // namespace

std::span<const ContactChoice> ContactChoices() {
  return kChoices;
}

const ContactChoice* FindContactChoice(std::string_view name, const synth::MaterialParams& params) {
  for (const auto& row : kChoices) {
    // Exact: the table prints every figure round-trip (%.17g), and a row measured on other
    // parameters says nothing about these.
    if (name == row.material && params.probe.mass_kg == row.probe_mass_kg &&
        params.impact.stiffness == row.stiffness &&
        params.impact.dissipation_s_per_m == row.dissipation_s_per_m &&
        params.impact.shape_alpha == row.shape_alpha) {
      return &row;
    }
  }
  return nullptr;
}

const ContactChoice* ApplyContactChoice(std::string_view name, synth::MaterialParams& params) {
  const ContactChoice* row = FindContactChoice(name, params);
  params.impact.oversample = 0;
  if (row == nullptr) {
    params.impact.scheme = synth::kDefaultContactScheme;
    params.impact.target_contact_samples = 0.0;
    params.impact.sustained_substeps = 0;
    params.impact.pressed_floor = false;
    return nullptr;
  }
  params.impact.scheme = row->scheme;
  params.impact.oversample = row->oversample;
  params.impact.target_contact_samples = row->target_contact_samples;
  params.impact.sustained_substeps = row->sustained_substeps;
  params.impact.pressed_floor = row->pressed_floor;
  return row;
}

std::string ContactPolicyText(const synth::MaterialParams& params, bool from_benchmark,
                              bool budget_met) {
  const char* chosen = !from_benchmark ? nullptr
                       : budget_met
                           ? "chosen by contact_bench"
                           : "chosen by contact_bench, as close as the built-in (budget not met)";
  const auto& impact = params.impact;
  char text[256];
  if (!impact.enabled) {
    std::snprintf(text, sizeof text, "%s, friction only (no impact), one sub-step",
                  ContactSchemeName(impact.scheme));
    return text;
  }
  const int most = synth::ChooseContactOversample(impact, params.probe.mass_kg, 48000.0);
  if (impact.oversample > 0) {
    std::snprintf(text, sizeof text, "%s, %d sub-steps per contact sample (fixed), %s",
                  ContactSchemeName(impact.scheme), most,
                  from_benchmark ? chosen : "set by the material file");
    return text;
  }
  std::snprintf(text, sizeof text,
                "%s, adaptive 1-%d sub-steps at 48 kHz (%g per contact at 1 m/s, %d held "
                "pressed%s), %s",
                ContactSchemeName(impact.scheme), most, synth::ContactTargetSamples(impact),
                synth::SustainedContactSubsteps(impact),
                impact.pressed_floor ? ", at least that while rubbing" : "",
                from_benchmark ? chosen : "built-in (not in the benchmark's table)");
  return text;
}

}  // namespace sas::kiosk
