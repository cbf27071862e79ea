#pragma once
// What the contact benchmark's two halves share: the sample rate, CPU-time measurement (best of N
// after a warm-up), the scheme names and the short scientific notation of the tables, and the
// 32-mode steel plate both the kiosk scene and the explicit-reference front strike.
#include <algorithm>
#include <limits>
#include <string>

#include "files/contact_scheme_names.h"
#include "synth/contact.h"
#include "synth/material_params.h"

namespace sas::bench {

constexpr double kFs = 48000.0;

// CPU time of this thread (s): the machine is shared, and time spent preempted is not the
// code's cost.
double CpuSeconds();

// Best of `reps` runs after one warm-up run.
template <class F>
double BestSeconds(int reps, F&& run) {
  if (reps <= 0) {  // just run it, untimed
    run();
    return 0.0;
  }
  run();
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < reps; ++r) {
    const double start = CpuSeconds();
    run();
    best = std::min(best, CpuSeconds() - start);
  }
  return best;
}

inline std::string SchemeName(synth::ContactScheme s) {
  return kiosk::ContactSchemeName(s);
}

// "1.2e-04" (0 as "0", negative or NaN as "-").
std::string Sci(double v, int digits = 1);

// metal.toml's steel plate (250 x 180 x 3 mm, E = 200 GPa, ρ = 7850, ν = 0.3, η = 8e-4, contact
// at (0.37 a, 0.41 b), pickup at (0.21 a, 0.67 b)) with its first 32 modes of |gain| >= 0.05, by
// the same thin-plate formula (Leissa, NASA SP-160) and rules as the file's comment: f_mn =
// (π/2) h sqrt(E / (12 ρ (1 - ν²))) ((m/a)² + (n/b)²), τ = 1 / (π f η), modal mass ρ h a b / 4
// over max(shape², 0.09) at the contact, gain = shape at the pickup.
synth::ResonatorParams SteelPlate32();

}  // namespace sas::bench
