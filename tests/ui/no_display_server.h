#pragma once
// For one test: no X or Wayland display and no video driver asked for by name, as on a server or
// a console without KMS; the environment is put back afterwards.
#include <cstdlib>
#include <string>

namespace sas::test {

class NoDisplayServer {
 public:
  NoDisplayServer() {
    Save("DISPLAY", display_);
    Save("WAYLAND_DISPLAY", wayland_);
    unsetenv("SDL_VIDEODRIVER");
  }
  ~NoDisplayServer() {
    if (!display_.empty()) setenv("DISPLAY", display_.c_str(), 1);
    if (!wayland_.empty()) setenv("WAYLAND_DISPLAY", wayland_.c_str(), 1);
  }
  NoDisplayServer(const NoDisplayServer&) = delete;
  NoDisplayServer& operator=(const NoDisplayServer&) = delete;

 private:
  static void Save(const char* name, std::string& value) {
    if (const char* set = std::getenv(name)) value = set;
    unsetenv(name);
  }
  std::string display_, wayland_;
};

}  // namespace sas::test
