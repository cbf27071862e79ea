#pragma once
// `sketch-a-scratch impact`: the measuring command for people calibrating materials. It drops a
// probe of mass M on a rigid, immovable body through the engine's own contact code path
// (synth::SimulateRigidWallImpact, the same per-sample kernel Scene::Process runs) and prints, as
// JSON, what the engine did next to what the closed forms say (reference/hunt-crossley.md):
// exit velocity, restitution, max compression, contact time, samples per contact, and the
// relative errors.
//
//   sketch-a-scratch impact --mass 0.01 --k 1e8 --mu 0.5 --alpha 1.5 --v-in 1
//                           [--fs 48000] [--scheme discrete-gradient] [--oversample N] [--phase P]

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
  int oversample = 0;  // 0: the engine's automatic choice from N_c
  double phase = 0.0;  // sub-sample onset phase in [0, 1)
};

// Throws std::invalid_argument with a message naming the bad option.
ImpactOptions ParseImpactArgs(const std::vector<std::string>& args);
// Runs the simulation and the closed forms and returns the JSON document (one object).
std::string ImpactReportJson(const ImpactOptions& options);
// The subcommand: returns the exit code (0 ok, 2 bad arguments). Never throws.
int RunImpactCommand(const std::vector<std::string>& args, std::FILE* out, std::FILE* err);

}  // namespace sas::kiosk
