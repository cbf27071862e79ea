// The contact benchmark's comparison with the explicit reference (explicit_reference.h, contact
// solved as the Sound Design Toolkit solves it): the default scheme's kernel and the reference on
// one impact (rigid wall and a heavy 32-mode plate) and on a friction rub, error against cost.
#include "explicit_front.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "contact_bench_common.h"
#include "explicit_reference.h"
#include "files/material_file.h"
#include "synth/contact.h"
#include "synth/contact_kernel.h"
#include "synth/hunt_crossley_closed_form.h"

namespace sas::bench {
namespace {

// The body the probe hits: none (a rigid wall) or metal.toml's 32-mode steel plate made 1e6 times
// heavier (every modal mass 1e6 x): its modes are computed like the kiosk's, so the cost is a
// real resonator's, while the wall hardly moves (the restitution stays the closed form's to
// ~1e-6).
synth::ResonatorParams HeavyPlate() {
  synth::ResonatorParams p = SteelPlate32();
  for (int i = 0; i < p.mode_count; ++i) p.modes[static_cast<std::size_t>(i)].mass_kg *= 1e6;
  return p;
}

struct FrontCase {
  double k, mu_v;
};
struct FrontPoint {
  double error = 0.0;  // worst relative restitution error over the phases
  double ns_per_contact = 0.0;
  double steps = 0.0;        // contact steps (sub-steps) per contact, mean over phases
  double guard_share = 0.0;  // reference: bisection iterations per step
};

// One contact per sub-sample onset phase, first measured (worst restitution error against the
// closed form, steps counted into *steps), then timed. `contact(phase, counted)` runs one impact
// from rest, adds its steps to *counted unless it is null, and returns the exit velocity.
template <class Contact>
FrontPoint OverPhases(double mu_v, double v_in, int phases, int reps, double* steps,
                      Contact&& contact) {
  const double exact = synth::HuntCrossleyRestitution(mu_v);
  FrontPoint point;
  auto run_all = [&](bool measure) {
    for (int p = 0; p < phases; ++p) {
      const double phase = (p + 0.5) / phases;
      const double exit_mps = contact(phase, measure ? steps : nullptr);
      if (measure) {
        const double e = exit_mps / v_in;
        point.error = std::max(point.error, std::fabs(e - exact) / exact);
      }
    }
  };
  run_all(true);
  point.steps = *steps / phases;
  point.ns_per_contact = BestSeconds(reps, [&] { run_all(false); }) * 1e9 / phases;
  return point;
}

// The synth's kernel (StepContactSample, the scene's per-sample code) on one impact: set up once,
// each phase from rest.
FrontPoint KernelFront(const FrontCase& c, const synth::ResonatorParams& body,
                       synth::ContactScheme scheme, int oversample, int phases, int reps) {
  const double mass = 0.01, v_in = 1.0, alpha = 1.5;
  synth::ImpactParams params;
  params.scheme = scheme;
  params.stiffness = c.k;
  params.dissipation_s_per_m = c.mu_v / v_in;
  params.shape_alpha = alpha;
  params.oversample = oversample;
  synth::ContactKernelConfig config;
  config.scheme = scheme;
  config.impact.Set(params);
  config.friction.enabled = false;
  config.probe_mass_kg = mass;
  config.SetTiming(kFs, synth::ChooseContactOversample(params, mass, kFs));
  synth::ModalState modes;
  const bool adaptive = oversample <= 0;
  modes.Prepare(body, kFs, config.substeps, false, adaptive);
  config.adaptive = adaptive && modes.level_count > 1;
  config.SetLevels(params, modes, kFs);
  double steps = 0.0;
  return OverPhases(c.mu_v, v_in, phases, reps, &steps, [&](double phase, double* counted) {
    modes.Reset();
    synth::ProbeDynamics probe;
    probe.active = true;
    probe.height_m = phase * v_in / kFs;
    probe.velocity_mps = -v_in;
    const synth::SampleDrive drive;
    bool started = false;
    for (long n = 0; n < static_cast<long>(kFs); ++n) {
      synth::StepContactSample(config, modes, probe, drive);
      if (counted) *counted += probe.substeps_used;
      if (probe.touched) started = true;
      if (started && !probe.touched && probe.compression_m < 0.0 && probe.velocity_mps > 0.0) break;
    }
    return probe.velocity_mps;
  });
}

// The reference's two bodies at rate fs: the resonator's modes, and the probe as a point mass
// (one mode of zero frequency and zero decay, unit gain).
void SetReferenceBodies(const synth::ResonatorParams& modes, double probe_mass_kg, double fs,
                        bench::SdtBody* body, bench::SdtBody* probe) {
  std::array<double, bench::SdtBody::kMax> f{}, d{}, m{}, g{};
  for (int i = 0; i < modes.mode_count; ++i) {
    const auto& mode = modes.modes[static_cast<std::size_t>(i)];
    f[static_cast<std::size_t>(i)] = mode.frequency_hz;
    d[static_cast<std::size_t>(i)] = mode.decay_s;
    m[static_cast<std::size_t>(i)] = mode.mass_kg;
    g[static_cast<std::size_t>(i)] = mode.gain;
  }
  body->Set(modes.mode_count, f.data(), d.data(), m.data(), g.data(), fs);
  const double zero = 0.0, one = 1.0;
  probe->Set(1, &zero, &zero, &probe_mass_kg, &one, fs);
}

// The explicit reference (explicit_reference.h) on the same impact at fs = oversample x 48 kHz.
FrontPoint ReferenceFront(const FrontCase& c, const synth::ResonatorParams& body_params,
                          int oversample, int phases, int reps) {
  const double mass = 0.01, v_in = 1.0;
  const double fs = kFs * oversample, t = 1.0 / fs;
  bench::SdtBody body, probe;
  SetReferenceBodies(body_params, mass, fs, &body, &probe);
  bench::SdtImpact impact;
  impact.k = c.k;
  impact.mu = c.mu_v / v_in;
  impact.alpha = 1.5;
  impact.guard_iterations = 0;
  decltype(impact.guard_iterations) measured_guard = 0;  // the timed runs keep counting
  double steps = 0.0;
  FrontPoint point =
      OverPhases(c.mu_v, v_in, phases, reps, &steps, [&](double phase, double* counted) {
        body.Reset();
        probe.Reset();
        probe.Place(-phase * v_in * t, v_in, t);
        impact.stored = 0.0;
        bool started = false;
        for (long n = 0; n < static_cast<long>(fs); ++n) {
          const double f = impact.Step(body, probe);
          if (counted) *counted += 1.0;
          if (f != 0.0) started = true;
          if (started && probe.Position() - body.Position() <= 0.0 && probe.Velocity() < 0.0) break;
        }
        if (counted) measured_guard = impact.guard_iterations;
        return -probe.Velocity();
      });
  point.guard_share = measured_guard / std::max(steps, 1.0);
  return point;
}

// One configuration of the front for one k: worst error over μ·v, costs and steps mean over μ·v.
struct FrontEntry {
  double error = 0.0, ns_rigid = 0.0, ns_plate = 0.0, steps = 0.0, guard = 0.0;
};
using FrontTable = std::map<double, std::map<int, FrontEntry>>;  // [k][oversample]

// The grid both sides of the front are measured on.
struct FrontGrid {
  int phases = 32;
  int reps = 3;
  std::vector<double> ks = {1e6, 1e8, 1e10};
  std::vector<double> mu_vs = {0.1, 0.5, 1.0};
  std::vector<int> ref_os = {1, 2, 3, 4, 6, 8, 12, 16};
  std::vector<int> dg_os = {0, 1, 2, 4, 8, 16, 32};  // 0: the automatic choice
};

// Folds one μ·v's rigid-wall (a) and heavy-plate (b) measurements into the entry.
void AddFrontPoints(FrontEntry& e, const FrontPoint& a, const FrontPoint& b, double mu_v_count,
                    bool with_guard) {
  e.error = std::max({e.error, a.error, b.error});
  e.ns_rigid += a.ns_per_contact / mu_v_count;
  e.ns_plate += b.ns_per_contact / mu_v_count;
  e.steps += a.steps / mu_v_count;
  if (with_guard) e.guard += a.guard_share / mu_v_count;
}

// Runs the reference and the default scheme over the grid, against the rigid wall and the heavy
// plate; --quick prints each rigid-wall error as it comes.
void MeasureFront(const FrontGrid& grid, bool quick, FrontTable* ref, FrontTable* def) {
  const synth::ResonatorParams rigid{}, heavy = HeavyPlate();
  const auto dg = synth::kDefaultContactScheme;
  const double mu_v_count = static_cast<double>(grid.mu_vs.size());
  for (double k : grid.ks) {
    for (double mu_v : grid.mu_vs) {
      const FrontCase c{k, mu_v};
      for (int os : grid.ref_os) {
        const FrontPoint a = ReferenceFront(c, rigid, os, grid.phases, grid.reps);
        if (quick) std::printf("  ref x%d k=%.0e mu*v=%g: %.2e\n", os, k, mu_v, a.error);
        const FrontPoint b = ReferenceFront(c, heavy, os, grid.phases, grid.reps);
        AddFrontPoints((*ref)[k][os], a, b, mu_v_count, true);
      }
      for (int os : grid.dg_os) {
        const FrontPoint a = KernelFront(c, rigid, dg, os, grid.phases, grid.reps);
        if (quick) std::printf("  dg x%d k=%.0e mu*v=%g: %.2e\n", os, k, mu_v, a.error);
        const FrontPoint b = KernelFront(c, heavy, dg, os, grid.phases, grid.reps);
        AddFrontPoints((*def)[k][os], a, b, mu_v_count, false);
      }
      std::printf("front: k=%.0e mu*v=%g done\n", k, mu_v);
      std::fflush(stdout);
    }
  }
}

// Order of the reference: least-squares slope of log error against log N, over the errors a
// power law can describe (above the rounding floor, below saturation).
double ReferenceOrder(const std::map<int, FrontEntry>& rows) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (auto& [os, e] : rows) {
    if (!(e.error > 1e-8) || e.error > 0.1) continue;
    const double x = std::log(static_cast<double>(os)), y = std::log(e.error);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    ++n;
  }
  return n >= 2 ? -(n * sxy - sx * sy) / (n * sxx - sx * sx) : 0.0;
}

// Every configuration measured: error, steps, cost on both bodies, guard work.
std::string FrontTableMarkdown(const FrontGrid& grid, const FrontTable& ref,
                               const FrontTable& def) {
  std::ostringstream md;
  char line[512];
  md << "| k | config | error | steps per contact | ns per contact (rigid) | ns per contact (32 "
        "modes) | guard bisections per step |\n|---|---|---:|---:|---:|---:|---:|\n";
  for (double k : grid.ks) {
    for (auto& [os, e] : ref.at(k)) {
      std::snprintf(line, sizeof line,
                    "| %.0e | reference ×%d | %s | %.1f | %.0f | %.0f | %.2f |\n", k, os,
                    Sci(e.error).c_str(), e.steps, e.ns_rigid, e.ns_plate, e.guard);
      md << line;
    }
    for (auto& [os, e] : def.at(k)) {
      const std::string name = os == 0 ? "auto" : "×" + std::to_string(os);
      std::snprintf(line, sizeof line, "| %.0e | %s %s | %s | %.1f | %.0f | %.0f | |\n", k,
                    SchemeName(synth::kDefaultContactScheme).c_str(), name.c_str(),
                    Sci(e.error).c_str(), e.steps, e.ns_rigid, e.ns_plate);
      md << line;
    }
  }
  return md.str();
}

// The cheapest configuration reaching 1e-4 (oversample, cost), or (-1, 1e300) if none does.
std::pair<int, double> CheapestAt1e4(const std::map<int, FrontEntry>& rows, bool plate) {
  int best = -1;
  double cost = 1e300;
  for (auto& [os, e] : rows) {
    const double c = plate ? e.ns_plate : e.ns_rigid;
    if (e.error <= 1e-4 && c < cost) {
      cost = c;
      best = os;
    }
  }
  return std::pair{best, cost};
}

std::string CheapestLabel(int os, double cost) {
  if (os < 0) return std::string("none within the range");
  char b[64];
  std::snprintf(b, sizeof b, "%s, %.0f ns", os == 0 ? "auto" : ("×" + std::to_string(os)).c_str(),
                cost);
  return std::string(b);
}

// The goal's table: per k, the cheapest of each side at 1e-4 and their cost ratio.
std::string FrontAt1e4Markdown(const FrontGrid& grid, const FrontTable& ref,
                               const FrontTable& def) {
  std::ostringstream md;
  char line[512];
  md << "\nAt 1e-4 (the cheapest configuration of each that reaches it; ratio default / "
        "reference, ≤ 0.5 is the goal):\n\n| k | reference order | reference | default | "
        "ratio (rigid) | ratio (32 modes) |\n|---|---:|---|---|---:|---:|\n";
  for (double k : grid.ks) {
    const auto [r_os, r_cost] = CheapestAt1e4(ref.at(k), false);
    const auto [d_os, d_cost] = CheapestAt1e4(def.at(k), false);
    const auto [rp_os, rp_cost] = CheapestAt1e4(ref.at(k), true);
    const auto [dp_os, dp_cost] = CheapestAt1e4(def.at(k), true);
    const bool both = r_os >= 0 && d_os >= 0, both_plate = rp_os >= 0 && dp_os >= 0;
    std::snprintf(line, sizeof line,
                  "| %.0e | %.2f | %s (plate: %s) | %s (plate: %s) | %s | %s |\n", k,
                  ReferenceOrder(ref.at(k)), CheapestLabel(r_os, r_cost).c_str(),
                  CheapestLabel(rp_os, rp_cost).c_str(), CheapestLabel(d_os, d_cost).c_str(),
                  CheapestLabel(dp_os, dp_cost).c_str(),
                  both ? (std::to_string(d_cost / r_cost).substr(0, 4)).c_str() : "-",
                  both_plate ? (std::to_string(dp_cost / rp_cost).substr(0, 4)).c_str() : "-");
    md << line;
  }
  return md.str();
}

// Friction against the explicit reference: a rub (friction only, wood.toml's elasto-plastic set,
// noise off, 1 N) on wood.toml's first `modes` modes, the hand at v_mps. Output: the pickup
// velocity at 48 kHz. The synth's kernel at ×os sub-steps, or the reference at os x 48 kHz.
struct RubRun {
  std::vector<double> out;
  double ns_per_sample = 0.0;
};
synth::ResonatorParams FirstModes(const synth::ResonatorParams& all, int count) {
  synth::ResonatorParams p = all;
  p.mode_count = std::min(count, all.mode_count);
  return p;
}
RubRun KernelRub(const synth::MaterialParams& wood, int modes_count, double v_mps, int os,
                 long frames, int reps) {
  synth::ContactKernelConfig config;
  config.impact.enabled = false;
  config.friction.Set(wood.friction);
  config.friction.sigma3 = 0.0;
  config.probe_mass_kg = wood.probe.mass_kg;
  config.SetTiming(kFs, os);
  synth::ModalState modes;
  modes.Prepare(FirstModes(wood.resonator, modes_count), kFs, config.substeps, false, false);
  synth::SampleDrive drive;
  drive.slide_velocity_mps = v_mps;
  drive.push_n = 1.0;
  drive.friction_share = 1.0;
  RubRun run;
  run.out.resize(static_cast<std::size_t>(frames));
  auto render = [&] {
    modes.Reset();
    synth::ProbeDynamics probe;
    probe.active = true;
    for (long n = 0; n < frames; ++n) {
      synth::StepContactSample(config, modes, probe, drive);
      run.out[static_cast<std::size_t>(n)] = modes.PickupVelocity();
    }
  };
  run.ns_per_sample = BestSeconds(reps, render) * 1e9 / static_cast<double>(frames);
  if (reps <= 0) return run;
  render();
  return run;
}
RubRun ReferenceRub(const synth::MaterialParams& wood, int modes_count, double v_mps, int os,
                    long frames, int reps, int* guard_iterations) {
  const double fs = kFs * os;
  bench::SdtBody body, probe;
  SetReferenceBodies(FirstModes(wood.resonator, modes_count), wood.probe.mass_kg, fs, &body,
                     &probe);
  bench::SdtFriction friction;
  const auto& fp = wood.friction;
  friction.sigma0 = fp.bristle_stiffness;
  friction.sigma1 = fp.bristle_damping;
  friction.sigma2 = fp.viscous_friction;
  friction.sigma3 = 0.0;
  friction.mu_s = fp.static_coefficient;
  friction.mu_d = fp.dynamic_coefficient;
  friction.v_s = fp.stribeck_velocity_mps;
  friction.c_ba = fp.breakaway_ratio;
  friction.fn = 1.0;
  friction.t = 1.0 / fs;
  RubRun run;
  run.out.resize(static_cast<std::size_t>(frames));
  auto render = [&] {
    body.Reset();
    probe.Reset();
    friction.z = 0.0;
    friction.guard_iterations = 0;
    for (long n = 0; n < frames; ++n) {
      for (int j = 0; j < os; ++j) friction.Step(body, probe, v_mps);
      run.out[static_cast<std::size_t>(n)] = body.Output();
    }
  };
  run.ns_per_sample = BestSeconds(reps, render) * 1e9 / static_cast<double>(frames);
  render();
  *guard_iterations = friction.guard_iterations;
  return run;
}
double RelativeRmsD(const std::vector<double>& y, const std::vector<double>& ref) {
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    num += (y[i] - ref[i]) * (y[i] - ref[i]);
    den += ref[i] * ref[i];
  }
  return den > 0.0 ? std::sqrt(num / den) : 0.0;
}

}  // namespace

