// The contact error budget's measurements (see contact_budget.h).
#include "calibration/contact_budget.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>

#include "surface/height_field.h"
#include "synth/contact.h"
#include "synth/hunt_crossley_closed_form.h"
#include "synth/scene.h"
#include "tools/builtin_profiles.h"

namespace sas::kiosk {
namespace {

constexpr double kFs = 48000.0;
// The hand's push and the penetration of a pen at mid pressure (pen_mapping.h: 2 N and the
// field's relief at full pressure).
constexpr double kPressure = 0.45;
constexpr double kMaxForceN = 2.0;
// The measured span starts after the landing's click (the impact budget covers landings).
constexpr double kSettleS = 0.05;
// The grating is 78 mm long: a stroke stays on it.
constexpr double kPathM = 0.065;
constexpr double kMaxStrokeS = 0.8;

double WidthMm(synth::ProbeStyle style) {
  switch (style) {
    case synth::ProbeStyle::kRub:
      return 4.0;  // a tilted pen (pen_mapping.h: 2 mm and wider rub)
    case synth::ProbeStyle::kRoll:
    case synth::ProbeStyle::kScrape:
    default:
      return 0.3;  // upright: rides the 0.6 mm ridges
  }
}

const surface::HeightField& Grating() {
  static const surface::HeightField field = *MakeBuiltinProfile("grating");
  return field;
}

}  // namespace

double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

const std::vector<double>& TargetSamplesLadder() {
  // Steps of about √2: the cost of a contact is about proportional to its sub-steps.
  static const std::vector<double> ladder = {1, 1.5, 2, 3, 4, 6, 8, 12, 17, 24, 34, 48, 68, 96, 136};
  return ladder;
}

const std::vector<int>& SustainedLadder() {
  static const std::vector<int> ladder = {1, 2, 4, 8, 16};
  return ladder;
}

const std::vector<int>& FixedLadder() {
  static const std::vector<int> ladder = {2, 3, 4, 6, 8, 12, 16};
  return ladder;
}

std::vector<ContactPolicy> PolicyLadder(synth::ContactScheme scheme) {
  std::vector<ContactPolicy> ladder;
  for (const double t : TargetSamplesLadder()) {
    for (const int h : SustainedLadder()) ladder.push_back({scheme, t, h, 0, false});
  }
  // A floor of 1 is no floor (the cap rung above).
  for (const double t : TargetSamplesLadder()) {
    for (const int h : SustainedLadder()) {
      if (h > 1) ladder.push_back({scheme, t, h, 0, true});
    }
  }
  for (const int n : FixedLadder()) ladder.push_back({scheme, 0.0, 0, n});
  return ladder;
}

int LadderIndex(const ContactPolicy& policy) {
  const auto ladder = PolicyLadder(policy.scheme);
  for (std::size_t i = 0; i < ladder.size(); ++i) {
    const auto& r = ladder[i];
    if (policy.oversample > 0 ? r.oversample == policy.oversample
                              : r.oversample == 0 &&
                                    r.target_contact_samples == policy.target_contact_samples &&
                                    r.sustained_substeps == policy.sustained_substeps &&
                                    r.pressed_floor == policy.pressed_floor) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

std::string PolicyName(const ContactPolicy& policy) {
  char text[48];
  if (policy.oversample > 0) {
    std::snprintf(text, sizeof text, "fixed x%d", policy.oversample);
  } else {
    std::snprintf(text, sizeof text, "%g / %d%s", policy.target_contact_samples,
                  policy.sustained_substeps, policy.pressed_floor ? " floor" : "");
  }
  return text;
}

ContactPolicy PolicyOf(const synth::MaterialParams& material) {
  return {material.impact.scheme, material.impact.target_contact_samples,
          material.impact.sustained_substeps, material.impact.oversample,
          material.impact.pressed_floor};
}

synth::MaterialParams WithPolicy(const synth::MaterialParams& material,
                                 const ContactPolicy& policy) {
  synth::MaterialParams m = material;
  m.impact.scheme = policy.scheme;
  m.impact.oversample = policy.oversample;
  m.impact.target_contact_samples = policy.oversample > 0 ? 0.0 : policy.target_contact_samples;
  m.impact.sustained_substeps = policy.oversample > 0 ? 0 : policy.sustained_substeps;
  m.impact.pressed_floor = policy.oversample == 0 && policy.pressed_floor;
  return m;
}

synth::MaterialParams FineReference(const synth::MaterialParams& material) {
  synth::MaterialParams m = material;
  m.impact.scheme = synth::kDefaultContactScheme;
  m.impact.oversample = kReferenceOversample;
  m.impact.target_contact_samples = 0.0;
  m.impact.sustained_substeps = 0;
  m.impact.pressed_floor = false;
  return m;
}

ImpactBudgetFigures MeasureImpactBudget(const synth::MaterialParams& material, int phase_stride) {
  ImpactBudgetFigures figures;
  const auto& im = material.impact;
  const double mass = material.probe.mass_kg;
  for (const double v : {0.03, 0.1, 0.3, 1.0, 3.0}) {
    const double exact =
        synth::HuntCrossleyImpact(mass, im.stiffness, im.dissipation_s_per_m, im.shape_alpha, v)
            .exit_speed_mps;
    const double allowed = v >= synth::kAbsoluteSpeedFloor
                               ? kRestitutionBudget * exact
                               : kRestitutionBudget * synth::kAbsoluteSpeedFloor;
    for (int p = 0; p < 32; p += std::max(phase_stride, 1)) {
      const auto run = synth::SimulateRigidWallImpact(im, mass, v, kFs, (p + 0.5) / 32.0);
      const double error = run.separated ? std::fabs(run.exit_velocity_mps - exact)
                                         : std::numeric_limits<double>::infinity();
      if (v >= synth::kAbsoluteSpeedFloor) {
        figures.worst_relative = std::max(figures.worst_relative, error / exact);
      }
      if (error / allowed > figures.worst_budget_ratio) {
        figures.worst_budget_ratio = error / allowed;
        figures.worst_speed_mps = v;
      }
    }
  }
  return figures;
}

std::string BudgetStroke::Name() const {
  char text[64];
  std::snprintf(text, sizeof text, "%s %.0f mm/s", std::string(synth::ProbeStyleName(style)).c_str(),
                speed_mps * 1e3);
  return text;
}

const std::vector<BudgetStroke>& BudgetStrokes() {
  // Slow, where glass and metal stick and slip (and squeal), and fast, where the probe flies
  // over the ridges and lands on each (the kiosk's grid spans 40–350 mm/s).
  static const std::vector<BudgetStroke> strokes = {
      {synth::ProbeStyle::kScrape, 0.04}, {synth::ProbeStyle::kScrape, 0.2},
      {synth::ProbeStyle::kRub, 0.04},    {synth::ProbeStyle::kRub, 0.2},
      {synth::ProbeStyle::kRoll, 0.04},   {synth::ProbeStyle::kRoll, 0.2},
  };
  return strokes;
}

StrokeRender RenderBudgetStroke(const synth::MaterialParams& material, const BudgetStroke& stroke,
                                int reps, double start_offset_m, bool count_substeps) {
  const auto& field = Grating();
  const double relief = surface::ReliefM(field);
  synth::ProbeCommand down;
  down.tip_down = true;
  down.x_m = 0.006 + start_offset_m;
  down.y_m = 0.5 * field.height() * field.pitch_m();
  down.velocity_mps = stroke.speed_mps;
  down.normal_force_n = kPressure * kMaxForceN;
  down.penetration_m = kPressure * relief;
  down.width_mm = WidthMm(stroke.style);
  down.style = stroke.style;
  down.landing_speed_mps = 0.1;
  const double duration = std::min(kMaxStrokeS, kPathM / stroke.speed_mps);
  const long frames = static_cast<long>(duration * kFs);
  const long settle = static_cast<long>(kSettleS * kFs);

  synth::Scene scene;
  scene.Init(kFs);
  synth::OutputParams output;  // unit gains: far below the limiters, levels are linear
  scene.Prepare(material, output, field.View());
  StrokeRender result;
  std::vector<float> out(2 * static_cast<std::size_t>(frames));
  auto render = [&] {
    scene.Reset();
    for (long start = 0; start < frames; start += 128) {
      const int n = static_cast<int>(std::min<long>(128, frames - start));
      scene.Process(start == 0 ? &down : nullptr, start == 0 ? 1 : 0,
                    out.data() + 2 * static_cast<std::size_t>(start), n);
    }
  };
  auto measure = [&] {
    double sound = 0.0, haptic = 0.0;
    for (long f = settle; f < frames; ++f) {
      const double s = out[2 * static_cast<std::size_t>(f)];
      const double h = out[2 * static_cast<std::size_t>(f) + 1];
      sound += s * s;
      haptic += h * h;
    }
    result.sound_energy = sound;
    result.haptic_energy = haptic;
  };
  if (count_substeps) {
    scene.Reset();
    for (long f = 0; f < frames; ++f) {
      scene.Process(f == 0 ? &down : nullptr, f == 0 ? 1 : 0,
                    out.data() + 2 * static_cast<std::size_t>(f), 1);
      const auto state = scene.probe_state();
      result.substeps += state.active ? state.substeps : 0;
    }
    result.samples = static_cast<double>(frames);
  }
  if (reps <= 1) {
    const double t0 = ThreadCpuSeconds();
    render();
    result.cpu_s = ThreadCpuSeconds() - t0;
    measure();
    return result;
  }
  render();  // warm-up
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < reps; ++r) {
    const double t0 = ThreadCpuSeconds();
    render();
    best = std::min(best, ThreadCpuSeconds() - t0);
  }
  result.cpu_s = best;
  measure();
  return result;
}

StrokeLevels MeasureStrokeLevels(const synth::MaterialParams& material,
                                 const BudgetStroke& stroke) {
  std::vector<double> sound, haptic;
  auto run = [&](int i) {
    auto m = material;
    if (!m.resonator.modes.empty()) m.resonator.modes[0].mass_kg *= 1.0 + 1e-12 * i;
    auto perturbed = stroke;
    perturbed.speed_mps *= 1.0 + 1e-6 * i;
    const auto r = RenderBudgetStroke(m, perturbed, 1, 1e-8 * i);
    auto db = [](double e) {
      return e > 0.0 ? 10.0 * std::log10(e) : -std::numeric_limits<double>::infinity();
    };
    sound.push_back(db(r.sound_energy));
    haptic.push_back(db(r.haptic_energy));
  };
  auto spread = [](const std::vector<double>& v) {
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    return *hi - *lo;
  };
  for (int i = 0; i < kProbeMembers; ++i) run(i);
  StrokeLevels levels;
  if (!(spread(sound) <= kDeterministicDb && spread(haptic) <= kDeterministicDb)) {
    for (int i = kProbeMembers; i < kEnsembleMembers; ++i) run(i);
  }
  levels.members = static_cast<int>(sound.size());
  auto stats = [&](const std::vector<double>& v, double& mean, double& sd) {
    mean = 0.0;
    for (const double x : v) mean += x;
    mean /= static_cast<double>(v.size());
    if (levels.members <= kProbeMembers) {
      sd = 0.0;  // deterministic: the probe members agree within kDeterministicDb
      return;
    }
    double ss = 0.0;
    for (const double x : v) ss += (x - mean) * (x - mean);
    sd = std::sqrt(ss / static_cast<double>(v.size() - 1));
  };
  stats(sound, levels.sound_db, levels.sound_sd);
  stats(haptic, levels.haptic_db, levels.haptic_sd);
  return levels;
}

StrokeBudgetFigures CompareLevels(const StrokeLevels& run, const StrokeLevels& reference) {
  auto se = [](double sd_a, int n_a, double sd_b, int n_b) {
    return std::sqrt(sd_a * sd_a / std::max(n_a, 1) + sd_b * sd_b / std::max(n_b, 1));
  };
  auto diff = [](double a, double b) {
    return std::isfinite(a) && std::isfinite(b) ? a - b
           : a == b                             ? 0.0
                                                : std::numeric_limits<double>::infinity();
  };
  return {diff(run.sound_db, reference.sound_db), diff(run.haptic_db, reference.haptic_db),
          se(run.sound_sd, run.members, reference.sound_sd, reference.members),
          se(run.haptic_sd, run.members, reference.haptic_sd, reference.members)};
}

StrokeReference MeasureStrokeReference(const synth::MaterialParams& material,
                                       const BudgetStroke& stroke, bool convergence) {
  StrokeReference ref;
  const auto fine = FineReference(material);
  ref.fine = MeasureStrokeLevels(fine, stroke);
  if (!convergence) return ref;
  auto coarser = fine;
  coarser.impact.oversample = kConvergenceOversample;
  ref.convergence = CompareLevels(MeasureStrokeLevels(coarser, stroke), ref.fine);
  coarser.impact.oversample = 16;
  ref.old_reference = CompareLevels(MeasureStrokeLevels(coarser, stroke), ref.fine);
  return ref;
}

bool MeetsLevelBudget(const StrokeBudgetFigures& f) {
  return std::fabs(f.sound_db) <= kLevelBudgetDb + f.sound_se &&
         std::fabs(f.haptic_db) <= kLevelBudgetDb + f.haptic_se;
}

bool NoFurtherOff(const StrokeBudgetFigures& f, const StrokeBudgetFigures& baseline) {
  auto allowed = [](double base_db, double base_se) {
    return std::fabs(base_db) <= kLevelBudgetDb + base_se ? kLevelBudgetDb : std::fabs(base_db);
  };
  return std::fabs(f.sound_db) <= allowed(baseline.sound_db, baseline.sound_se) + f.sound_se &&
         std::fabs(f.haptic_db) <= allowed(baseline.haptic_db, baseline.haptic_se) + f.haptic_se;
}

}  // namespace sas::kiosk
