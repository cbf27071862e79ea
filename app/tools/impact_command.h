#pragma once
// `sketch-a-scratch impact`: the measuring command for people calibrating materials. It drops a
// probe of mass M on a rigid, immovable body through the engine's own contact code path
// (synth::SimulateRigidWallImpact, the same per-sample kernel Scene::Process runs) and prints, as
// JSON, what the engine did next to what the closed forms say (hunt_crossley_closed_form.h):
// exit velocity, restitution, max compression, contact time, samples per contact, and the
// relative errors.
//
//   sketch-a-scratch impact --mass 0.01 --k 1e8 --mu 0.5 --alpha 1.5 --v-in 1
//                           [--fs 48000] [--scheme discrete-gradient] [--oversample N] [--phase P]
//                           [--max-wall-s 30]
//
// The JSON is written by nlohmann-json, so it is always valid: a closed-form value that does not
// exist for the inputs (contact time when μ·v ≥ 1 or α ≠ 1.5 has no closed form here) is null.

#include <cstdio>
#include <string>
#include <vector>

#include "synth/material_params.h"

namespace sas::kiosk {

struct ImpactOptions {
  double mass_kg = 0.01;
  double k = 1e8;
  double mu = 0.5;
  double alpha = 1.5;
  double v_in_mps = 1.0;
  double sample_rate_hz = 48000.0;
  synth::ContactScheme scheme = synth::kDefaultContactScheme;
  int oversample = 0;        // 0: the engine's automatic choice from N_c
  double phase = 0.0;        // sub-sample onset phase in [0, 1)
  double max_wall_s = 30.0;  // the run is stopped (exit 1) after this much wall time
};

// `energy_gained` is true only when the exit speed exceeds the entry speed by more than this
// relative amount: the DESIGN's energy figure (e <= e_exact * (1 + 1e-6)). With no damping
// (mu = 0) the exact restitution is 1 and round-off alone leaves e = 1 +- a few 1e-9.
inline constexpr double kEnergyGainTolerance = 1e-6;

// Runs the simulation and the closed forms and returns the JSON document (one object). Throws
// std::runtime_error when the run hit options.max_wall_s.
std::string ImpactReportJson(const ImpactOptions& options);
// The subcommand: returns the exit code (0 ok, 1 stopped by the wall-time cap, 2 bad arguments,
// 0 after --help). Never throws.
int RunImpactCommand(const std::vector<std::string>& args, std::FILE* out, std::FILE* err);

}  // namespace sas::kiosk
