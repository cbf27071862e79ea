#pragma once
// Helpers shared by the fault-matrix test files.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "kiosk/kiosk_engine.h"

namespace sas::test {

// A kiosk texture of the source tree (kSasSourceDir: the fault-matrix executable's definition).
inline std::string TexturePath(const std::string& key) {
  return (std::filesystem::path(kSasSourceDir) / "textures" / key / "texture.toml").string();
}

// A whole file as bytes ("" when it cannot be read): what a row expects to find kept.
inline std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// One short stroke on a kiosk engine (tip down at 1 s, up 50 ms later): enough to count a visit
// and a stroke, which the fault-matrix rows then expect to find saved.
inline void OneStroke(sas::kiosk::KioskEngine& engine) {
  engine.SetAudioRunning(true);
  sas::platform::PenReading pen;
  pen.time_ns = 1'000'000'000;
  pen.x_px = 400;
  pen.y_px = 300;
  pen.pressure = 0.8;
  pen.tip_down = true;
  engine.OnPen(pen);
  pen.time_ns += 50'000'000;
  pen.tip_down = false;
  pen.pressure = 0.0;
  engine.OnPen(pen);
}

}  // namespace sas::test
