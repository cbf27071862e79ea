// Material files: TOML -> synth::MaterialParams with strict validation (see material_file.h; the
// file format and every key's range are in textures/materials/README.md). The schema is a table of
// key specs per TOML table, so the accepted keys, their types and ranges are written once.
#include "files/material_file.h"

#include "files/contact_choice.h"
#include "files/contact_scheme_names.h"
#include "sas/version.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

namespace sas::kiosk {
namespace {

namespace fs = std::filesystem;

int LineOf(const toml::node& node) {
  // The root table has no source line of its own; report line 1 for it.
  return std::max(1, static_cast<int>(node.source().begin.line));
}

std::string Where(const std::string& source, int line, const std::string& key) {
  return source + ":" + std::to_string(line) + ": " + key + ": ";
}

template <typename Target>
using Setter = std::function<void(const toml::node&, Target&, const std::string& where)>;

template <typename Target>
struct KeySpec {
  const char* key;
  Setter<Target> apply;
  bool optional = false;  // may be left out: the synth's default stays
};

std::string RangeText(double min, double max) {
  std::ostringstream text;
  text << "[" << min << ", " << max << "]";
  return text.str();
}

template <typename Target>
Setter<Target> Real(double Target::*member, double min, double max) {
  return [=](const toml::node& node, Target& target, const std::string& where) {
    if (!node.is_number()) throw MaterialError(where + "expected a number");
    const double value = *node.value<double>();
    if (!std::isfinite(value)) throw MaterialError(where + "must be a finite number (not NaN/inf)");
    if (value < min || value > max) {
      std::ostringstream message;
      message << where << value << " is out of range " << RangeText(min, max);
      throw MaterialError(message.str());
    }
    target.*member = value;
  };
}

template <typename Target>
Setter<Target> Integer(int Target::*member, int min, int max) {
  return [=](const toml::node& node, Target& target, const std::string& where) {
    if (!node.is_integer()) throw MaterialError(where + "expected an integer");
    const int64_t value = *node.value<int64_t>();
    if (value < min || value > max) {
      throw MaterialError(where + std::to_string(value) + " is out of range " +
                          RangeText(min, max));
    }
    target.*member = static_cast<int>(value);
  };
}

template <typename Target>
Setter<Target> Flag(bool Target::*member) {
  return [=](const toml::node& node, Target& target, const std::string& where) {
    if (!node.is_boolean()) throw MaterialError(where + "expected true or false");
    target.*member = *node.value<bool>();
  };
}

Setter<synth::ImpactParams> Scheme() {
  return [](const toml::node& node, synth::ImpactParams& impact, const std::string& where) {
    const std::string choices = ContactSchemeChoices();
    if (!node.is_string()) {
      throw MaterialError(where + "expected a string (one of " + choices + ")");
    }
    const std::string value = *node.value<std::string>();
    // The benchmark's choice is applied once the probe and the impact are known (ParseMaterial).
    if (value == kBenchmarkSchemeName) return;
    if (!ParseContactScheme(value, &impact.scheme)) {
      throw MaterialError(where + "unknown scheme \"" + value + "\" (one of " + choices + ", " +
                          std::string(kBenchmarkSchemeName) + ")");
    }
  };
}

Setter<synth::FrictionParams> Bristle() {
  return [](const toml::node& node, synth::FrictionParams& friction, const std::string& where) {
    const std::string choices = BristleUpdateChoices();
    if (!node.is_string()) {
      throw MaterialError(where + "expected a string (one of " + choices + ")");
    }
    const std::string value = *node.value<std::string>();
    if (!ParseBristleUpdate(value, &friction.bristle_update)) {
      throw MaterialError(where + "unknown bristle update \"" + value + "\" (one of " + choices +
                          ")");
    }
  };
}

// Ranges: wide enough for any physical material, narrow enough to keep the synth's numerics in
// the domain the contact schemes are held to (k <= 1e12, 1 <= α <= 4, probe 0.1 g .. 1 kg).
const std::vector<KeySpec<synth::ProbeParams>>& ProbeKeys() {
  using P = synth::ProbeParams;
  static const std::vector<KeySpec<P>> keys = {
      {"mass_kg", Real(&P::mass_kg, 1e-4, 1.0)},
      {"ball_radius_m", Real(&P::ball_radius_m, 1e-4, 0.05)},
      {"body_mass_kg", Real(&P::body_mass_kg, 0.0, 1.0), true},
      {"body_spring_n_per_m", Real(&P::body_spring_n_per_m, 1e2, 1e7), true},
  };
  return keys;
}

const std::vector<KeySpec<synth::ImpactParams>>& ImpactKeys() {
  using I = synth::ImpactParams;
  static const std::vector<KeySpec<I>> keys = {
      {"enabled", Flag(&I::enabled)},
      {"stiffness_n_per_m_alpha", Real(&I::stiffness, 1e2, 1e12)},
      {"dissipation_s_per_m", Real(&I::dissipation_s_per_m, 0.0, 100.0)},
      {"shape_alpha", Real(&I::shape_alpha, 1.0, 4.0)},
      {"scheme", Scheme()},
      {"oversample", Integer(&I::oversample, 0, 64)},
  };
  return keys;
}

const std::vector<KeySpec<synth::FrictionParams>>& FrictionKeys() {
  using F = synth::FrictionParams;
  static const std::vector<KeySpec<F>> keys = {
      {"enabled", Flag(&F::enabled)},
      {"sigma0_n_per_m", Real(&F::bristle_stiffness, 1.0, 1e8)},
      {"sigma1_n_s_per_m", Real(&F::bristle_damping, 0.0, 1e5)},
      {"sigma2_n_s_per_m", Real(&F::viscous_friction, 0.0, 1e4)},
      {"sigma3_noise", Real(&F::noise_coefficient, 0.0, 100.0)},
      {"mu_s", Real(&F::static_coefficient, 0.0, 2.0)},
      {"mu_d", Real(&F::dynamic_coefficient, 0.0, 2.0)},
      {"stribeck_velocity_mps", Real(&F::stribeck_velocity_mps, 1e-4, 10.0)},
      {"breakaway_ratio", Real(&F::breakaway_ratio, 0.01, 0.99)},
      {"felt_noise_share", Real(&F::felt_noise_share, 0.0, 1.0), true},
      // Optional: only the benchmark's comparison sets "explicit_euler" (it chatters).
      {"bristle_update", Bristle(), true},
  };
  return keys;
}

// Micro-roughness (synth::RoughnessParams): from polished (0.01 µm) to coarse soil (1 mm).
const std::vector<KeySpec<synth::RoughnessParams>>& RoughnessKeys() {
  using R = synth::RoughnessParams;
  static const std::vector<KeySpec<R>> keys = {
      {"rms_height_m", Real(&R::rms_m, 0.0, 1e-3)},
      {"correlation_length_m", Real(&R::length_m, 1e-7, 1e-2)},
  };
  return keys;
}

// A crumbling crust (synth::CrumbleParams, synth/crumble.h).
const std::vector<KeySpec<synth::CrumbleParams>>& CrumbleKeys() {
  using C = synth::CrumbleParams;
  static const std::vector<KeySpec<C>> keys = {
      {"grain_spacing_m", Real(&C::grain_spacing_m, 1e-5, 0.1)},
      {"strength_n", Real(&C::strength_n, 1e-3, 100.0)},
      {"weibull_modulus", Real(&C::weibull_modulus, 0.5, 20.0)},
      {"flake_low_hz", Real(&C::flake_low_hz, 20.0, kMaxModeFrequencyHz)},
      {"flake_high_hz", Real(&C::flake_high_hz, 20.0, kMaxModeFrequencyHz)},
      {"size_exponent", Real(&C::size_exponent, 0.5, 4.0)},
      {"flake_mass_kg", Real(&C::flake_mass_kg, 1e-7, 1.0)},
      {"flake_speed_ratio", Real(&C::flake_speed_ratio, 0.0, 10.0)},
      {"flake_loss_factor", Real(&C::flake_loss_factor, 1e-3, 1.0)},
      {"flake_gain", Real(&C::flake_gain, 0.0, 100.0)},
  };
  return keys;
}

const std::vector<KeySpec<synth::ModeParams>>& ModeKeys() {
  using M = synth::ModeParams;
  static const std::vector<KeySpec<M>> keys = {
      {"frequency_hz", Real(&M::frequency_hz, 1.0, kMaxModeFrequencyHz)},
      {"decay_s", Real(&M::decay_s, 1e-4, 60.0)},
      {"mass_kg", Real(&M::mass_kg, 1e-6, 100.0)},
      {"gain", Real(&M::gain, -100.0, 100.0)},
  };
  return keys;
}

// Applies every key of `table` (named `prefix` in messages) to `target`: unknown keys first in file
// order, then any missing key, reported at the table's own line.
template <typename Target>
void ApplyTable(const toml::table& table, const std::string& prefix,
                const std::vector<KeySpec<Target>>& specs, Target& target,
                const std::string& source) {
  for (const auto& [key, node] : table) {
    const std::string_view name = key.str();  // not captured as a binding: clang 14 cannot
    const std::string dotted = prefix + "." + std::string(name);
    const auto spec = std::find_if(specs.begin(), specs.end(),
                                   [&](const KeySpec<Target>& s) { return name == s.key; });
    if (spec == specs.end()) {
      std::string known;
      for (const auto& s : specs) known += std::string(known.empty() ? "" : ", ") + s.key;
      throw MaterialError(Where(source, LineOf(node), dotted) + "unknown key (expected one of " +
                          known + ")");
    }
    spec->apply(node, target, Where(source, LineOf(node), dotted));
  }
  for (const auto& spec : specs) {
    if (!spec.optional && !table.contains(spec.key)) {
      throw MaterialError(Where(source, LineOf(table), prefix + "." + spec.key) + "missing key");
    }
  }
}

const toml::table& RequireTable(const toml::table& root, const char* name,
                                const std::string& source) {
  const toml::node* node = root.get(name);
  if (node == nullptr) throw MaterialError(Where(source, 1, name) + "missing table [" + name + "]");
  const toml::table* table = node->as_table();
  if (table == nullptr) {
    throw MaterialError(Where(source, LineOf(*node), name) + "expected a table [" + name + "]");
  }
  return *table;
}

void ParseModes(const toml::table& root, const std::string& source,
                synth::ResonatorParams& resonator) {
  const toml::node* node = root.get("modes");
  if (node == nullptr) throw MaterialError(Where(source, 1, "modes") + "missing key");
  const toml::array* modes = node->as_array();
  if (modes == nullptr) {
    throw MaterialError(Where(source, LineOf(*node), "modes") +
                        "expected an array of tables { frequency_hz, decay_s, mass_kg, gain }");
  }
  if (modes->empty() || modes->size() > static_cast<std::size_t>(synth::kMaxModes)) {
    throw MaterialError(Where(source, LineOf(*node), "modes") + std::to_string(modes->size()) +
                        " modes; expected 1 to " + std::to_string(synth::kMaxModes));
  }
  resonator.mode_count = 0;
  for (std::size_t i = 0; i < modes->size(); ++i) {
    const toml::node& element = *modes->get(i);
    const std::string prefix = "modes[" + std::to_string(i) + "]";
    const toml::table* mode = element.as_table();
    if (mode == nullptr) {
      throw MaterialError(Where(source, LineOf(element), prefix) +
                          "expected a table { frequency_hz, decay_s, mass_kg, gain }");
    }
    synth::ModeParams params;
    ApplyTable(*mode, prefix, ModeKeys(), params, source);
    resonator.modes[i] = params;
    ++resonator.mode_count;
  }
}

void ParseDescription(const toml::table& root, const std::string& source, std::string& out) {
  const toml::node* node = root.get("description");
  if (node == nullptr) throw MaterialError(Where(source, 1, "description") + "missing key");
  const std::string where = Where(source, LineOf(*node), "description");
  if (!node->is_string()) throw MaterialError(where + "expected a string");
  const std::string text = *node->value<std::string>();
  if (text.empty()) throw MaterialError(where + "must not be empty");
  if (text.find_first_of("\r\n") != std::string::npos) {
    throw MaterialError(where + "must be a single line");
  }
  out = text;
}

bool IsValidName(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
  });
}

}  // namespace

