#pragma once
// The synth's top level: one probe (the stylus tip) touching one resonating material over a
// surface profile, rendered to two channels. Chain per sample (paper §4):
//   ProbeCommand -> SurfaceReader (profile under the probe: width window, penetration threshold,
//   scrape | rub | roll) -> contact (Hunt–Crossley normal force + elasto-plastic friction, solved
//   together with the probe mass and the resonator) -> ModalResonator (exact per-mode update)
//   -> OutputStage (ch 1 sound: gain + soft limiter; ch 2 haptic: the contact force in 40–400 Hz,
//   gain, limiter, band limit).
// Process() loops one inline per-sample kernel; the block is split at the commands' frame
// offsets, so rendering in any block size gives bit-identical output. Process() allocates nothing,
// takes no lock, throws nothing, does no I/O, and runs with denormals flushed (FTZ/DAZ).
// Work that cannot change the output is skipped (SceneSkips below); each skip has a
// test comparing it with the full computation (tests/synth/test_skips.cpp).

#include <cstdint>
#include <memory>

#include "synth/height_field_view.h"
#include "synth/material_params.h"
#include "synth/probe_command.h"

namespace sas::synth {

// A snapshot of the physical state, for tests, meters and the calibration commands.
struct SceneProbeState {
  bool active = false;            // false: tip up and the probe parked (no contact computed)
  double height_m = 0.0;          // probe height (up = positive)
  double velocity_mps = 0.0;      // probe vertical velocity
  double compression_m = 0.0;     // Hunt–Crossley compression x (> 0 in contact)
  double normal_force_n = 0.0;    // last contact force on the probe (up = positive)
  double friction_force_n = 0.0;  // last friction force on the resonator (along the stroke)
  double bristle_m = 0.0;         // elasto-plastic bristle deflection z
  double surface_offset_m = 0.0;  // felt profile height under the probe (+ micro-roughness)
  // The felt profile alone (penetration threshold applied, no roughness): 0 wherever the probe
  // feels nothing of the texture (benchmarks check that a stroke feels its profile).
  double felt_profile_m = 0.0;
  bool touched = false;  // a contact force acted during the last sample
  double x_m = 0.0;      // probe position on the surface
  double y_m = 0.0;
  int substeps = 1;               // contact sub-steps used in the last sample
  bool friction_skipped = false;  // SceneSkips::relaxed_friction left friction out of it
  // The pen was lifted and the hand is still taking the load off the tip (a few ms; scene.cpp,
  // kLiftSpeedMps): the hand's work is an input to the energy until it ends.
  bool unloading = false;
  // The style changed while the tip was down and the felt height is still gliding from the old
  // style's profile to the new one's (scene.cpp, kStyleGlideS): the surface moves under the
  // probe, an input to the energy like a slide's, until it ends.
  bool gliding = false;
};

// What the scene leaves out because it cannot change the output. Everything is skipped by default;
// tests switch a skip off to compare against the full computation.
struct SceneSkips {
  // Pen up, probe parked, resonator and output filters below kIdleSilence: the scene zeroes its
  // (inaudible) state once and then writes zeros without running the per-sample kernel until the
  // next touch or burst. Checked every kIdleCheckFrames frames of absolute time, so the output
  // still does not depend on the block size.
  bool idle_blocks = true;
  // Friction not solved while the probe is not sliding, the bristle is relaxed and nothing moves at
  // the contact (resonator and probe still): friction could only answer a slip far below what
  // changes any output sample by 1e-7. (A bristle left deflected by a stroke stays stuck, hence
  // not relaxed, until the pen is lifted.)
  bool relaxed_friction = true;
  // Modes at or above 0.45 fs or with |gain| < kNegligibleGain are not computed (ModalState). Off:
  // they are computed like the others (the above-Nyquist ones alias).
  bool inaudible_modes = true;
};

// Pickup amplitude (full scale = 1) below which the pen-up scene counts as silent: -140 dBFS, so
// zeroing it changes no output sample by more than 1e-7 (the target is -120 dBFS or lower).
inline constexpr double kIdleSilence = 1e-7;
inline constexpr int kIdleCheckFrames = 32;

class Scene {
 public:
  Scene();
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;
  Scene(Scene&&) noexcept;
  Scene& operator=(Scene&&) noexcept;

  // Sets the sample rate (Hz). Not real-time.
  void Init(double sample_rate_hz);

  // Takes the material, the output settings and the surface (the view must outlive the scene or
  // the next Prepare). Computes the per-mode coefficients and picks the contact oversampling
  // (ChooseContactOversample in synth/contact.h). Not real-time. Ends with Reset().
  void Prepare(const MaterialParams& material, const OutputParams& output,
               const HeightFieldView& surface);

  // Chooses the skips (default: all on). Not real-time; takes effect at the next Prepare().
  void SetSkips(const SceneSkips& skips);

  // Back to rest: probe parked, resonator and filters silent. Equals a freshly prepared scene.
  void Reset();

  // Renders `frames` frames of 2 interleaved channels (ch 1 sound, ch 2 haptic) into
  // `interleaved_out`. `commands` (sorted by frame_offset; offsets >= frames apply at the last
  // frame; none is consumed when frames <= 0) take effect at the sample they name, before it is
  // rendered. Non-finite command fields are ignored or replaced by safe values. Real-time safe.
  void Process(const ProbeCommand* commands, int command_count, float* interleaved_out, int frames);

  // The staff-selected low-vibration mode (OutputParams::low_vibration_gain on the transducer
  // channel). Callable from any thread while another runs Process(): a relaxed atomic store that
  // Process() reads once per block; the change then ramps over 20 ms. Prepare() sets it from
  // OutputParams::low_vibration.
  void SetLowVibration(bool on);
  bool low_vibration() const;

  // Per-stroke loudness-matching gains (linear factors on ch 1 and ch 2, clamped to
  // [0, OutputStage::kMaxStrokeGain]; the kiosk's stroke gains, levels/stroke_gain.h), applied
  // before the limiters. Callable from any thread while another runs Process(): relaxed atomic
  // stores that Process() reads once per block; a change then ramps linearly over `ramp_s`
  // (default 20 ms; at least OutputStage::kMinStrokeRampS), so it never steps. Reset() and
  // Prepare() take the values last set at once (the scene is silent); they stay set across
  // Prepare() (default 1).
  void SetStrokeGains(double sound, double haptic, double ramp_s = 0.02);

  // Vibrational energy of the resonator (J), cheap (O(modes)).
  double ResonatorEnergy() const;
  // Total mechanical energy (J): resonator + probe kinetic + contact potential k x^(α+1)/(α+1) +
  // bristle σ0 z²/2 + potential of the constant push (f_N · height). Without input it never
  // increases (the contact schemes are passive).
  double TotalEnergy() const;
  // True when the tip is up, the probe parked, the resonator below kIdleSilence (-140 dBFS) and
  // the output filters silent: a block would be (nearly) all zeros. With SceneSkips::idle_blocks
  // such blocks are not computed.
  bool IsIdle() const;
  // True while the scene is skipping the kernel (idle_blocks): it writes zeros.
  bool skipping_idle() const;

  SceneProbeState probe_state() const;
  double sample_rate_hz() const;
  int contact_oversample() const;  // sub-steps per sample used while in contact
  // The contact scheme the kernel runs, and whether its sub-step count adapts per compression
  // (1, 2, 4, ... up to contact_oversample()) or is fixed at contact_oversample().
  ContactScheme contact_scheme() const;
  bool adaptive_oversample() const;
  int active_mode_count() const;   // modes actually computed (below 0.45 fs, audible)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sas::synth
