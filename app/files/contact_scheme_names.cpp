// Contact scheme names (see contact_scheme_names.h).
#include "files/contact_scheme_names.h"

#include <algorithm>

namespace sas::kiosk {
namespace {

struct SchemeName {
  const char* name;
  synth::ContactScheme scheme;
};

constexpr SchemeName kSchemes[] = {
    {"explicit_passive", synth::ContactScheme::kExplicitPassive},
    {"trapezoid_newton", synth::ContactScheme::kTrapezoidNewton},
    {"discrete_gradient", synth::ContactScheme::kDiscreteGradient},
    {"energy_quadratised", synth::ContactScheme::kEnergyQuadratised},
};

struct BristleName {
  const char* name;
  synth::BristleUpdate update;
};

constexpr BristleName kBristleUpdates[] = {
    {"exponential", synth::BristleUpdate::kExponential},
    {"explicit_euler", synth::BristleUpdate::kExplicitEuler},
};

std::string Normalised(std::string_view name) {
  std::string normalised(name);
  std::replace(normalised.begin(), normalised.end(), '-', '_');
  return normalised;
}

}  // namespace

const char* ContactSchemeName(synth::ContactScheme scheme) {
  for (const auto& entry : kSchemes) {
    if (entry.scheme == scheme) return entry.name;
  }
  return "unknown";
}

bool ParseContactScheme(std::string_view name, synth::ContactScheme* scheme) {
  const std::string normalised = Normalised(name);
  for (const auto& entry : kSchemes) {
    if (normalised == entry.name) {
      *scheme = entry.scheme;
      return true;
    }
  }
  return false;
}

std::string ContactSchemeChoices() {
  std::string choices;
  for (const auto& entry : kSchemes) {
    if (!choices.empty()) choices += ", ";
    choices += entry.name;
  }
  return choices;
}

const char* BristleUpdateName(synth::BristleUpdate update) {
  for (const auto& entry : kBristleUpdates) {
    if (entry.update == update) return entry.name;
  }
  return "unknown";
}

bool ParseBristleUpdate(std::string_view name, synth::BristleUpdate* update) {
  const std::string normalised = Normalised(name);
  for (const auto& entry : kBristleUpdates) {
    if (normalised == entry.name) {
      *update = entry.update;
      return true;
    }
  }
  return false;
}

std::string BristleUpdateChoices() {
  std::string choices;
  for (const auto& entry : kBristleUpdates) {
    if (!choices.empty()) choices += ", ";
    choices += entry.name;
  }
  return choices;
}

}  // namespace sas::kiosk