// The 1-mode rub's cost per sample against the reference's ×1 step: metal.toml's and wood.toml's
// first mode, each with its own friction set (noise off), 1 N, 0.2 m/s. The two sides are timed in
// alternating rounds, best of each, so a load that comes and goes on the machine weighs on both.
// Errors: each against its own ×64 (the two models converge to slightly different limits).
std::string RubCostMarkdown(bool quick, int bench_reps) {
  constexpr double kRubSpeedMps = 0.2;
  constexpr double kRatioTarget = 2.5;
  const long frames = static_cast<long>((quick ? 0.2 : 0.5) * kFs);
  const int rounds = quick ? 2 : std::max(bench_reps, 3) * 3;
  std::ostringstream md;
  char line[512];
  md << "\n### The 1-mode rub against the reference's ×1 step\n\n"
        "One mode (the material's first) rubbed at "
     << kRubSpeedMps
     << " m/s with 1 N, its own friction set (noise off), "
     << static_cast<double>(frames) / kFs
     << " s: the synth's kernel at ×1 against the explicit reference at ×1 (its forward-Euler "
        "bristle and energy guard at 48 kHz), timed in "
     << rounds
     << " alternating rounds (thread CPU time, best of each). Error: relative RMS difference of the "
        "pickup velocity from each side's own ×64. Target: synth / reference ≤ "
     << kRatioTarget
     << ".\n\n| material | synth ×1: error, ns per sample | reference ×1: error, ns per sample | "
        "ratio synth / reference |\n|---|---|---|---:|\n";
  const auto dirs = kiosk::MaterialSearchDirs("");
  bool all_ok = true;
  for (const char* name : {"metal", "wood"}) {
    const kiosk::Material material = kiosk::FindMaterial(name, dirs);
    const RubRun fine = KernelRub(material.params, 1, kRubSpeedMps, 64, frames, 0);
    int guard = 0;
    const RubRun fine_ref = ReferenceRub(material.params, 1, kRubSpeedMps, 64, frames, 0, &guard);
    double kernel_ns = std::numeric_limits<double>::infinity(), reference_ns = kernel_ns;
    double kernel_error = 0.0, reference_error = 0.0;
    for (int round = 0; round < rounds; ++round) {
      const RubRun k = KernelRub(material.params, 1, kRubSpeedMps, 1, frames, 1);
      const RubRun r = ReferenceRub(material.params, 1, kRubSpeedMps, 1, frames, 1, &guard);
      kernel_ns = std::min(kernel_ns, k.ns_per_sample);
      reference_ns = std::min(reference_ns, r.ns_per_sample);
      kernel_error = RelativeRmsD(k.out, fine.out);
      reference_error = RelativeRmsD(r.out, fine_ref.out);
    }
    const double ratio = kernel_ns / reference_ns;
    all_ok = all_ok && ratio <= kRatioTarget;
    std::snprintf(line, sizeof line, "| %s | %s, %.0f | %s, %.0f | %.2f |\n", name,
                  Sci(kernel_error).c_str(), kernel_ns, Sci(reference_error).c_str(), reference_ns,
                  ratio);
    md << line;
    std::printf("rub cost: %s synth %.1f ns, reference %.1f ns per sample, ratio %.2f\n", name,
                kernel_ns, reference_ns, ratio);
    std::fflush(stdout);
  }
  md << "\nTarget (synth ≤ " << kRatioTarget << "× the reference's ×1 step): **"
     << (all_ok ? "holds" : "does not hold") << "**.\n";
  return md.str();
}