Material ParseMaterial(const std::string& text, const std::string& source_name,
                       const std::string& name) {
  if (!IsValidName(name)) {
    throw MaterialError(source_name + ": material name \"" + name +
                        "\" must be lower-case letters, digits and _ only");
  }
  toml::table root;
  try {
    root = toml::parse(text, source_name);
  } catch (const toml::parse_error& error) {
    throw MaterialError(source_name + ":" + std::to_string(error.source().begin.line) +
                        ": syntax error: " + std::string(error.description()));
  }
  for (const auto& [key, node] : root) {
    const std::string_view k = key.str();
    if (k != "description" && k != "probe" && k != "impact" && k != "friction" && k != "modes" &&
        k != "roughness" && k != "crumble") {
      throw MaterialError(Where(source_name, LineOf(node), std::string(k)) +
                          "unknown key (expected description, [probe], [impact], [friction], "
                          "[roughness], [crumble], modes)");
    }
  }

  Material material;  // built locally and returned whole: a throw leaves the caller's data alone
  material.name = name;
  // In the order of a material file, so the first problem in the file is the one reported.
  ParseDescription(root, source_name, material.description);
  ParseModes(root, source_name, material.params.resonator);
  ApplyTable(RequireTable(root, "probe", source_name), "probe", ProbeKeys(), material.params.probe,
             source_name);
  ApplyTable(RequireTable(root, "impact", source_name), "impact", ImpactKeys(),
             material.params.impact, source_name);
  if (const auto* scheme = RequireTable(root, "impact", source_name).get("scheme");
      scheme != nullptr && scheme->value<std::string>() == std::string(kBenchmarkSchemeName)) {
    const ContactChoice* row = ApplyContactChoice(name, material.params);
    material.contact_from_benchmark = row != nullptr;
    material.contact_budget_met = row != nullptr && row->budget_met;
  }
  const toml::table& friction = RequireTable(root, "friction", source_name);
  ApplyTable(friction, "friction", FrictionKeys(), material.params.friction, source_name);
  // Static friction below dynamic friction has no Stribeck dip and breaks z_ss's meaning.
  if (material.params.friction.dynamic_coefficient > material.params.friction.static_coefficient) {
    throw MaterialError(Where(source_name, LineOf(*friction.get("mu_d")), "friction.mu_d") +
                        "must not exceed friction.mu_s");
  }
  // A tap must not leave the speaker near full scale for seconds (a material within every key's
  // range can: light, undamped, loud modes). Refused rather than turned down: the file is wrong,
  // and staff should hear about it, not get a quietly different material.
  int worst = -1;
  if (const double ring = RingDownSeconds(material.params, &worst); ring > kRingDownMaxSeconds) {
    const auto& mode =
        material.params.resonator.modes[static_cast<std::size_t>(std::max(worst, 0))];
    std::ostringstream message;
    message << source_name << ": modes: a " << kRingDownTapMps
            << " m/s tap rings above -6 dBFS for " << ring << " s (at most " << kRingDownMaxSeconds
            << " s); loudest then: modes[" << worst << "] (" << mode.frequency_hz << " Hz, decay_s "
            << mode.decay_s << ", mass_kg " << mode.mass_kg << ", gain " << mode.gain
            << "): shorten its decay, raise its mass or lower its gain";
    throw MaterialError(message.str());
  }
  // Optional: a material without [roughness] is smooth below the picture's pixel.
  if (root.get("roughness") != nullptr) {
    ApplyTable(RequireTable(root, "roughness", source_name), "roughness", RoughnessKeys(),
               material.params.roughness, source_name);
    material.params.roughness.enabled = true;
  }
  // Optional: a material without [crumble] does not break under the tip.
  if (root.get("crumble") != nullptr) {
    const toml::table& crumble = RequireTable(root, "crumble", source_name);
    ApplyTable(crumble, "crumble", CrumbleKeys(), material.params.crumble, source_name);
    if (material.params.crumble.flake_low_hz > material.params.crumble.flake_high_hz) {
      throw MaterialError(Where(source_name, LineOf(*crumble.get("flake_low_hz")),
                                "crumble.flake_low_hz") +
                          "must not exceed crumble.flake_high_hz");
    }
    material.params.crumble.enabled = true;
  }
  return material;
}

