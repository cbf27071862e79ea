#pragma once
// VirtualVisit: drives a KioskEngine on its virtual clock the way the kiosk's devices would, one
// audio block at a time, for everything that plays a visit without real devices: the headless
// default (app/headless_demo.cpp), the soak run (tests/kiosk/kiosk_soak.cpp) and the texture
// loudness calibration (calibration/texture_levels.h), so the three drive the engine with one loop.
//
// Each block (config.buffer_frames frames, 128 at 48 kHz = 2.67 ms):
//   pen samples due before the block (a tablet's report rate, 200 Hz) -> KioskEngine::OnPen
//   -> KioskEngine::Tick (session timers, recording, switches) -> the microphone gets one block of
//   the scripted voice while the recorder is armed -> the platform's callback core renders one
//   device block through the engine's audio() (the player) -> the clock advances by the block.
// Hooks let the caller watch each step (the headless visit's view, the soak's NaN count).
// A straight pen stroke (StraightStroke) is the script all three use.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "kiosk/device_configs.h"
#include "kiosk/gesture.h"
#include "kiosk/kiosk_engine.h"
#include "platform/audio/audio_input.h"
#include "platform/audio/audio_output.h"

namespace sas::kiosk {

// One scripted pen report: the reading, and the probe style the script forces (a roll stroke).
struct ScriptedPen {
  platform::PenReading reading;
  std::optional<synth::ProbeStyle> style;
};
// The pen at time t (seconds on the visit's clock), or nothing (no report at that time).
using PenScript = std::function<std::optional<ScriptedPen>(double t_s)>;

// A straight stroke at constant speed between two points given as fractions of the screen.
struct PenStroke {
  double x0 = 0.2, y0 = 0.5, x1 = 0.8, y1 = 0.5;  // screen fractions
  double duration_s = 1.0;                        // tip down for this long, then lifted
  double pressure = 0.7;                          // 0..1
  double tilt_deg = 0.0;                          // upright = scrape, tilted = rub (gesture.h)
  std::optional<synth::ProbeStyle> style;         // forces a style (roll)
  // The pen hovers (tip up, in the tablet's range) for this long before touching down, moving
  // along the stroke's line at its speed, as a hand does coming in for a stroke: the kiosk then
  // knows the stroke's speed when the tip lands (KioskEngine's per-stroke gain).
  double hover_s = 0.0;
};

// The pen reports of `stroke` starting at `t0_s` on a screen of width x height pixels: a tablet
// (its tilt counts, leaning along x), hovering until t0 + hover_s, tip down for duration_s from
// then, then lifted at the end point with pressure 0.
PenScript StraightStroke(const PenStroke& stroke, double t0_s, int width_px, int height_px);

// The pen reports of `gesture` starting at `t0_s`: a tablet in range from t0 on, at the gesture's
// rows interpolated at each report, tip down while the gesture presses (kGesturePenUpPressure),
// lifted at its last point once it has ended. The gesture's millimetres are on the field under the
// pen (its top-left sample at 0, 0) and reach the screen through engine.FieldToScreen, so the pen
// lands where the gesture says on the field the kiosk plays (the picture covers the screen: a
// gesture off the shown crop is off the screen). `engine` must outlive the script.
PenScript GesturePenScript(Gesture gesture, const KioskEngine& engine, double t0_s,
                           std::optional<synth::ProbeStyle> style = {});

class VirtualVisit {
 public:
  struct Hooks {
    // Each pen reading, after the engine took it.
    std::function<void(const platform::PenReading&)> on_pen;
    std::function<void(std::vector<SessionAction>)> on_tick;  // the engine's actions each block
    std::function<void()> before_render;                      // after tick and microphone
    std::function<void(std::span<const float>)> on_block;     // each rendered block (clock moved)
  };

  // The engine must have been made with virtual_clock = true. `keep_output`: append every block
  // to output() (2 interleaved channels).
  VirtualVisit(KioskEngine& engine, Hooks hooks = {}, bool keep_output = true,
               double pen_rate_hz = 200.0);

  // Runs `seconds` of the visit (rounded up to whole blocks); `pen` reports at the pen rate.
  void Advance(double seconds, const PenScript& pen = {});

  // The fake microphone the engine's recorder belongs to, and what is "said" into it while the
  // recorder is armed (one block per audio block, silence after the end).
  void SetMicrophone(platform::FakeAudioInput* microphone) { microphone_ = microphone; }
  void SetVoice(std::vector<float> voice);
  std::size_t voice_left() const { return voice_.size() - voice_pos_; }

  std::int64_t now_ns() const { return now_ns_; }
  double now_s() const { return static_cast<double>(now_ns_) * 1e-9; }
  int block_frames() const { return block_frames_; }
  double sample_rate_hz() const { return fs_hz_; }
  const std::vector<float>& output() const { return output_; }
  std::size_t frames_kept() const { return output_.size() / 2; }
  void ClearOutput() { output_.clear(); }

 private:
  void FeedMicrophone();

  KioskEngine& engine_;
  Hooks hooks_;
  bool keep_output_;
  double pen_period_ns_;
  double fs_hz_;
  int block_frames_;
  platform::AudioCallbackCore core_;
  std::vector<float> block_;
  std::vector<float> output_;
  std::vector<float> mic_block_;
  platform::FakeAudioInput* microphone_ = nullptr;
  std::vector<float> voice_;
  std::size_t voice_pos_ = 0;
  std::int64_t now_ns_ = 0;
  std::int64_t next_pen_ns_ = 0;
};

}  // namespace sas::kiosk
