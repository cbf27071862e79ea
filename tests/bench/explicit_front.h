#pragma once
// The default contact scheme against the explicit reference (explicit_reference.h): each returns a
// markdown section for the contact benchmark's report, printing progress as it measures. `quick`
// trades accuracy of the costs (one repetition, shorter rubs) for time; `bench_reps` is the
// benchmark's --reps (at least 3 are used otherwise).
#include <string>

namespace sas::bench {

// Impact: worst restitution error and cost per contact against a rigid wall and a heavy 32-mode
// plate, every configuration, and the cheapest of each side at 1e-4.
std::string ExplicitFront(bool quick, int bench_reps);

// Friction: a rub on wood.toml's first 1 and 8 modes, error against each side's own ×64 and cost
// per sample, and the reference configuration as accurate as the synth at ×1.
// Ends with RubCostMarkdown's table.
std::string FrictionFront(bool quick, int bench_reps);

// The 1-mode rub (metal's and wood's friction sets, 0.2 m/s, 1 N): the synth's ×1 cost per sample
// against the reference's ×1 step, and whether it is within 2.5x.
std::string RubCostMarkdown(bool quick, int bench_reps);

}  // namespace sas::bench
