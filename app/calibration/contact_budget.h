#pragma once
// The kiosk's contact error budget, and the measurements that check a contact policy (scheme +
// sub-step policy of the automatic oversampling) against it. contact_bench --choose runs them over
// a ladder of policies for every shipped material and writes the cheapest that meets the budget
// to app/files/contact_choices.inc, which the material loader applies; the calibration test runs
// them on the committed choices (they must meet the budget, and one rung coarser must not).
//
// The budget (docs/contact-budget.md argues it with the figures contact_bench measures):
//   impact   the rebound speed against the Lambert-W closed form (hunt_crossley_closed_form.h),
//            rigid wall, the material's probe mass, k, μ, α, worst of the onset phases: relative
//            kRestitutionBudget from 0.1 m/s, absolute kRestitutionBudget · 0.1 m/s below (the
//            house figure, synth/contact.h's rule).
//   strokes  scrape, rub and roll, slow and fast, on the built-in grating: the level of the sound
//            (channel 1) and of the vibration (channel 2, 40–400 Hz) of the whole stroke within
//            kLevelBudgetDb of the same stroke run at a fine fixed sub-step count (kReferenceOversample
//            on every contact sample, the default scheme): a level error the ear and the hand
//            cannot tell. Level, not waveform: a stroke that sticks and slips is chaotic (a 1e-12
//            change of a modal mass moves its waveform by O(1)), its level is not.
// Offline only (the bench, the tests).

#include <string>
#include <vector>

#include "synth/material_params.h"
#include "synth/probe_command.h"

namespace sas::kiosk {

inline constexpr double kRestitutionBudget = 1e-4;
inline constexpr double kLevelBudgetDb = 0.5;
inline constexpr int kReferenceOversample = 16;

// The automatic setting's policy (ImpactParams: scheme, target_contact_samples,
// sustained_substeps).
struct ContactPolicy {
  synth::ContactScheme scheme = synth::kDefaultContactScheme;
  double target_contact_samples = 0.0;
  int sustained_substeps = 0;
};
// The rungs the bench tries, coarsest first.
const std::vector<double>& TargetSamplesLadder();
const std::vector<int>& SustainedLadder();

synth::MaterialParams WithPolicy(const synth::MaterialParams& material, const ContactPolicy& policy);
// The fine-step reference run of the material (default scheme, kReferenceOversample fixed).
synth::MaterialParams FineReference(const synth::MaterialParams& material);

struct ImpactBudgetFigures {
  double worst_relative = 0.0;  // worst over speeds >= 0.1 m/s of |e - e_exact| / e_exact
  double worst_budget_ratio = 0.0;  // worst error over its budget (<= 1 meets it), all speeds
  double worst_speed_mps = 0.0;     // where that ratio is reached
  bool Meets() const { return worst_budget_ratio <= 1.0; }
};
// Speeds 0.03, 0.1, 0.3, 1 and 3 m/s; onset phases (p + 0.5) / 32 for p = 0, stride, ...
ImpactBudgetFigures MeasureImpactBudget(const synth::MaterialParams& material, int phase_stride);

struct BudgetStroke {
  synth::ProbeStyle style = synth::ProbeStyle::kScrape;
  double speed_mps = 0.04;
  std::string Name() const;  // "scrape 40 mm/s"
};
const std::vector<BudgetStroke>& BudgetStrokes();

struct StrokeRender {
  double sound_energy = 0.0;  // Σ y² over the measured span, channel 1
  double haptic_energy = 0.0;  // channel 2
  double cpu_s = 0.0;          // thread CPU time of the render (best of `reps`, 1 if reps <= 1)
};
StrokeRender RenderBudgetStroke(const synth::MaterialParams& material, const BudgetStroke& stroke,
                                int reps = 1);

struct StrokeBudgetFigures {
  double sound_db = 0.0;   // level - reference level, dB
  double haptic_db = 0.0;
};
StrokeBudgetFigures CompareLevels(const StrokeRender& run, const StrokeRender& reference);

// The fine-step reference of one budget stroke, and its chaos floor: the largest level change
// (sound, vibration) that the reference itself shows when one modal mass moves by ±1e-12. A stroke
// that sticks and slips, or flies over the ridges and lands on each, is chaotic: its level moves
// by up to ~2 dB on that change (docs/contact-budget.md), and a difference within the floor is not
// the scheme's. A policy meets the budget on the stroke when its level is within kLevelBudgetDb
// plus the floor of the reference's.
struct StrokeReference {
  StrokeRender fine;
  StrokeBudgetFigures floor;  // magnitudes
  bool Meets(const StrokeBudgetFigures& f) const;
};
StrokeReference MeasureStrokeReference(const synth::MaterialParams& material,
                                       const BudgetStroke& stroke);

double ThreadCpuSeconds();

}  // namespace sas::kiosk
