// SDL2 full-screen kiosk window: set-up, input mapping and drawing (see kiosk_window.h).
#include "ui/kiosk_window.h"

#include <SDL.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <map>
#include <utility>

#include "ui/display_probe.h"

namespace sas::ui {
namespace {

std::int64_t NowNs() {
  // steady_clock is CLOCK_MONOTONIC on Linux: the same clock libinput and libgpiod stamp with.
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// SDL stamps events with its millisecond tick at queue time; move that onto the monotonic clock
// by subtracting how long the event has waited in the queue.
std::int64_t EventTimeNs(Uint32 sdl_timestamp_ms) {
  const Uint32 now_ms = SDL_GetTicks();
  const Uint32 age_ms = now_ms >= sdl_timestamp_ms ? now_ms - sdl_timestamp_ms : 0;
  return NowNs() - static_cast<std::int64_t>(age_ms) * 1'000'000;
}

struct ParsedChord {
  SDL_Keycode key = SDLK_UNKNOWN;
  bool ctrl = false, alt = false, shift = false, gui = false;
};

ParsedChord ParseChord(const std::string& spec) {
  ParsedChord chord;
  std::string lowered(spec.size(), ' ');
  std::transform(spec.begin(), spec.end(), lowered.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  std::size_t start = 0;
  std::vector<std::string> parts;
  while (start <= lowered.size()) {
    const std::size_t plus = lowered.find('+', start);
    const std::size_t end = plus == std::string::npos ? lowered.size() : plus;
    parts.push_back(lowered.substr(start, end - start));
    if (plus == std::string::npos) break;
    start = plus + 1;
  }
  if (parts.empty() || parts.back().empty()) {
    throw WindowError("staff chord '" + spec + "': expected modifiers+key, e.g. ctrl+alt+s");
  }
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    const std::string& m = parts[i];
    if (m == "ctrl" || m == "control")
      chord.ctrl = true;
    else if (m == "alt")
      chord.alt = true;
    else if (m == "shift")
      chord.shift = true;
    else if (m == "super" || m == "gui" || m == "win")
      chord.gui = true;
    else
      throw WindowError("staff chord '" + spec + "': unknown modifier '" + m + "'");
  }
  chord.key = SDL_GetKeyFromName(parts.back().c_str());
  if (chord.key == SDLK_UNKNOWN) {
    throw WindowError("staff chord '" + spec + "': unknown key '" + parts.back() + "'");
  }
  if (!chord.ctrl && !chord.alt && !chord.gui) {
    // A chord a visitor can hit by leaning on a keyboard is no staff chord.
    throw WindowError("staff chord '" + spec + "': needs ctrl, alt or super");
  }
  return chord;
}

bool ModsSatisfy(const ParsedChord& c, Uint16 mod) {
  return (!c.ctrl || (mod & KMOD_CTRL)) && (!c.alt || (mod & KMOD_ALT)) &&
         (!c.shift || (mod & KMOD_SHIFT)) && (!c.gui || (mod & KMOD_GUI));
}

bool IsModifierKey(SDL_Keycode k) {
  return k == SDLK_LCTRL || k == SDLK_RCTRL || k == SDLK_LALT || k == SDLK_RALT ||
         k == SDLK_LSHIFT || k == SDLK_RSHIFT || k == SDLK_LGUI || k == SDLK_RGUI;
}

int TokenForKey(SDL_Keycode k) {
  switch (k) {
    case SDLK_1:
    case SDLK_KP_1:
      return 0;
    case SDLK_2:
    case SDLK_KP_2:
      return 1;
    case SDLK_3:
    case SDLK_KP_3:
      return 2;
    case SDLK_4:
    case SDLK_KP_4:
      return 3;
    case SDLK_0:
    case SDLK_KP_0:
      return -1;
    default:
      return -2;  // not a token key
  }
}

}  // namespace

float PressRamp::At(double held_s) const {
  const double rise = rise_s > 0.0 ? std::clamp(held_s / rise_s, 0.0, 1.0) : 1.0;
  return static_cast<float>(light + (firm - light) * rise);
}

struct KioskWindow::Impl {
  KioskWindowOptions options;
  ParsedChord chord;
  bool sdl_video = false;
  SDL_Window* window = nullptr;
  SDL_Renderer* renderer = nullptr;
  int width = 0, height = 0, refresh = 0;
  float scale_x = 1.0f, scale_y = 1.0f;  // window coordinates -> drawable pixels (HiDPI)
  Uint32 window_id = 0;