double RingDownSeconds(const synth::MaterialParams& params, int* worst_mode) {
  // The whole pen taps: a body behind the nib lands on it through the sensor spring within a
  // couple of milliseconds, an impulse to every mode under a few hundred hertz.
  const double impulse = 2.0 * (params.probe.mass_kg + params.probe.body_mass_kg) * kRingDownTapMps;
  const auto amplitude = [&](double t, int* loudest) {
    double sum = 0.0, best = -1.0;
    for (int i = 0; i < params.resonator.mode_count; ++i) {
      const auto& mode = params.resonator.modes[static_cast<std::size_t>(i)];
      const double a = std::fabs(mode.gain) * impulse / mode.mass_kg * std::exp(-t / mode.decay_s);
      sum += a;
      if (loudest != nullptr && a > best) {
        best = a;
        *loudest = i;
      }
    }
    return sum;
  };
  if (worst_mode != nullptr) *worst_mode = -1;
  if (amplitude(0.0, nullptr) <= kRingDownLimit) return 0.0;
  // A(t) falls monotonically: bisect for the crossing (to 1 ms) within the longest plausible ring.
  double lo = 0.0, hi = 3600.0;
  if (amplitude(hi, nullptr) > kRingDownLimit) return hi;
  while (hi - lo > 1e-3) {
    const double mid = 0.5 * (lo + hi);
    (amplitude(mid, nullptr) > kRingDownLimit ? lo : hi) = mid;
  }
  if (worst_mode != nullptr) amplitude(lo, worst_mode);
  return hi;
}

