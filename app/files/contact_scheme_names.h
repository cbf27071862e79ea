#pragma once
// The contact schemes' names as staff and engineers write them: in material files
// (`scheme = "discrete_gradient"`) and on the command line (`--scheme discrete-gradient`; '-' and
// '_' are interchangeable), and the friction's bristle updates (`bristle_update = "exponential"`).

#include <string>
#include <string_view>

#include "synth/material_params.h"

namespace sas::kiosk {

const char* ContactSchemeName(synth::ContactScheme scheme);
// False when `name` is not a scheme.
bool ParseContactScheme(std::string_view name, synth::ContactScheme* scheme);
// "explicit_passive, trapezoid_newton, ..." for error messages.
std::string ContactSchemeChoices();

const char* BristleUpdateName(synth::BristleUpdate update);
// False when `name` is not a bristle update ("exponential", "explicit_euler").
bool ParseBristleUpdate(std::string_view name, synth::BristleUpdate* update);
std::string BristleUpdateChoices();

}  // namespace sas::kiosk