  // Input state.
  bool mouse_down = false;  // the left or the right button is held (a stroke)
  bool left_held = false, right_held = false;
  bool roll_key = false;  // Space held: the stroke rolls
  bool finger_active = false;
  SDL_FingerID finger = 0;
  bool press_ramps = false;         // this stroke's pressure comes from options.press
  std::int64_t press_since_ns = 0;  // when its button or finger went down
  bool rest_reported = false;       // the resting press has nothing more to report
  platform::PenReading last{};
  bool chord_held = false;
  bool chord_fired = false;
  std::int64_t chord_since_ns = 0;
  bool staff_open = false;
  std::int64_t last_event_ns = 0;

  // GPU textures of the pictures on screen (at most two: current and cross-fade source).
  struct Cached {
    std::shared_ptr<const ImageRgba> picture;
    SDL_Texture* texture = nullptr;
  };
  std::vector<Cached> cache;
  SDL_Texture* patch_texture = nullptr;
  int patch_w = 0, patch_h = 0;
  // GPU textures of the text lines on screen (white, alpha = coverage; tinted when drawn), kept
  // while a frame still shows them.
  struct TextTexture {
    std::shared_ptr<const TextMask> mask;
    SDL_Texture* texture = nullptr;
    bool used = false;
  };
  std::map<const TextMask*, TextTexture> text_textures;

  ~Impl() { Close(); }

  SDL_Texture* TextureFor(const std::shared_ptr<const TextMask>& mask) {
    auto& entry = text_textures[mask.get()];
    entry.used = true;
    if (entry.texture != nullptr || mask->w <= 0 || mask->h <= 0) return entry.texture;
    entry.mask = mask;
    std::vector<std::uint8_t> rgba(mask->alpha.size() * 4, 255);
    for (std::size_t i = 0; i < mask->alpha.size(); ++i) rgba[4 * i + 3] = mask->alpha[i];
    entry.texture = SDL_CreateTexture(renderer, SDL_PIXELFORMAT_RGBA32, SDL_TEXTUREACCESS_STATIC,
                                      mask->w, mask->h);
    if (entry.texture != nullptr) {
      SDL_UpdateTexture(entry.texture, nullptr, rgba.data(), mask->w * 4);
      SDL_SetTextureBlendMode(entry.texture, SDL_BLENDMODE_BLEND);
    }
    return entry.texture;
  }

  void ReleaseUnusedText() {
    for (auto it = text_textures.begin(); it != text_textures.end();) {
      if (!it->second.used) {
        if (it->second.texture) SDL_DestroyTexture(it->second.texture);
        it = text_textures.erase(it);
      } else {
        it->second.used = false;
        ++it;
      }
    }
  }

  // Event time on the monotonic clock, never earlier than the previous event's: SDL's 1 ms
  // timestamps could otherwise put two close events out of order, and the audio side splits its
  // blocks at event times.
  std::int64_t Stamp(Uint32 sdl_timestamp_ms) {
    last_event_ns = std::max(last_event_ns, EventTimeNs(sdl_timestamp_ms));
    return last_event_ns;
  }

  void Close() {
    for (auto& c : cache) SDL_DestroyTexture(c.texture);
    cache.clear();
    for (auto& [mask, text] : text_textures) {
      if (text.texture) SDL_DestroyTexture(text.texture);
    }
    text_textures.clear();
    if (patch_texture) SDL_DestroyTexture(patch_texture);
    patch_texture = nullptr;
    patch_w = patch_h = 0;
    if (renderer) SDL_DestroyRenderer(renderer);
    renderer = nullptr;
    if (window) SDL_DestroyWindow(window);
    window = nullptr;
    if (sdl_video) SDL_QuitSubSystem(SDL_INIT_VIDEO);
    sdl_video = false;
  }

  void UpdateSize() {
    int win_w = 0, win_h = 0;
    SDL_GetWindowSize(window, &win_w, &win_h);
    SDL_GetRendererOutputSize(renderer, &width, &height);
    scale_x = win_w > 0 ? static_cast<float>(width) / static_cast<float>(win_w) : 1.0f;
    scale_y = win_h > 0 ? static_cast<float>(height) / static_cast<float>(win_h) : 1.0f;
  }