// Measures the default scheme against the explicit reference on the rigid wall and the heavy
// plate; returns the markdown section, whose last table says whether the default costs <= 0.5x
// the reference at 1e-4.
std::string ExplicitFront(bool quick, int bench_reps) {
  FrontGrid grid;
  grid.reps = quick ? 1 : std::max(bench_reps, 3);
  FrontTable ref, def;
  MeasureFront(grid, quick, &ref, &def);
  std::ostringstream md;
  md << "\n### Against the explicit reference (how the Sound Design Toolkit solves contact)\n\n"
        "The explicit reference (tests/bench/explicit_reference.h): impulse-invariant modes and "
        "a central-difference probe with a one-sample delay from force to position, the "
        "Hunt–Crossley force explicit in the current state, and the energy-bisection passivity "
        "guard, run at ×N the sample rate. The default ("
     << SchemeName(synth::kDefaultContactScheme)
     << ") runs its kernel at ×N contact sub-steps (auto: the kiosk's adaptive choice). 10 g at "
        "1 m/s, α = 1.5, μ·v ∈ {0.1, 0.5, 1}, worst relative restitution error over 32 onset "
        "phases and the three μ·v; cost per contact (touch to separation, thread CPU time, best of "
     << grid.reps
     << "), mean over μ·v, against a rigid wall and against metal.toml's 32-mode steel plate "
        "made 1e6 times heavier (the modes computed as in the kiosk; the restitution error moves "
        "by < 1e-6).\n\n";
  md << FrontTableMarkdown(grid, ref, def) << FrontAt1e4Markdown(grid, ref, def);
  return md.str();
}

