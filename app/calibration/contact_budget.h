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
//            cannot tell. Level, not waveform, and over an ensemble: a stroke that sticks and slips,
//            or flies over the ridges and lands on each, is chaotic (a 1e-12 change of a modal mass
//            a 1e-6 change of speed or a 10 nm shift of its start moves its waveform by O(1) and its level by up to a few
//            dB), so its level is a random variable and the budget compares ensemble means:
//            |mean(policy) - mean(reference)| <= kLevelBudgetDb + the standard error of that
//            difference. A stroke whose perturbed runs agree is deterministic and compared as one.
// Offline only (the bench, the tests).

#include <string>
#include <vector>

#include "synth/material_params.h"
#include "synth/probe_command.h"

namespace sas::kiosk {

inline constexpr double kRestitutionBudget = 1e-4;
inline constexpr double kLevelBudgetDb = 0.5;
// ×16 was not converged on metal's scrapes (ensemble means moved by ~1 dB from ×16 to ×32 and
// ×64, docs/contact-budget.md), ×64 moves by less than the budget from ×32.
inline constexpr int kReferenceOversample = 64;
// The coarser reference whose distance from kReferenceOversample the docs show (convergence).
inline constexpr int kConvergenceOversample = 32;
// Ensemble members of a chaotic stroke (a deterministic one is seen as such from the first
// kProbeMembers, which agree to kDeterministicDb).
inline constexpr int kEnsembleMembers = 16;
inline constexpr int kProbeMembers = 4;
inline constexpr double kDeterministicDb = 1e-3;

// The automatic setting's policy (ImpactParams: scheme, target_contact_samples,
// sustained_substeps, pressed_floor), or a fixed sub-step count on every contact sample
// (oversample > 0).
struct ContactPolicy {
  synth::ContactScheme scheme = synth::kDefaultContactScheme;
  double target_contact_samples = 0.0;
  int sustained_substeps = 0;
  int oversample = 0;
  bool pressed_floor = false;
};
// The rungs the bench tries, coarsest first: every (sub-steps per contact, held) pair with the
// held count a cap, then the same pairs with it also a floor while friction acts (a rub whose
// friction needs sub-steps at walking closing speeds gets them there: a cap does not raise a
// slowly closing contact's count), then the fixed counts on every contact sample.
const std::vector<double>& TargetSamplesLadder();
const std::vector<int>& SustainedLadder();
const std::vector<int>& FixedLadder();
// The whole ladder of one scheme, in the order tried.
std::vector<ContactPolicy> PolicyLadder(synth::ContactScheme scheme);
// The index of `policy` in PolicyLadder(policy.scheme), or -1.
int LadderIndex(const ContactPolicy& policy);
std::string PolicyName(const ContactPolicy& policy);  // "136 / 4", "34 / 8 floor" or "fixed x4"
ContactPolicy PolicyOf(const synth::MaterialParams& material);

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
  // Contact sub-steps summed over every sample of the render (with `count_substeps`: a second,
  // frame-by-frame pass, the same output), and the samples: the work a policy asks for, which,
  // unlike CPU time, does not move with the machine's load.
  double substeps = 0.0;
  double samples = 0.0;
};
StrokeRender RenderBudgetStroke(const synth::MaterialParams& material, const BudgetStroke& stroke,
                                int reps = 1, double start_offset_m = 0.0,
                                bool count_substeps = false);

// The levels (dB of the energies) of a stroke's ensemble: member i starts i · 10 nm further on,
// runs at speed × (1 + i · 1e-6) and has the first modal mass × (1 + i · 1e-12) (a wide rub
// averages a shifted start away and shrugs off the mass, but a squealing one changes its level
// by ~1 dB with a 1e-6 change of speed; a deterministic stroke's level moves by ~1e-5 dB). kProbeMembers first; the rest of kEnsembleMembers
// only if those disagree (a chaotic stroke).
struct StrokeLevels {
  double sound_db = 0.0, haptic_db = 0.0;  // ensemble means
  double sound_sd = 0.0, haptic_sd = 0.0;  // standard deviations of one member
  int members = 0;
  bool Chaotic() const { return members > kProbeMembers; }
};
StrokeLevels MeasureStrokeLevels(const synth::MaterialParams& material, const BudgetStroke& stroke);

struct StrokeBudgetFigures {
  double sound_db = 0.0;   // mean level - reference mean level, dB
  double haptic_db = 0.0;
  double sound_se = 0.0;   // standard error of that difference (0: both deterministic)
  double haptic_se = 0.0;
};
StrokeBudgetFigures CompareLevels(const StrokeLevels& run, const StrokeLevels& reference);

// The fine-step reference of one budget stroke (kReferenceOversample), and the same at
// kConvergenceOversample: how far the reference still moves with its step.
struct StrokeReference {
  StrokeLevels fine;
  StrokeBudgetFigures convergence;  // kConvergenceOversample against kReferenceOversample
  StrokeBudgetFigures old_reference;  // ×16 (the reference before ×64) against it
};
// With `convergence` false (the test), only `fine` is measured.
StrokeReference MeasureStrokeReference(const synth::MaterialParams& material,
                                       const BudgetStroke& stroke, bool convergence = false);
// The budget's test of one stroke: |difference of means| <= kLevelBudgetDb + its standard error,
// sound and vibration.
bool MeetsLevelBudget(const StrokeBudgetFigures& f);
// Whether `f` is as close to the reference as `baseline`, channel by channel: within the budget
// where the baseline is, and no further off (plus f's standard error) where it is not.
bool NoFurtherOff(const StrokeBudgetFigures& f, const StrokeBudgetFigures& baseline);

double ThreadCpuSeconds();

}  // namespace sas::kiosk