  SDL_Texture* TextureFor(const std::shared_ptr<const ImageRgba>& picture) {
    for (auto& c : cache) {
      if (c.picture == picture) return c.texture;
    }
    SDL_Texture* t = SDL_CreateTexture(renderer, SDL_PIXELFORMAT_RGBA32, SDL_TEXTUREACCESS_STATIC,
                                       picture->width(), picture->height());
    if (t == nullptr) return nullptr;
    SDL_UpdateTexture(t, nullptr, picture->data(), picture->pitch_bytes());
    cache.push_back({picture, t});
    return t;
  }

  void EvictExcept(const Frame& frame) {
    std::erase_if(cache, [&](Cached& c) {
      if (c.picture == frame.picture || c.picture == frame.fade_from) return false;
      SDL_DestroyTexture(c.texture);
      return true;
    });
  }

  platform::PenReading Sample(float x_win, float y_win, bool down, float pressure,
                              platform::PenOrigin origin, std::int64_t t_ns) const {
    platform::PenReading s;
    s.time_ns = t_ns;
    s.x_px = x_win * scale_x;
    s.y_px = y_win * scale_y;
    s.tip_down = down;
    s.pressure = down ? std::clamp(pressure, 0.0f, 1.0f) : 0.0f;
    s.origin = origin;
    s.barrel_button = roll_key || (origin == platform::PenOrigin::kMouse && right_held);
    return s;
  }

  // The mouse's (or a pressure-less finger's) press at `t_ns` into the stroke.
  float RampedPress(std::int64_t t_ns) const {
    return options.press.At(static_cast<double>(t_ns - press_since_ns) * 1e-9);
  }

  // The stroke's last reading again at `t_ns` with what changed without a motion event: the
  // grown press, or the barrel button's stand-ins (then a kButton reading: no new position).
  void Resend(std::vector<UiEvent>& out, std::int64_t t_ns, platform::PenReadingKind kind) {
    platform::PenReading s = last;
    s.time_ns = t_ns;
    s.kind = kind;
    if (press_ramps) s.pressure = RampedPress(t_ns);
    s.barrel_button = roll_key || (s.origin == platform::PenOrigin::kMouse && right_held);
    Pointer(out, UiEvent::Kind::kPointerMove, s);
  }

  bool Pressing() const { return mouse_down || finger_active; }

  // Called after a poll that left SDL's queue empty: a press resting longer than kPressReportS
  // reports its grown pressure, and that it rests (the probe stops instead of sliding on at the
  // last motion's speed), until the press is firm.
  void ReportRestingPress(std::vector<UiEvent>& out) {
    if (!Pressing() || rest_reported) return;
    const std::int64_t now = NowNs();
    if (static_cast<double>(now - last.time_ns) * 1e-9 < KioskWindow::kPressReportS) return;
    last_event_ns = std::max(last_event_ns, now);
    Resend(out, last_event_ns, platform::PenReadingKind::kMotion);
    rest_reported = !press_ramps || last.pressure >= options.press.firm;
  }

  void Pointer(std::vector<UiEvent>& out, UiEvent::Kind kind, const platform::PenReading& s) {
    UiEvent e;
    e.kind = kind;
    e.time_ns = s.time_ns;
    e.stylus = s;
    last = s;
    rest_reported = false;
    out.push_back(e);
  }

  void FireChord(std::vector<UiEvent>& out, std::int64_t t_ns) {
    chord_fired = true;
    staff_open = !staff_open;
    UiEvent e;
    e.kind = UiEvent::Kind::kStaffChord;
    e.time_ns = t_ns;
    e.pressed = staff_open;
    out.push_back(e);
  }