std::string FrictionFront(bool quick, int bench_reps) {
  const kiosk::Material wood = kiosk::FindMaterial("wood", kiosk::MaterialSearchDirs(""));
  const long frames = static_cast<long>((quick ? 0.2 : 0.5) * kFs);
  const int reps = quick ? 1 : std::max(bench_reps, 3);
  std::ostringstream md;
  char line[512];
  md << "\n### Friction against the explicit reference\n\n"
        "A rub on wood.toml's first 1 and 8 modes (its elasto-plastic set, noise off, 1 N, the "
        "hand at 0.1 and 2 m/s), "
     << static_cast<double>(frames) / kFs
     << " s: the explicit reference's forward-Euler bristle with its energy guard at ×N the "
        "sample rate, and the synth's kernel (exact exponential bristle relaxation, the "
        "friction force solved with the modes' exact maps) at ×N sub-steps. Error: relative RMS "
        "difference of the pickup velocity from the synth's ×64 (and, in brackets, from the "
        "reference's ×64); cost: ns per output sample (thread CPU time, best of "
     << reps
     << ").\n\n| modes | v (m/s) | config | error vs synth ×64 (vs reference ×64) | ns "
        "per sample | guard bisections per sample |\n|---:|---:|---|---|---:|---:|\n";
  std::ostringstream summary;
  summary << "\nAt equal accuracy (each against its own ×64: the two models differ slightly, the "
             "synth's σ1 term being switched off where the bristle relaxes against the slip, "
             "so they converge to limits the first column's bracket shows apart): the synth's "
             "kernel at ×1 and the cheapest reference configuration as accurate.\n\n| modes | "
             "v (m/s) | synth ×1: error, ns | reference as accurate | ratio synth / reference "
             "|\n|---:|---:|---|---|---:|\n";
  for (int count : {1, 8}) {
    for (double v : {0.1, 2.0}) {
      const RubRun fine = KernelRub(wood.params, count, v, 64, frames, 0);
      int it = 0;
      const RubRun fine_ref = ReferenceRub(wood.params, count, v, 64, frames, 0, &it);
      const RubRun one = KernelRub(wood.params, count, v, 1, frames, reps);
      const double target = RelativeRmsD(one.out, fine.out);
      int match_os = -1;
      double match_ns = 0.0, match_err = 0.0;
      for (int os : {1, 2, 4, 8, 16, 32}) {
        int guard = 0;
        const RubRun r = ReferenceRub(wood.params, count, v, os, frames, reps, &guard);
        const double own = RelativeRmsD(r.out, fine_ref.out);
        if (match_os < 0 && own <= target) {
          match_os = os;
          match_ns = r.ns_per_sample;
          match_err = own;
        }
        if (os == 32) {
          if (match_os < 0) {
            std::snprintf(line, sizeof line,
                          "| %d | %g | %s, %.0f | none up to ×32 (×32: %s, %.0f ns) | < %.2f |\n",
                          count, v, Sci(target).c_str(), one.ns_per_sample, Sci(own).c_str(),
                          r.ns_per_sample, one.ns_per_sample / r.ns_per_sample);
          } else {
            std::snprintf(line, sizeof line, "| %d | %g | %s, %.0f | ×%d: %s, %.0f ns | %.2f |\n",
                          count, v, Sci(target).c_str(), one.ns_per_sample, match_os,
                          Sci(match_err).c_str(), match_ns, one.ns_per_sample / match_ns);
          }
          summary << line;
          continue;
        }
        std::snprintf(line, sizeof line, "| %d | %g | reference ×%d | %s (%s) | %.0f | %.2f |\n",
                      count, v, os, Sci(RelativeRmsD(r.out, fine.out)).c_str(),
                      Sci(RelativeRmsD(r.out, fine_ref.out)).c_str(), r.ns_per_sample,
                      static_cast<double>(guard) / static_cast<double>(frames));
        md << line;
      }
      for (int os : {1, 2, 4, 8, 16}) {
        const RubRun r = KernelRub(wood.params, count, v, os, frames, reps);
        std::snprintf(line, sizeof line, "| %d | %g | %s ×%d | %s (%s) | %.0f | |\n", count, v,
                      SchemeName(synth::kDefaultContactScheme).c_str(), os,
                      Sci(RelativeRmsD(r.out, fine.out)).c_str(),
                      Sci(RelativeRmsD(r.out, fine_ref.out)).c_str(), r.ns_per_sample);
        md << line;
      }
      std::printf("friction front: %d modes, v=%g done\n", count, v);
      std::fflush(stdout);
    }
  }
  return md.str() + summary.str() + RubCostMarkdown(quick, bench_reps);
}

}  // namespace sas::bench
