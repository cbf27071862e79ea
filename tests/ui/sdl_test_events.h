#pragma once
// The window tests' input: SDL's offscreen video driver for one test, and SDL events pushed into
// SDL's queue as the devices would put them there.
#include <SDL.h>

#include <catch2/catch.hpp>
#include <cstdlib>

namespace sas::test {

// Selects the offscreen driver for one test and restores the environment after it.
struct OffscreenDriver {
  OffscreenDriver() { setenv("SDL_VIDEODRIVER", "offscreen", 1); }
  ~OffscreenDriver() { unsetenv("SDL_VIDEODRIVER"); }
};

inline void PushKey(SDL_Keycode key, bool down, Uint16 mod = KMOD_NONE) {
  SDL_Event e{};
  e.type = down ? SDL_KEYDOWN : SDL_KEYUP;
  e.key.state = down ? SDL_PRESSED : SDL_RELEASED;
  e.key.keysym.sym = key;
  e.key.keysym.scancode = SDL_GetScancodeFromKey(key);
  e.key.keysym.mod = mod;
  REQUIRE(SDL_PushEvent(&e) == 1);
}

inline void PushMouseButton(int x, int y, bool down, Uint8 button = SDL_BUTTON_LEFT) {
  SDL_Event e{};
  e.type = down ? SDL_MOUSEBUTTONDOWN : SDL_MOUSEBUTTONUP;
  e.button.button = button;
  e.button.state = down ? SDL_PRESSED : SDL_RELEASED;
  e.button.clicks = 1;
  e.button.x = x;
  e.button.y = y;
  REQUIRE(SDL_PushEvent(&e) == 1);
}

inline void PushMouseMotion(int x, int y) {
  SDL_Event e{};
  e.type = SDL_MOUSEMOTION;
  e.motion.x = x;
  e.motion.y = y;
  REQUIRE(SDL_PushEvent(&e) == 1);
}

}  // namespace sas::test