  void Key(const SDL_KeyboardEvent& k, bool down, std::vector<UiEvent>& out) {
    const std::int64_t t = Stamp(k.timestamp);
    const SDL_Keycode code = k.keysym.sym;
    if (code == chord.key || IsModifierKey(code)) {
      if (down && code == chord.key && !k.repeat && ModsSatisfy(chord, k.keysym.mod)) {
        chord_held = true;
        chord_fired = false;
        chord_since_ns = t;
        if (options.staff_chord.hold_s <= 0.0) FireChord(out, t);
      } else if (!down) {
        // Held long enough by the events' time stamps: it counts. SDL stamps an event when it
        // reads it from the kernel, not when the key moved, so this holds across a slow frame
        // only if SDL read the press before the frame and the release after it; a press and
        // release read together look instant (staff hold the chord until the panel answers).
        if (chord_held && !chord_fired &&
            static_cast<double>(t - chord_since_ns) * 1e-9 >= options.staff_chord.hold_s) {
          FireChord(out, t);
        }
        chord_held = false;  // any part of the chord released: start over
      }
      if (code == chord.key) return;  // the chord's key is not also a token/record key
    }
    if (k.repeat) return;
    if (code == SDLK_SPACE) {
      // The roll key: a stroke under way switches at once (and back on release).
      roll_key = down;
      if (Pressing()) Resend(out, t, platform::PenReadingKind::kButton);
      return;
    }
    const int token = TokenForKey(code);
    if (token >= -1 && down) {
      UiEvent e;
      e.kind = UiEvent::Kind::kTokenKey;
      e.time_ns = t;
      e.token = token;
      out.push_back(e);
    } else if (code == SDLK_r) {
      UiEvent e;
      e.kind = UiEvent::Kind::kRecordKey;
      e.time_ns = t;
      e.pressed = down;
      out.push_back(e);
    } else if (code == SDLK_l && down) {
      UiEvent e;
      e.kind = UiEvent::Kind::kLanguageKey;
      e.time_ns = t;
      out.push_back(e);
    }
    // Everything else — Escape, Alt-F4, Ctrl-Q, Ctrl-W... — is deliberately ignored.
  }