Material LoadMaterialFile(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw MaterialError(path + ": cannot open material file");
  std::ostringstream text;
  text << file.rdbuf();
  return ParseMaterial(text.str(), path, fs::path(path).stem().string());
}

std::vector<std::string> ListMaterialNames(const std::string& directory) {
  std::vector<std::string> names;
  std::error_code error;
  for (fs::directory_iterator it(directory, error), end; !error && it != end; it.increment(error)) {
    if (it->path().extension() == ".toml" && it->is_regular_file(error)) {
      names.push_back(it->path().stem().string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<Material> LoadMaterialDirectory(const std::string& directory) {
  std::error_code error;
  if (!fs::is_directory(directory, error)) {
    throw MaterialError(directory + ": not a readable directory of material files");
  }
  const auto names = ListMaterialNames(directory);
  if (names.empty()) throw MaterialError(directory + ": holds no material files (*.toml)");
  std::vector<Material> materials;
  materials.reserve(names.size());
  for (const auto& name : names) {
    materials.push_back(LoadMaterialFile((fs::path(directory) / (name + ".toml")).string()));
  }
  return materials;
}

void MaterialLibrary::LoadDirectory(const std::string& directory) {
  auto loaded = LoadMaterialDirectory(directory);  // throws before touching materials_
  materials_ = std::move(loaded);
}

const Material* MaterialLibrary::Find(std::string_view name) const {
  for (const auto& material : materials_) {
    if (material.name == name) return &material;
  }
  return nullptr;
}

std::vector<std::string> MaterialLibrary::Names() const {
  std::vector<std::string> names;
  for (const auto& material : materials_) names.push_back(material.name);
  return names;
}

std::vector<std::string> MaterialSearchDirs(const std::string& cli_dir) {
  namespace fs = std::filesystem;
  std::vector<std::string> dirs;
  if (!cli_dir.empty()) dirs.push_back(cli_dir);
  if (const char* data_dir = std::getenv("SAS_DATA_DIR"); data_dir != nullptr && *data_dir) {
    dirs.push_back((fs::path(data_dir) / "materials").string());
  }
  dirs.push_back((fs::path(kSourceDir) / "textures" / "materials").string());
  dirs.push_back((fs::path(kInstallPrefix) / "share" / "sketch-a-scratch" / "materials").string());
  return dirs;
}

Material FindMaterial(const std::string& name, const std::vector<std::string>& dirs) {
  namespace fs = std::filesystem;
  std::set<std::string> available;
  for (const auto& dir : dirs) {
    const fs::path candidate = fs::path(dir) / (name + ".toml");
    std::error_code error;
    if (!name.empty() && name.find('/') == std::string::npos &&
        fs::is_regular_file(candidate, error)) {
      return LoadMaterialFile(candidate.string());
    }
    for (const auto& found : ListMaterialNames(dir)) available.insert(found);
  }
  const auto join = [](const auto& items) {
    std::string out;
    for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
    return out.empty() ? std::string("none") : out;
  };
  throw MaterialError("unknown material \"" + name + "\"; available: " + join(available) +
                      " (searched " + join(dirs) + ")");
}

}  // namespace sas::kiosk
