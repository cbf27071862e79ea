// libFuzzer target : arbitrary bytes as the kiosk's configuration file.
// ParseKioskConfig documents ConfigError for every bad file; anything else escaping (another
// exception, a crash, a sanitizer report) is a bug. Built with -fsanitize=fuzzer under SAS_FUZZ,
// or linked with replay_main.cpp so CTest replays the corpus and kept crash inputs every run.
#include <cstddef>
#include <cstdint>
#include <string>

#include "files/kiosk_config.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const sas::kiosk::KioskConfig config = sas::kiosk::ParseKioskConfig(text, "fuzz.toml");
    // A file that parsed must hold values the validator promised (ranges from kiosk_config.cpp).
    if (config.buffer_frames < 16 || config.buffer_frames > 4096) __builtin_trap();
    if (config.gpio_lines.size() != 5) __builtin_trap();
  } catch (const sas::kiosk::ConfigError&) {
    // documented rejection of a bad file
  }
  return 0;
}