  void Handle(const SDL_Event& ev, std::vector<UiEvent>& out) {
    switch (ev.type) {
      case SDL_QUIT:
        return;  // no quit path for a visitor (the staff stop the service)
      case SDL_WINDOWEVENT:
        switch (ev.window.event) {
          case SDL_WINDOWEVENT_MINIMIZED:
          case SDL_WINDOWEVENT_HIDDEN:
            // Something pushed us away (a WM shortcut): come straight back.
            SDL_RestoreWindow(window);
            SDL_RaiseWindow(window);
            return;
          case SDL_WINDOWEVENT_SIZE_CHANGED:
          case SDL_WINDOWEVENT_RESIZED:
            UpdateSize();
            [[fallthrough]];
          case SDL_WINDOWEVENT_EXPOSED:
          case SDL_WINDOWEVENT_SHOWN:
          case SDL_WINDOWEVENT_RESTORED: {
            UiEvent e;
            e.kind = UiEvent::Kind::kRedraw;
            e.time_ns = Stamp(ev.window.timestamp);
            out.push_back(e);
            return;
          }
          default:
            return;  // SDL_WINDOWEVENT_CLOSE included: swallowed
        }
      case SDL_MOUSEBUTTONDOWN:
      case SDL_MOUSEBUTTONUP: {
        // Left or right button: a stroke while either is held; the right one rolls it.
        const bool left = ev.button.button == SDL_BUTTON_LEFT;
        if (ev.button.which == SDL_TOUCH_MOUSEID || finger_active ||
            (!left && ev.button.button != SDL_BUTTON_RIGHT))
          return;
        const bool down = ev.type == SDL_MOUSEBUTTONDOWN;
        bool& held = left ? left_held : right_held;
        if (held == down) return;
        held = down;
        const std::int64_t t = Stamp(ev.button.timestamp);
        if (mouse_down == (left_held || right_held)) {
          // The other button is still held: only the roll changed.
          Resend(out, t, platform::PenReadingKind::kButton);
          return;
        }
        mouse_down = down;
        if (down) {
          press_ramps = true;
          press_since_ns = t;
        }
        Pointer(out, down ? UiEvent::Kind::kPointerDown : UiEvent::Kind::kPointerUp,
                Sample(static_cast<float>(ev.button.x), static_cast<float>(ev.button.y), down,
                       down ? RampedPress(t) : 0.0f, platform::PenOrigin::kMouse, t));
        return;
      }
      case SDL_MOUSEMOTION: {
        if (ev.motion.which == SDL_TOUCH_MOUSEID || finger_active) return;
        const std::int64_t t = Stamp(ev.motion.timestamp);
        Pointer(out, UiEvent::Kind::kPointerMove,
                Sample(static_cast<float>(ev.motion.x), static_cast<float>(ev.motion.y), mouse_down,
                       RampedPress(t), platform::PenOrigin::kMouse, t));
        return;
      }
      case SDL_FINGERDOWN:
      case SDL_FINGERMOTION:
      case SDL_FINGERUP: {
        const auto& f = ev.tfinger;
        if (ev.type == SDL_FINGERDOWN) {
          if (finger_active || mouse_down) return;  // one stylus: later fingers are ignored
          finger_active = true;
          finger = f.fingerId;
        } else if (!finger_active || f.fingerId != finger) {
          return;
        }
        int win_w = 0, win_h = 0;
        SDL_GetWindowSize(window, &win_w, &win_h);
        const float x = f.x * static_cast<float>(win_w);  // touch coordinates are 0..1
        const float y = f.y * static_cast<float>(win_h);
        const std::int64_t t = Stamp(f.timestamp);
        // Panels without a pressure sensor report 0 or 1: treat "no reading" like the mouse.
        if (ev.type == SDL_FINGERDOWN) {
          press_ramps = !(f.pressure > 0.0f);
          press_since_ns = t;
        } else if (f.pressure > 0.0f) {
          press_ramps = false;
        }
        const float pressure = press_ramps ? RampedPress(t) : f.pressure;
        const bool up = ev.type == SDL_FINGERUP;
        if (up) finger_active = false;
        Pointer(out,
                ev.type == SDL_FINGERDOWN ? UiEvent::Kind::kPointerDown
                : up                      ? UiEvent::Kind::kPointerUp
                                          : UiEvent::Kind::kPointerMove,
                Sample(x, y, !up, pressure, platform::PenOrigin::kTouch, t));
        return;
      }
      case SDL_KEYDOWN:
      case SDL_KEYUP:
        Key(ev.key, ev.type == SDL_KEYDOWN, out);
        return;
      default:
        return;
    }
  }
};

KioskWindow::KioskWindow(KioskWindowOptions options) : impl_(std::make_unique<Impl>()) {
  impl_->options = std::move(options);
}
KioskWindow::~KioskWindow() = default;
KioskWindow::KioskWindow(KioskWindow&&) noexcept = default;
KioskWindow& KioskWindow::operator=(KioskWindow&&) noexcept = default;

void KioskWindow::Open() {
  Impl& m = *impl_;
  if (m.window) return;
  m.chord = ParseChord(m.options.staff_chord.keys);
  // Before SDL_Init: SIGTERM/SIGINT must stop the process (systemd), not become an SDL_QUIT we
  // swallow; a full-screen kiosk must not minimise when focus moves; no screensaver.
  SDL_SetHint(SDL_HINT_NO_SIGNAL_HANDLERS, "1");
  SDL_SetHint(SDL_HINT_VIDEO_MINIMIZE_ON_FOCUS_LOSS, "0");
  SDL_SetHint(SDL_HINT_VIDEO_ALLOW_SCREENSAVER, "0");
  SDL_SetHint(SDL_HINT_MOUSE_TOUCH_EVENTS, "0");
  SDL_SetHint(SDL_HINT_GRAB_KEYBOARD, m.options.grab_keyboard ? "1" : "0");
  SkipUnreachableWayland();
  if (SDL_InitSubSystem(SDL_INIT_VIDEO) != 0) {
    throw WindowError(std::string("SDL video: ") + SDL_GetError());
  }
  m.sdl_video = true;
  // A display that fails to open (an X server too slow to answer, a DRM device another process
  // still holds at boot) makes SDL fall back to its invisible offscreen driver: the kiosk would
  // run for no one while its supervisor sees it healthy. That is an error the caller can retry.
  const char* driver = SDL_GetCurrentVideoDriver();
  if (IsUnrequestedVirtualDriver(driver != nullptr ? driver : "")) {
    m.Close();
    throw WindowError(std::string("no x11, wayland or KMSDRM display would open (SDL fell back to "
                                  "its virtual '") +
                      (driver != nullptr ? driver : "") + "' driver)");
  }
  SDL_DisplayMode mode{};
  if (SDL_GetDesktopDisplayMode(0, &mode) != 0 || mode.w <= 0 || mode.h <= 0) {
    const std::string why = SDL_GetError();
    m.Close();
    throw WindowError("no desktop display mode: " + why);
  }
  m.refresh = mode.refresh_rate;
  // The desktop size, not 0x0: see the header (1x1 window under X with no window manager).
  const Uint32 flags =
      SDL_WINDOW_FULLSCREEN_DESKTOP | SDL_WINDOW_BORDERLESS | SDL_WINDOW_SHOWN |
      SDL_WINDOW_ALWAYS_ON_TOP |
      (m.options.grab_keyboard ? static_cast<Uint32>(SDL_WINDOW_KEYBOARD_GRABBED) : 0U);
  m.window = SDL_CreateWindow(m.options.title.c_str(), SDL_WINDOWPOS_UNDEFINED_DISPLAY(0),
                              SDL_WINDOWPOS_UNDEFINED_DISPLAY(0), mode.w, mode.h, flags);
  if (m.window == nullptr) {
    const std::string why = SDL_GetError();
    m.Close();
    throw WindowError("cannot open the window: " + why);
  }
  m.window_id = SDL_GetWindowID(m.window);
  const Uint32 vsync = m.options.vsync ? static_cast<Uint32>(SDL_RENDERER_PRESENTVSYNC) : 0U;
  // On the bare display (KMSDRM: EGL on GBM) SDL's first choice, desktop OpenGL, gets a context
  // with Mesa but shows a black screen; OpenGL ES 2 is EGL's own API there and draws. A
  // SDL_RENDER_DRIVER set in the environment still wins (a normal-priority hint yields to it).
  const char* video_driver = SDL_GetCurrentVideoDriver();
  if (video_driver != nullptr && std::string(video_driver) == "KMSDRM")
    SDL_SetHint(SDL_HINT_RENDER_DRIVER, "opengles2");
  m.renderer = SDL_CreateRenderer(m.window, -1, SDL_RENDERER_ACCELERATED | vsync);
  if (m.renderer == nullptr) m.renderer = SDL_CreateRenderer(m.window, -1, SDL_RENDERER_SOFTWARE);
  if (m.renderer == nullptr) {
    const std::string why = SDL_GetError();
    m.Close();
    throw WindowError("cannot create a renderer: " + why);
  }
  SDL_ShowCursor(SDL_DISABLE);
  SDL_DisableScreenSaver();
  m.UpdateSize();
}

void KioskWindow::Close() {
  impl_->Close();
}
bool KioskWindow::is_open() const {
  return impl_ && impl_->window != nullptr;
}
int KioskWindow::width_px() const {
  return impl_->width;
}
int KioskWindow::height_px() const {
  return impl_->height;
}
int KioskWindow::refresh_hz() const {
  return impl_->refresh;
}

std::string KioskWindow::driver() const {
  const char* d = impl_->sdl_video ? SDL_GetCurrentVideoDriver() : nullptr;
  return d ? d : "";
}

std::string KioskWindow::renderer_name() const {
  SDL_RendererInfo info{};
  if (!impl_->renderer || SDL_GetRendererInfo(impl_->renderer, &info) != 0) return "";
  return info.name ? info.name : "";
}

bool KioskWindow::staff_panel_open() const {
  return impl_->staff_open;
}
void KioskWindow::set_staff_panel_open(bool open) {
  impl_->staff_open = open;
}

std::vector<UiEvent> KioskWindow::PollEvents(int wait_ms, std::size_t max_sdl_events) {
  Impl& m = *impl_;
  std::vector<UiEvent> out;
  if (!m.window) return out;
  SDL_Event ev;
  std::size_t taken = 0;
  if (wait_ms > 0 && max_sdl_events > 0) {
    // Never sleep past the moment a held staff chord completes.
    if (m.chord_held && !m.chord_fired) {
      const double left_ms = m.options.staff_chord.hold_s * 1e3 -
                             static_cast<double>(NowNs() - m.chord_since_ns) * 1e-6;
      wait_ms = std::clamp(static_cast<int>(std::ceil(left_ms)), 1, wait_ms);
    }
    if (SDL_WaitEventTimeout(&ev, wait_ms) == 1) {
      m.Handle(ev, out);
      ++taken;
    }
  }
  while (taken < max_sdl_events && SDL_PollEvent(&ev) == 1) {
    m.Handle(ev, out);
    ++taken;
  }
  if (taken < max_sdl_events) m.ReportRestingPress(out);
  if (m.chord_held && !m.chord_fired) {
    const std::int64_t now = NowNs();
    if (static_cast<double>(now - m.chord_since_ns) * 1e-9 >= m.options.staff_chord.hold_s) {
      m.last_event_ns = std::max(m.last_event_ns, now);
      m.FireChord(out, m.last_event_ns);
    }
  }
  return out;
}

void KioskWindow::Present(const Frame& frame, ImageRgba* read_back) {
  Impl& m = *impl_;
  if (!m.renderer) throw WindowError("Present on a closed window");
  SDL_SetRenderDrawBlendMode(m.renderer, SDL_BLENDMODE_NONE);
  SDL_SetRenderDrawColor(m.renderer, 0, 0, 0, 255);
  SDL_RenderClear(m.renderer);
  m.EvictExcept(frame);
  const SDL_Rect full{0, 0, frame.width, frame.height};
  if (frame.fade_from) {
    if (SDL_Texture* from = m.TextureFor(frame.fade_from)) {
      SDL_SetTextureBlendMode(from, SDL_BLENDMODE_NONE);
      SDL_RenderCopy(m.renderer, from, nullptr, &full);
    }
  }
  if (frame.picture) {
    if (SDL_Texture* pic = m.TextureFor(frame.picture)) {
      const bool fading = frame.fade_from != nullptr;
      SDL_SetTextureBlendMode(pic, fading ? SDL_BLENDMODE_BLEND : SDL_BLENDMODE_NONE);
      const auto alpha = static_cast<Uint8>(
          std::lround(255.0f * (fading ? std::clamp(frame.fade_weight, 0.0f, 1.0f) : 1.0f)));
      SDL_SetTextureAlphaMod(pic, alpha);
      SDL_RenderCopy(m.renderer, pic, nullptr, &full);
    }
  }
  if (!frame.patch_rect.empty()) {
    if (frame.patch_rect.w > m.patch_w || frame.patch_rect.h > m.patch_h) {
      if (m.patch_texture) SDL_DestroyTexture(m.patch_texture);
      m.patch_w = std::max(frame.patch_rect.w, 256);
      m.patch_h = std::max(frame.patch_rect.h, 256);
      m.patch_texture = SDL_CreateTexture(m.renderer, SDL_PIXELFORMAT_RGBA32,
                                          SDL_TEXTUREACCESS_STREAMING, m.patch_w, m.patch_h);
      if (m.patch_texture) SDL_SetTextureBlendMode(m.patch_texture, SDL_BLENDMODE_NONE);
    }
    if (m.patch_texture) {
      const SDL_Rect src{0, 0, frame.patch_rect.w, frame.patch_rect.h};
      const SDL_Rect dst{frame.patch_rect.x, frame.patch_rect.y, frame.patch_rect.w,
                         frame.patch_rect.h};
      SDL_UpdateTexture(m.patch_texture, &src, frame.patch.data(), frame.patch.pitch_bytes());
      SDL_RenderCopy(m.renderer, m.patch_texture, &src, &dst);
    }
  }
  SDL_SetRenderDrawBlendMode(m.renderer, SDL_BLENDMODE_BLEND);
  for (const auto& s : frame.overlays) {
    const SDL_Rect r{s.rect.x, s.rect.y, s.rect.w, s.rect.h};
    if (s.mask) {
      // The same pixels as DrawOverlays: the colour at its alpha times the coverage.
      if (SDL_Texture* text = m.TextureFor(s.mask)) {
        SDL_SetTextureColorMod(text, s.color.r, s.color.g, s.color.b);
        SDL_SetTextureAlphaMod(text, s.color.a);
        const SDL_Rect size{s.rect.x, s.rect.y, s.mask->w, s.mask->h};
        SDL_RenderCopy(m.renderer, text, nullptr, &size);
      }
      continue;
    }
    SDL_SetRenderDrawColor(m.renderer, s.color.r, s.color.g, s.color.b, s.color.a);
    SDL_RenderFillRect(m.renderer, &r);
  }
  m.ReleaseUnusedText();
  if (read_back) {
    read_back->Reshape(m.width, m.height);
    if (SDL_RenderReadPixels(m.renderer, nullptr, SDL_PIXELFORMAT_RGBA32, read_back->data(),
                             read_back->pitch_bytes()) != 0) {
      throw WindowError(std::string("cannot read the frame back: ") + SDL_GetError());
    }
  }
  SDL_RenderPresent(m.renderer);
}

}  // namespace sas::ui
