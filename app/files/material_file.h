#pragma once
// Materials as data: one TOML file per material (textures/materials/<name>.toml) holding the
// resonator's modes, the Hunt–Crossley impact, the elasto-plastic friction and the probe, with
// units in the key names and a one-line description (format in
// textures/materials/README.md). Loading fills a synth::MaterialParams at set-up time, never on
// the audio thread.
//
// Validation is strict because a typo in a material file must not silently become a default: an
// unknown key, a missing key, a wrong type, NaN/Inf or a value out of range throws MaterialError
// "<file>:<line>: <key>: <what>". Everything is parsed into a local object and returned only when
// the whole file (or directory) is good, so a failed load never leaves anything half-loaded.

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "synth/material_params.h"

namespace sas::kiosk {

class MaterialError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Material {
  std::string name;         // the file name without ".toml"
  std::string description;  // one line for people (staff panel, --help, README)
  synth::MaterialParams params;
  // The file asked for the benchmark's contact choice and the table has this material's row
  // (files/contact_choice.h).
  bool contact_from_benchmark = false;
  // ... and that row meets the error budget (false: none did within the tool's cost ceiling; the
  // row is the policy as close to the reference as the built-in one).
  bool contact_budget_met = false;
};

// Highest mode frequency a material file may hold: 0.45 of the kiosk's 48 kHz rate. The synth drops
// modes above 0.45 fs at lower rates by itself.
inline constexpr double kMaxModeFrequencyHz = 0.45 * 48000.0;

// A material that rings too loud for too long (a tap must not leave the speaker near full scale
// for seconds): the tap is kRingDownTapMps with the material's probe; the ring-down bound is
// A(t) = Σ |gain_i| (J / m_i) e^(-t / τ_i) with J = 2 m_probe v (an elastic bounce off a rigid
// body, the most momentum a tap can give), every mode in phase: no real ring-down is louder.
// Returns how long A stays above kRingDownLimit (linear, at 0 dB gain) in seconds, and the mode
// that keeps it there longest in `worst_mode` (may be null).
inline constexpr double kRingDownTapMps = 0.5;
inline constexpr double kRingDownLimit = 0.5;       // -6 dBFS
inline constexpr double kRingDownMaxSeconds = 2.0;  // materials ringing longer are refused
double RingDownSeconds(const synth::MaterialParams& params, int* worst_mode = nullptr);

// Parses one material from text; `source_name` is used in messages, `name` becomes Material::name.
Material ParseMaterial(const std::string& text, const std::string& source_name,
                       const std::string& name);
// Reads `path`; the material's name is the file's stem (wood.toml -> "wood").
Material LoadMaterialFile(const std::string& path);
// Every *.toml file in `directory`, sorted by name. Throws on the first bad file (naming it) or
// when the directory cannot be read or holds no material.
std::vector<Material> LoadMaterialDirectory(const std::string& directory);
// The names of the *.toml files in `directory`, sorted; empty if it does not exist.
std::vector<std::string> ListMaterialNames(const std::string& directory);

// The material directories to search, in order (existing or not): `cli_dir` (a --materials-dir
// option) when given, $SAS_DATA_DIR/materials, the source tree, the installed share directory.
std::vector<std::string> MaterialSearchDirs(const std::string& cli_dir);
// Loads material `name` from the first directory in `dirs` holding it. Throws MaterialError
// listing the available materials and the directories searched when none does, or when the file
// is bad.
Material FindMaterial(const std::string& name, const std::vector<std::string>& dirs);

// The set of materials the kiosk offers. Reloading is all-or-nothing: a directory with one bad file
// throws and the library keeps the materials it had.
class MaterialLibrary {
 public:
  void LoadDirectory(const std::string& directory);
  const Material* Find(std::string_view name) const;
  std::vector<std::string> Names() const;
  const std::vector<Material>& materials() const { return materials_; }

 private:
  std::vector<Material> materials_;
};

}  // namespace sas::kiosk
