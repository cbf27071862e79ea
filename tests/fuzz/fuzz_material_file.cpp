// libFuzzer target : arbitrary bytes as a material file
// (textures/materials/<name>.toml). ParseMaterial documents MaterialError for every bad file;
// anything else escaping is a bug. See fuzz_kiosk_config.cpp for how the targets are built.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "files/material_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const sas::kiosk::Material material = sas::kiosk::ParseMaterial(text, "fuzz.toml", "fuzz");
    // An accepted material has only finite, in-band modes (material_file.h's promise).
    const auto& resonator = material.params.resonator;
    if (resonator.mode_count < 1 ||
        resonator.mode_count > static_cast<int>(resonator.modes.size())) {
      __builtin_trap();
    }
    for (int i = 0; i < resonator.mode_count; ++i) {
      const double f = resonator.modes[static_cast<std::size_t>(i)].frequency_hz;
      if (!std::isfinite(f) || f > sas::kiosk::kMaxModeFrequencyHz) __builtin_trap();
    }
  } catch (const sas::kiosk::MaterialError&) {
    // documented rejection of a bad file
  }
  return 0;
}
