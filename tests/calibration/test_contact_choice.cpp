// The contact policies the kiosk takes from its benchmark (files/contact_choice.h) against the
// error budget (calibration/contact_budget.h): every shipped material with a row in the table
// meets it, impacts against the Lambert-W closed form and strokes against the fine-step
// reference; and the budget is a real bar: a first-order scheme at the same sub-steps, or one rung
// coarser where the ladder has one, misses it.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "calibration/contact_budget.h"
#include "files/contact_choice.h"
#include "files/material_file.h"

using namespace sas;

namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr int kPhaseStride = 8;  // ~10x slower under the sanitizer
#else
constexpr int kPhaseStride = 2;
#endif

std::vector<kiosk::Material> ShippedMaterials() {
  for (const auto& dir : kiosk::MaterialSearchDirs("")) {
    if (!kiosk::ListMaterialNames(dir).empty()) return kiosk::LoadMaterialDirectory(dir);
  }
  return {};
}

// Whether `params` meets the budget on every budget stroke; the failures in `why`.
bool StrokesMeet(const synth::MaterialParams& params,
                 const std::vector<kiosk::StrokeReference>& references, std::string* why) {
  bool ok = true;
  for (std::size_t i = 0; i < references.size(); ++i) {
    const auto& stroke = kiosk::BudgetStrokes()[i];
    const auto f = kiosk::CompareLevels(kiosk::RenderBudgetStroke(params, stroke),
                                        references[i].fine);
    if (!references[i].Meets(f)) {
      ok = false;
      *why += stroke.Name() + ": sound " + std::to_string(f.sound_db) + " dB, vibration " +
              std::to_string(f.haptic_db) + " dB; ";
    }
  }
  return ok;
}

}  // namespace

TEST_CASE(
    "contact choice: every table row was measured on the parameters its shipped material file "
    "holds",
    "[dsp]") {
  const auto materials = ShippedMaterials();
  REQUIRE(!materials.empty());
  for (const auto& row : kiosk::ContactChoices()) {
    INFO(row.material);
    bool found = false;
    for (const auto& m : materials) {
      if (m.name == row.material) {
        found = true;
        CHECK(kiosk::FindContactChoice(m.name, m.params) == &row);
        CHECK(m.contact_from_benchmark);
      }
    }
    CHECK(found);
  }
  for (const auto& m : materials) {
    if (!m.contact_from_benchmark) WARN(m.name << ": no policy met the budget; built-in policy");
  }
}

TEST_CASE(
    "contact choice: each chosen policy meets the restitution and stroke-level budget against the "
    "closed form and the fine-step reference and a coarser one does not",
    "[dsp][render]") {
  int checked = 0;
  for (const auto& m : ShippedMaterials()) {
    if (!m.contact_from_benchmark) continue;
    INFO(m.name << ": " << kiosk::ContactPolicyText(m.params, true));
    ++checked;
    const auto impact = kiosk::MeasureImpactBudget(m.params, kPhaseStride);
    INFO("worst impact error " << impact.worst_relative << " relative, " << impact.worst_budget_ratio
                               << "x the budget at " << impact.worst_speed_mps << " m/s");
    CHECK(impact.Meets());
    std::vector<kiosk::StrokeReference> references;
    for (const auto& stroke : kiosk::BudgetStrokes()) {
      references.push_back(kiosk::MeasureStrokeReference(m.params, stroke));
    }
    std::string why;
    CHECK(StrokesMeet(m.params, references, &why));
    INFO(why);

    // Coarser: the first-order explicit scheme at the same sub-steps misses the impact budget.
    kiosk::ContactPolicy policy{m.params.impact.scheme, m.params.impact.target_contact_samples,
                                m.params.impact.sustained_substeps};
    auto explicit_policy = policy;
    explicit_policy.scheme = synth::ContactScheme::kExplicitPassive;
    CHECK_FALSE(
        kiosk::MeasureImpactBudget(kiosk::WithPolicy(m.params, explicit_policy), kPhaseStride)
            .Meets());
    // One rung down the ladder (fewer sub-steps per contact, or fewer held), where there is one.
    const auto& targets = kiosk::TargetSamplesLadder();
    const auto& held = kiosk::SustainedLadder();
    for (std::size_t t = 1; t < targets.size(); ++t) {
      if (targets[t] != policy.target_contact_samples) continue;
      auto coarser = policy;
      coarser.target_contact_samples = targets[t - 1];
      const auto params = kiosk::WithPolicy(m.params, coarser);
      std::string coarser_why;
      CHECK_FALSE((kiosk::MeasureImpactBudget(params, kPhaseStride).Meets() &&
                   StrokesMeet(params, references, &coarser_why)));
    }
    for (std::size_t h = 1; h < held.size(); ++h) {
      if (held[h] != policy.sustained_substeps) continue;
      auto coarser = policy;
      coarser.sustained_substeps = held[h - 1];
      std::string coarser_why;
      CHECK_FALSE(StrokesMeet(kiosk::WithPolicy(m.params, coarser), references, &coarser_why));
    }
  }
  CHECK(checked > 0);
}
