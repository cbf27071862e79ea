// contact_bench --choose (see contact_choice.h). For each shipped material and each implicit or
// non-iterative scheme (the explicit scheme is first order: its 1e-4 needs ~27000 sub-steps per
// contact, synth/contact.h, beyond the 128 cap):
//   impact          the fewest sub-steps per contact at 1 m/s (TargetSamplesLadder) whose rigid-wall
//                   restitution meets the budget at every speed and onset phase;
//   scrape/rub/roll the coarsest (sub-steps per contact, sustained sub-steps) rung, in ladder order,
//                   whose slow and fast strokes both keep their sound and vibration levels within
//                   the budget of the fine-step reference;
// the material's policy is the finest of its styles' (the pen's tilt moves a stroke between styles:
// one policy must serve them all), raised rung by rung until every style meets the budget with it.
// The scheme is then the one whose policy costs least (thread CPU time of all budget strokes, best
// of N). Writes the table (app/files/contact_choices.inc) and docs/contact-budget.md.
#include "contact_choice.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "calibration/contact_budget.h"
#include "contact_bench_common.h"
#include "files/contact_scheme_names.h"
#include "files/material_file.h"
#include "synth/contact.h"

namespace sas::bench {
namespace {

using kiosk::BudgetStroke;
using kiosk::ContactPolicy;
using kiosk::StrokeBudgetFigures;
using kiosk::StrokeRender;

constexpr synth::ContactScheme kCandidates[] = {synth::ContactScheme::kDiscreteGradient,
                                                synth::ContactScheme::kEnergyQuadratised,
                                                synth::ContactScheme::kTrapezoidNewton};
constexpr synth::ProbeStyle kStyles[] = {synth::ProbeStyle::kScrape, synth::ProbeStyle::kRub,
                                         synth::ProbeStyle::kRoll};
// The impact figures use every onset phase the synth's tests use (32 / stride).
constexpr int kPhaseStride = 2;

std::string G17(double v);

struct Rung {
  std::size_t target = 0;  // index into TargetSamplesLadder
  std::size_t held = 0;    // index into SustainedLadder
};

ContactPolicy PolicyAt(synth::ContactScheme scheme, Rung r) {
  return {scheme, kiosk::TargetSamplesLadder()[r.target], kiosk::SustainedLadder()[r.held]};
}

struct StyleResult {
  bool found = false;
  Rung rung;
  std::vector<StrokeBudgetFigures> figures;  // per stroke of the style, at the rung
};

struct SchemeResult {
  synth::ContactScheme scheme{};
  bool found = false;
  std::size_t impact_target = 0;  // the impact rung
  kiosk::ImpactBudgetFigures impact;
  StyleResult styles[3];
  Rung chosen;
  std::vector<StrokeBudgetFigures> chosen_figures;  // every budget stroke at the chosen policy
  double ns_per_sample = 0.0;                       // the budget strokes at the chosen policy
  // One rung coarser than chosen (sub-steps per contact, then held), what fails there.
  std::string coarser_fails;
};

struct MaterialResult {
  kiosk::Material material;
  std::vector<kiosk::StrokeReference> reference;
  std::vector<SchemeResult> schemes;
  int best = -1;
  // Where no policy met the budget: what the built-in policy (which the material then keeps)
  // misses.
  std::string builtin_fails;
};

std::vector<StrokeBudgetFigures> Compare(const synth::MaterialParams& params,
                                         const std::vector<kiosk::StrokeReference>& reference,
                                         const std::vector<std::size_t>& which) {
  std::vector<StrokeBudgetFigures> out;
  for (std::size_t i : which) {
    out.push_back(kiosk::CompareLevels(
        kiosk::RenderBudgetStroke(params, kiosk::BudgetStrokes()[i]), reference[i].fine));
  }
  return out;
}

bool AllMeet(const std::vector<StrokeBudgetFigures>& f,
             const std::vector<kiosk::StrokeReference>& reference,
             const std::vector<std::size_t>& which) {
  for (std::size_t k = 0; k < f.size(); ++k) {
    if (!reference[which[k]].Meets(f[k])) return false;
  }
  return true;
}

std::vector<std::size_t> StrokesOf(synth::ProbeStyle style) {
  std::vector<std::size_t> which;
  for (std::size_t i = 0; i < kiosk::BudgetStrokes().size(); ++i) {
    if (kiosk::BudgetStrokes()[i].style == style) which.push_back(i);
  }
  return which;
}

std::vector<std::size_t> AllStrokes() {
  std::vector<std::size_t> which(kiosk::BudgetStrokes().size());
  for (std::size_t i = 0; i < which.size(); ++i) which[i] = i;
  return which;
}

// Rungs in the order tried: sub-steps per contact from `first_target` up, the held count from
// the least at each.
std::vector<Rung> RungsFrom(std::size_t first_target, std::size_t first_held = 0) {
  std::vector<Rung> rungs;
  for (std::size_t t = first_target; t < kiosk::TargetSamplesLadder().size(); ++t) {
    for (std::size_t h = t == first_target ? first_held : 0; h < kiosk::SustainedLadder().size();
         ++h) {
      rungs.push_back({t, h});
    }
  }
  return rungs;
}

std::string FailText(const std::vector<StrokeBudgetFigures>& f,
                     const std::vector<kiosk::StrokeReference>& reference,
                     const std::vector<std::size_t>& which) {
  std::string text;
  for (std::size_t k = 0; k < f.size(); ++k) {
    if (reference[which[k]].Meets(f[k])) continue;
    char line[160];
    std::snprintf(line, sizeof line, "%s%s: sound %+.2f dB, vibration %+.2f dB",
                  text.empty() ? "" : "; ", kiosk::BudgetStrokes()[which[k]].Name().c_str(),
                  f[k].sound_db, f[k].haptic_db);
    text += line;
  }
  return text;
}

SchemeResult ChooseForScheme(const kiosk::Material& material, synth::ContactScheme scheme,
                             const std::vector<kiosk::StrokeReference>& reference, int reps) {
  SchemeResult r;
  r.scheme = scheme;
  const auto& targets = kiosk::TargetSamplesLadder();
  bool impact_found = false;
  for (std::size_t t = 0; t < targets.size(); ++t) {
    const auto params = kiosk::WithPolicy(material.params, PolicyAt(scheme, {t, 0}));
    r.impact = kiosk::MeasureImpactBudget(params, kPhaseStride);
    if (r.impact.Meets()) {
      r.impact_target = t;
      impact_found = true;
      break;
    }
  }
  std::printf("  %s: impact %s at %g per contact (worst %.1e relative)\n",
              SchemeName(scheme).c_str(), impact_found ? "meets the budget" : "never meets it",
              targets[r.impact_target], r.impact.worst_relative);
  if (!impact_found) return r;

  Rung need{r.impact_target, 0};
  for (std::size_t s = 0; s < 3; ++s) {
    const auto which = StrokesOf(kStyles[s]);
    for (const Rung rung : RungsFrom(0)) {
      const auto params = kiosk::WithPolicy(material.params, PolicyAt(scheme, rung));
      auto figures = Compare(params, reference, which);
      if (AllMeet(figures, reference, which)) {
        r.styles[s] = {true, rung, std::move(figures)};
        break;
      }
    }
    std::printf("    %s: %s\n", std::string(synth::ProbeStyleName(kStyles[s])).c_str(),
                r.styles[s].found
                    ? ("meets the budget at " + std::to_string(targets[r.styles[s].rung.target]) +
                       " per contact, " +
                       std::to_string(kiosk::SustainedLadder()[r.styles[s].rung.held]) + " held")
                          .c_str()
                    : "never meets it");
    if (!r.styles[s].found) return r;
    need.target = std::max(need.target, r.styles[s].rung.target);
    need.held = std::max(need.held, r.styles[s].rung.held);
  }
  // The styles' finest rung serves them all only if the strokes are monotone in it (chaos can
  // break that): check them all together, and climb until they meet.
  for (const Rung rung : RungsFrom(need.target, need.held)) {
    const auto params = kiosk::WithPolicy(material.params, PolicyAt(scheme, rung));
    if (!kiosk::MeasureImpactBudget(params, kPhaseStride).Meets()) continue;
    auto figures = Compare(params, reference, AllStrokes());
    if (AllMeet(figures, reference, AllStrokes())) {
      r.found = true;
      r.chosen = rung;
      r.chosen_figures = std::move(figures);
      break;
    }
  }
  if (!r.found) return r;
  // What one rung coarser misses (the calibration test checks the same).
  auto coarser = [&](Rung rung) {
    const auto params = kiosk::WithPolicy(material.params, PolicyAt(scheme, rung));
    const auto impact = kiosk::MeasureImpactBudget(params, kPhaseStride);
    std::string text;
    if (!impact.Meets()) {
      char line[128];
      std::snprintf(line, sizeof line, "impact at %.2g m/s: %.1fx its budget",
                    impact.worst_speed_mps, impact.worst_budget_ratio);
      text = line;
    }
    const auto all = AllStrokes();
    const std::string strokes = FailText(Compare(params, reference, all), reference, all);
    if (!strokes.empty()) text += (text.empty() ? "" : "; ") + strokes;
    return text.empty() ? std::string("nothing (chaos: see the floor)") : text;
  };
  if (r.chosen.target > 0) {
    r.coarser_fails += G17(targets[r.chosen.target - 1]) +
                       " per contact: " + coarser({r.chosen.target - 1, r.chosen.held});
  }
  if (r.chosen.held > 0) {
    r.coarser_fails += std::string(r.coarser_fails.empty() ? "" : " | ") +
                       std::to_string(kiosk::SustainedLadder()[r.chosen.held - 1]) +
                       " held: " + coarser({r.chosen.target, r.chosen.held - 1});
  }
  // Cost: every budget stroke at the chosen policy.
  const auto params = kiosk::WithPolicy(material.params, PolicyAt(scheme, r.chosen));
  double seconds = 0.0, frames = 0.0;
  for (const auto& stroke : kiosk::BudgetStrokes()) {
    const auto run = kiosk::RenderBudgetStroke(params, stroke, reps);
    seconds += run.cpu_s;
    frames += std::min(0.8, 0.065 / stroke.speed_mps) * kFs;
  }
  r.ns_per_sample = seconds * 1e9 / frames;
  std::printf("    all styles: %g per contact, %d held, %.0f ns per sample\n",
              targets[r.chosen.target], kiosk::SustainedLadder()[r.chosen.held], r.ns_per_sample);
  return r;
}

std::string G17(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

std::string SchemeEnum(synth::ContactScheme s) {
  switch (s) {
    case synth::ContactScheme::kExplicitPassive:
      return "ContactScheme::kExplicitPassive";
    case synth::ContactScheme::kTrapezoidNewton:
      return "ContactScheme::kTrapezoidNewton";
    case synth::ContactScheme::kEnergyQuadratised:
      return "ContactScheme::kEnergyQuadratised";
    case synth::ContactScheme::kDiscreteGradient:
    default:
      return "ContactScheme::kDiscreteGradient";
  }
}

void WriteTable(const std::string& path, const std::vector<MaterialResult>& results) {
  std::ostringstream out;
  out << "// Written by contact_bench --choose (tests/bench/contact_choice.cpp); do not edit. "
         "Regenerate:\n// cmake --build build --target regenerate_contact_choices. The figures "
         "behind each row: docs/contact-budget.md.\n"
         "// {material, probe mass kg, k, mu, alpha, scheme, sub-steps per contact at 1 m/s, "
         "held pressed}\n";
  for (const auto& m : results) {
    if (m.best < 0) continue;
    const auto& s = m.schemes[static_cast<std::size_t>(m.best)];
    const auto& p = m.material.params;
    out << "{\"" << m.material.name << "\", " << G17(p.probe.mass_kg) << ", "
        << G17(p.impact.stiffness) << ", " << G17(p.impact.dissipation_s_per_m) << ", "
        << G17(p.impact.shape_alpha) << ", " << SchemeEnum(s.scheme) << ", "
        << G17(kiosk::TargetSamplesLadder()[s.chosen.target]) << ", "
        << kiosk::SustainedLadder()[s.chosen.held] << "},\n";
  }
  std::ofstream(path) << out.str();
  std::printf("wrote %s\n", path.c_str());
}

std::string Fixed(double v, int digits) {
  char text[32];
  std::snprintf(text, sizeof text, "%+.*f", digits, v);
  return text;
}

std::string Markdown(const std::vector<MaterialResult>& results, int reps) {
  std::ostringstream md;
  const auto& strokes = kiosk::BudgetStrokes();
  md << "# The contact error budget and the scheme each material runs\n\n"
        "Written by `contact_bench --choose` (tests/bench/contact_choice.cpp, the measurements in "
        "app/calibration/contact_budget.cpp); do not edit. The table it chose from these figures "
        "is app/files/contact_choices.inc, which the material loader applies to every material file "
        "saying `scheme = \"benchmark\"`.\n\n"
        "## The budget\n\n"
     << "- **Impact**: rebound speed within " << Sci(kiosk::kRestitutionBudget)
     << " (relative) of the Lambert-W closed form from 0.1 m/s, within "
     << Sci(kiosk::kRestitutionBudget * synth::kAbsoluteSpeedFloor)
     << " m/s below, rigid wall, the material's probe, worst of 16 onset phases at 0.03, 0.1, 0.3, "
        "1 and 3 m/s.\n"
     << "- **Strokes**: the sound's and the vibration's level (energy of channel 1 and of "
        "channel 2, 40-400 Hz, over the stroke after its first 50 ms) within ±"
     << kiosk::kLevelBudgetDb << " dB of the same stroke run with the default scheme at ×"
     << kiosk::kReferenceOversample
     << " sub-steps on every contact sample (the fine-step reference). Strokes: scrape (0.3 mm), "
        "rub (4 mm) and roll, each at 40 and 200 mm/s, 0.9 N, on the built-in grating.\n\n";
  // Why these figures: what an error of the budget's size does to what the visitor hears and
  // feels, computed from the budget's own constants and the measured errors.
  double worst_chosen = 0.0;
  for (const auto& m : results) {
    if (m.best >= 0) {
      worst_chosen = std::max(worst_chosen,
                              m.schemes[static_cast<std::size_t>(m.best)].impact.worst_relative);
    }
  }
  const double eps = kiosk::kRestitutionBudget;
  char why[2400];
  std::snprintf(
      why, sizeof why,
      "## Why this budget\n\n"
      "- An impact's sound and vibration are the resonator's answer to the impulse the contact "
      "gives it, (1 + e) m v for a rebound of restitution e. A relative error ε in the rebound "
      "speed moves that impulse by ε e / (1 + e) < ε / 2, so the level of the click by at most "
      "20 log10(1 + ε/2): %.1e dB at the budget's ε = %.0e, %.1e dB at the worst error the chosen "
      "policies make (%.1e). The smallest level change listeners detect in a broadband sound is "
      "about 0.4-0.5 dB (Miller, \"Sensitivity to changes in the intensity of white noise\", "
      "JASA 19, 1947); the hand's, for vibration, 1-2 dB (Gescheider, Bolanowski, Verrillo, "
      "Arpajian & Ryan, JASA 87, 1990). The restitution budget is the project's figure for impact "
      "restitution and %.0f times inside the ear's step.\n"
      "- A stroke's level error of %.1f dB is the ear's step for broadband sound (Miller 1947) "
      "and a third to a quarter of the hand's; the kiosk matches its textures' levels within "
      "1 dB (calibration/texture_levels.h), so a contact error within the budget is half what "
      "the level matching already allows. The level is what is compared, not the waveform or the "
      "spectrum's shape: the spectrum of a chaotic stroke is not reproducible (its band energies "
      "move by tens of %% on a 1e-12 change, docs/contact-bench.md), and a level that is not the "
      "same within the ear's step would be the audible part.\n\n",
      20.0 * std::log10(1.0 + eps / 2.0), eps, 20.0 * std::log10(1.0 + worst_chosen / 2.0),
      worst_chosen, 0.45 / (20.0 * std::log10(1.0 + eps / 2.0)), kiosk::kLevelBudgetDb);
  md << why;
  md << "Chaos floor: the reference against itself with one modal mass changed by ±1e-12 "
        "(a stroke that sticks and slips, or flies over the ridges and lands on each, is chaotic; "
        "a level difference within this floor is not the scheme's, so a stroke meets the budget "
        "within ±(" << kiosk::kLevelBudgetDb << " dB + its floor)). |dB|, sound / vibration:\n\n"
        "| material |";
  for (const auto& st : strokes) md << " " << st.Name() << " |";
  md << "\n|---|";
  for (std::size_t i = 0; i < strokes.size(); ++i) md << "---:|";
  md << "\n";
  for (const auto& m : results) {
    md << "| " << m.material.name << " |";
    for (const auto& r : m.reference) {
      md << " " << Fixed(r.floor.sound_db, 2).substr(1) << " / " << Fixed(r.floor.haptic_db, 2).substr(1)
         << " |";
    }
    md << "\n";
  }
  md << "\n## Per material and style: the coarsest rung meeting the budget\n\n"
        "Rungs: sub-steps per contact at 1 m/s (the automatic oversampling's target; an impact at "
        "speed v gets what its restitution needs, synth/contact.h) and the most sub-steps a "
        "pressed contact keeps (held). Impact: the rigid-wall restitution alone; a style: its "
        "slow and fast strokes.\n\n"
        "| material | scheme | impact | scrape | rub | roll | chosen (all styles) | ns per "
        "sample | worst impact error |\n|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
  const auto& targets = kiosk::TargetSamplesLadder();
  const auto& held = kiosk::SustainedLadder();
  auto rung = [&](const Rung& r) {
    char text[32];
    std::snprintf(text, sizeof text, "%g / %d", targets[r.target], held[r.held]);
    return std::string(text);
  };
  for (const auto& m : results) {
    for (std::size_t i = 0; i < m.schemes.size(); ++i) {
      const auto& s = m.schemes[i];
      md << "| " << m.material.name << " | " << SchemeName(s.scheme)
         << (static_cast<int>(i) == m.best ? " **(chosen)**" : "") << " | "
         << G17(targets[s.impact_target]);
      for (const auto& st : s.styles) md << " | " << (st.found ? rung(st.rung) : "-");
      md << " | " << (s.found ? rung(s.chosen) : "none") << " | "
         << (s.found ? std::to_string(static_cast<int>(std::lround(s.ns_per_sample))) : "-")
         << " | " << Sci(s.impact.worst_relative) << " |\n";
    }
  }
  md << "\nns per sample: thread CPU time of all six budget strokes at the chosen rung, best of "
     << reps
     << ", one core of the build machine (shared: a few % of noise); the cheapest scheme "
        "is the material's choice.\n\n## The chosen policies against the reference\n\n"
        "Level error (dB, sound / vibration) of each budget stroke with the chosen policy, and "
        "what one rung coarser misses (the calibration test checks both).\n\n| material | policy |";
  for (const auto& st : strokes) md << " " << st.Name() << " |";
  md << " one rung coarser |\n|---|---|";
  for (std::size_t i = 0; i < strokes.size(); ++i) md << "---:|";
  md << "---|\n";
  for (const auto& m : results) {
    if (m.best < 0) {
      md << "| " << m.material.name << " | none met the budget: the built-in policy ("
         << SchemeName(synth::kDefaultContactScheme) << ", "
         << G17(synth::TargetContactSamples(synth::kDefaultContactScheme)) << " / "
         << synth::kSustainedContactSubsteps << ") stays, and misses it: "
         << (m.builtin_fails.empty() ? "nothing" : m.builtin_fails) << " |\n";
      continue;
    }
    const auto& s = m.schemes[static_cast<std::size_t>(m.best)];
    md << "| " << m.material.name << " | " << SchemeName(s.scheme) << " " << rung(s.chosen) << " |";
    for (const auto& f : s.chosen_figures) {
      md << " " << Fixed(f.sound_db, 2) << " / " << Fixed(f.haptic_db, 2) << " |";
    }
    md << " " << (s.coarser_fails.empty() ? "(the coarsest rung)" : s.coarser_fails) << " |\n";
  }
  md << "\n";
  return md.str();
}

}  // namespace

int RunChoose(const ChooseOptions& options) {
  std::vector<MaterialResult> results;
  for (const auto& name : kiosk::ListMaterialNames(options.materials_dir)) {
    MaterialResult m;
    m.material = kiosk::LoadMaterialFile(
        (std::filesystem::path(options.materials_dir) / (name + ".toml")).string());
    std::printf("%s\n", name.c_str());
    std::fflush(stdout);
    for (const auto& stroke : kiosk::BudgetStrokes()) {
      m.reference.push_back(kiosk::MeasureStrokeReference(m.material.params, stroke));
      std::printf("  floor %s: %.3f / %.3f dB\n", stroke.Name().c_str(),
                  m.reference.back().floor.sound_db, m.reference.back().floor.haptic_db);
    }
    double best_ns = 0.0;
    for (const auto scheme : kCandidates) {
      m.schemes.push_back(ChooseForScheme(m.material, scheme, m.reference, options.reps));
      const auto& s = m.schemes.back();
      if (s.found && (m.best < 0 || s.ns_per_sample < best_ns)) {
        m.best = static_cast<int>(m.schemes.size() - 1);
        best_ns = s.ns_per_sample;
      }
      std::fflush(stdout);
    }
    if (m.best < 0) {
      const auto params = kiosk::WithPolicy(m.material.params, {synth::kDefaultContactScheme, 0, 0});
      const auto all = AllStrokes();
      m.builtin_fails = FailText(Compare(params, m.reference, all), m.reference, all);
    }
    results.push_back(std::move(m));
  }
  if (options.table_path != "-") WriteTable(options.table_path, results);
  const std::string md = Markdown(results, options.reps);
  if (options.docs_path != "-") {
    std::ofstream(options.docs_path) << md;
    std::printf("wrote %s\n", options.docs_path.c_str());
  } else {
    std::fputs(md.c_str(), stdout);
  }
  return std::all_of(results.begin(), results.end(), [](const auto& m) { return m.best >= 0; })
             ? 0
             : 1;
}

}  // namespace sas::bench
