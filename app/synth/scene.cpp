// Scene: commands -> surface reader -> contact kernel -> output stage (see scene.h).
#include "synth/scene.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "synth/contact_kernel.h"
#include "synth/crumble.h"
#include "synth/output_stage.h"
#include "synth/surface_reader.h"

#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#endif

namespace sas::synth {
namespace {

// Flush-to-zero and denormals-are-zero for the duration of Process(): a decaying resonator
// would otherwise spend its tail in subnormal arithmetic (100× slower on x86).
class DenormalGuard {
 public:
#if defined(__SSE__) || defined(__x86_64__)
  DenormalGuard() : saved_(_mm_getcsr()) {
    _mm_setcsr(saved_ | 0x8040u);
  }  // FTZ | DAZ
  ~DenormalGuard() {
    _mm_setcsr(saved_);
  }

 private:
  unsigned saved_;
#elif defined(__aarch64__)
  DenormalGuard() {
    asm volatile("mrs %0, fpcr" : "=r"(saved_));
    const std::uint64_t flushed = saved_ | (std::uint64_t{1} << 24);  // FZ
    asm volatile("msr fpcr, %0" : : "r"(flushed));
  }
  ~DenormalGuard() {
    asm volatile("msr fpcr, %0" : : "r"(saved_));
  }

 private:
  std::uint64_t saved_ = 0;
#else
  DenormalGuard() = default;
#endif
 public:
  DenormalGuard(const DenormalGuard&) = delete;
  DenormalGuard& operator=(const DenormalGuard&) = delete;
};

double FiniteOr(double v, double fallback) {
  return std::isfinite(v) ? v : fallback;
}

// Friction skip (SceneSkips::relaxed_friction): the pickup amplitude that the skipped friction
// could at most have caused — from releasing the bristle's static force σ0 z, or from stopping the
// resonator's residual motion at the contact — stays below this (two orders below the 1e-7 the
// skip may change the output by).
constexpr double kFrictionSkipAmplitude = 1e-9;
constexpr std::uint64_t kNoiseSeed = 0x9E3779B97F4A7C15ull;
// Commanded speeds are clamped here (m/s): far beyond any hand, still finite arithmetic.
constexpr double kMaxSpeed = 100.0;
// Lifting the pen. A pen-up report does not end the contact in one sample: the hand rises at
// kLiftSpeedMps (the speed a tap lands with, ProbeCommand::landing_speed_mps) and holds the pen
// in the fingertips' pulp, a spring of about 1 mm per newton at a pen's load (fingertip pulp
// compression: Serina, Mote & Rempel, J. Biomechanics 30(10), 1997; its stiffening with force is
// left out). So the tip's load falls as the hand rises — over ~10 ms for 1 N, longer where the
// surface it pressed down springs back with it — and once the spring is slack it pulls the tip
// off. Stepping the load away instead releases the surface's whole deflection at once: a pop
// louder than the stroke on a soft material. The unload is bounded by kMaxUnloadS: on a soft
// contact in series with the pulp (bubble wrap: ~1.3e3 N/m at 0.6 N) the load takes ~45 ms to go,
// and a bound at 50 ms let the rest of it go at once.
// The fingers do not let a light load go faster than a heavy one: the load leaves over at least
// kMinUnloadS (the hand rises more slowly while the tip bears load, at kLiftSpeedMps once it
// does not). At 1 mm/N a light press (0.2 N) went in 2 ms, faster than a bubble's 5.5 ms
// period, and released its whole deflection as a ring 3-4 dB over the stroke; over 20 ms, four
// periods of the lowest kiosk mode, the surface follows the load back up instead.
constexpr double kLiftSpeedMps = 0.1;
constexpr double kFingerPulpNPerM = 1e3;
constexpr double kMinUnloadS = 0.02;
constexpr double kMaxUnloadS = 0.1;
// A pen with a body (ProbeParams::body_mass_kg): the hand grips the body, and the grip damps it,
// a few N s/m at the fingertips (Hajian & Howe, J. Biomech. Eng. 119(1), 1997: 1.5-3.5 N s/m on
// an index finger); the sensor spring between body and nib is an elastomer with a loss factor of
// about 0.1 at the body's resonance (Nashif, Jones & Henderson, "Vibration Damping", 1985).
constexpr double kGripDampingNsPerM = 2.0;
constexpr double kSensorLossFactor = 0.1;
// A rolling ball does not slide, but its contact creeps: the patch's trailing part micro-slips at
// a fraction of the rolling speed, of the order 1e-3 to 1e-2 (creep in rolling contact: Johnson,
// "Contact Mechanics", 1985, ch. 8). That micro-slip breaks the asperity junctions as sliding
// does, at a rate set by the rolling speed: the friction's noise term σ3 w sqrt(v f_N) at the
// creep's speed. Without it a slow roll over a smooth stretch rang nothing (-92 to -101 dBFS at
// 10 mm/s). The upper end of the range: at 3e-3 the quietest slow roll sat on -90 dBFS.
constexpr double kRollingCreep = 0.01;
// A style switched while the tip is down (the pen's barrel button pressed or let go mid-stroke):
// each style feels a different profile under the same point (a rolling ball bridges a crack a
// point falls into), and stepping from one to the other struck the probe like a tap (a step up
// to 7 times the stroke's usual largest sample-to-sample change on cracked ground). The felt
// height glides from the old profile to the new one over kStyleGlideS with a raised cosine (no
// step in height or in its slope): at 100 mm/s the tip travels 2 mm meanwhile, about the chord
// over which a ball rolls up out of a crack its own size.
constexpr double kStyleGlideS = 0.02;

}  // namespace

struct Scene::Impl {
  double fs = 48000.0;
  MaterialParams material{};
  OutputParams output_params{};
  ContactKernelConfig config{};
  ModalState modes{};
  ProbeDynamics probe{};
  SurfaceReader reader{};
  CrumbleSource crumble{};
  OutputStage output{};
  // Written by the control thread (Scene::SetLowVibration), read once per block by Process().
  std::atomic<bool> low_vibration{false};
  // Written by the control thread (Scene::SetStrokeGains), read once per block by Process().
  std::atomic<double> stroke_sound_gain{1.0};
  std::atomic<double> stroke_haptic_gain{1.0};
  std::atomic<double> stroke_ramp_s{0.02};
  double stroke_bound = 1.0;  // OutputStage::StrokeGainBound() for this block
  SceneSkips skips{};
  bool friction_skipped = false;  // the last sample left friction out (relaxed_friction)
  bool idle = false;              // skipping the kernel (SceneSkips::idle_blocks)
  std::uint64_t frame_count = 0;  // frames rendered since Reset (idle checks on absolute time)
  double output_gain = 1.0;       // max(|sound gain|, |haptic gain|, 1)
  double release_gain = 0.0;  // output_gain · Σ |g_i| / (m_i ω0_i): pickup per newton released
  double max_abs_gain = 0.0;  // output_gain · max |g_i|
  double felt_per_newton = 0.0;  // contact force -> transducer input (RenderFrame)
  double felt_noise_share = 1.0;  // FrictionParams::felt_noise_share
  // The pen's body (ProbeParams::body_mass_kg > 0, impact on): a second mass above the nib (the
  // probe), joined by the pressure sensor's spring; the hand's push acts on the body. Heights as
  // the probe's; at rest without load the body sits at the nib's height.
  bool pen_body = false;
  double body_inv_mass = 0.0;
  double body_spring_n_per_m = 0.0;
  double body_damping_n_s_per_m = 0.0;  // the sensor spring's own damping
  double body_height_m = 0.0;
  double body_velocity_mps = 0.0;

  // Gesture state set by the last command.
  ProbeCommand gesture{};
  double x_m = 0.0, y_m = 0.0;
  double step_x_m = 0.0, step_y_m = 0.0;  // pen movement per frame (set with the gesture)
  double surface_m = 0.0;     // felt profile at the probe position (end of the last sample)
  // A style switch's glide (kStyleGlideS): the old profile's height above the new one at the
  // switch, faded out over glide_samples; glide_pos counts the samples done.
  double glide_m = 0.0;
  int glide_samples = 0, glide_pos = 0;
  bool burst_flight = false;  // tip up, released by a burst: park once it leaves the surface
  // A lift being carried out (kLiftSpeedMps): the stroke's gesture stays in force, its push the
  // fingers' spring as the hand rises, until the tip is off the surface; then the probe is parked
  // and `unload_after` (the pen-up command, or the latest one of the pen hovering since) applies.
  bool unloading = false;
  int unload_samples = 0;                  // samples since the lift
  double unload_tip_m = 0.0;               // the height the hand holds (body, or tip) at the lift
  double unload_rise_mps = kLiftSpeedMps;  // the hand's rise while the tip still bears load
  double unload_hand_m = 0.0;              // how far the hand has risen since the lift
  ProbeCommand unload_after{};
  bool finishing_unload = false;
  bool burst_touched = false;
  int burst_samples = 0;
  std::uint64_t noise_state = kNoiseSeed;
  // Micro-roughness (RoughnessParams): the spatial process, its contact filter and the friction
  // noise's spatial process, advanced by the distance travelled each sample. The coefficients
  // depend on the speed and the contact, so Apply() sets them once per command.
  double rough_keep = 1.0, rough_in = 0.0, contact_step = 0.0;
  double noise_keep = 0.0, noise_in = 1.0;
  double rough_raw = 0.0, rough_c1 = 0.0, rough_felt = 0.0, noise_w = 0.0;
  double noise_junction_step = 0.0, noise_junction = 0.0;
  // N added to the contact force on the transducer this sample: the friction noise it does not
  // carry (negative), a roll's creep noise it does (felt_noise_share of each).
  double felt_adjust_n = 0.0;
  // Frames rendered but not yet through the output stage (RenderFrame -> FlushOutput): run as a
  // block (OutputStage::ProcessBlock) the stage's filters keep their state in registers and one
  // frame's work overlaps the next's. Flushed before anything that reads or changes the stage (a
  // command, the idle check) and at the end of Process, so the output is the per-frame one, bit
  // for bit.
  static constexpr int kOutputChunk = kIdleCheckFrames;
  int pending = 0;
  float* pending_out = nullptr;  // the first pending frame
  double pending_pickup[kOutputChunk] = {};
  double pending_felt[kOutputChunk] = {};

  void FlushOutput() {
    if (pending > 0) output.ProcessBlock(pending_pickup, pending_felt, pending_out, pending);
    pending = 0;
  }

  double Felt(double x, double y) const {
    return reader.Felt(x, y, gesture.width_mm * 1e-3, gesture.penetration_m, gesture.style,
                       material.probe.ball_radius_m, gesture.direction_x, gesture.direction_y);
  }
  // The same, bit for bit, from the reader's record of the last sample (RenderFrame only).
  double FeltTracked(double x, double y) {
    return reader.FeltTracked(x, y, gesture.width_mm * 1e-3, gesture.penetration_m, gesture.style,
                              material.probe.ball_radius_m, gesture.direction_x,
                              gesture.direction_y);
  }

  double Uniform() {  // xorshift64*: uniform in [-1, 1)
    noise_state ^= noise_state >> 12;
    noise_state ^= noise_state << 25;
    noise_state ^= noise_state >> 27;
    const std::uint64_t r = noise_state * 0x2545F4914F6CDD1Dull;
    return static_cast<double>(r >> 11) * (2.0 / 9007199254740992.0) - 1.0;
  }

  void Reset() {
    modes.Reset();
    crumble.Reset();
    pending = 0;
    probe = ProbeDynamics{};
    // A reset scene is silent: the transducer trim may jump to the requested mode at once.
    output.SetLowVibration(low_vibration.load(std::memory_order_relaxed));
    output.SetStrokeGains(stroke_sound_gain.load(std::memory_order_relaxed),
                          stroke_haptic_gain.load(std::memory_order_relaxed));
    output.Reset();
    stroke_bound = output.StrokeGainBound();
    gesture = ProbeCommand{};
    x_m = y_m = 0.0;
    step_x_m = step_y_m = 0.0;
    surface_m = 0.0;
    glide_m = 0.0;
    glide_pos = glide_samples;
    burst_flight = burst_touched = false;
    burst_samples = 0;
    unloading = false;
    unload_samples = 0;
    unload_tip_m = 0.0;
    unload_after = ProbeCommand{};
    body_height_m = body_velocity_mps = 0.0;
    noise_state = kNoiseSeed;
    rough_keep = 1.0;
    rough_in = contact_step = 0.0;
    noise_keep = 0.0;
    noise_in = 1.0;
    rough_raw = rough_c1 = rough_felt = noise_w = noise_junction = felt_adjust_n = 0.0;
    noise_junction_step = 0.0;
    idle = false;
    frame_count = 0;
    friction_skipped = false;
  }

  // Pen up, probe parked, resonator and output filters below half of kIdleSilence: the haptic
  // band-pass (a 16th-order low-pass) can ring its state up past the bound of its input for a
  // while, so the margin keeps every zeroed output sample below kIdleSilence.
  bool Silent() const {
    if (probe.active) return false;
    constexpr double kThreshold = 0.5 * kIdleSilence;
    return (modes.PickupAmplitudeBound() + crumble.AmplitudeBound()) * output_gain * stroke_bound <
               kThreshold &&
           output.FilterActivity() < kThreshold;
  }

  // Friction can be left out this sample (SceneSkips::relaxed_friction): not sliding, the bristle
  // relaxed (its static force σ0 z could not move the output by kFrictionSkipAmplitude if
  // released) and nothing at the contact moving: the resonator still about its static deflection
  // under the current load, and (impact model on) the probe at rest and balanced by the normal
  // force. Friction would then see no slip; the friction force can at most stop a residual slip
  // (it is passive), so leaving it out changes the output by less than kFrictionSkipAmplitude.
  bool FrictionIdle(const SampleDrive& drive) const {
    if (drive.slide_velocity_mps != 0.0) return false;
    // Relaxed: the deflection is negligible for the friction's own future (1e-9 of the break-away
    // deflection, so zeroing it cannot change when the bristle sticks or slips) and for the sound.
    const FrictionModel& fm = config.friction;
    const double fn = drive.friction_share *
                      (config.impact.enabled ? std::max(probe.normal_n, 0.0) : drive.push_n);
    const double z = std::fabs(probe.bristle_m);
    if (z > 1e-9 * fm.c_ba * fm.mu_d * fn / fm.sigma0) return false;
    if (fm.sigma0 * z * release_gain * stroke_bound > kFrictionSkipAmplitude) return false;
    // Σ (v² + ω0² (q - q_static)²): squared contact-velocity amplitudes of the modes.
    const double load = probe.friction_n - probe.normal_n;  // force on the resonator
    double sum = 0.0;
    for (int i = 0; i < modes.count; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const double w2 = modes.omega0_sq[k];
      const double dq = modes.q[k] - load / (modes.mass[k] * w2);
      sum += modes.v[k] * modes.v[k] + w2 * dq * dq;
    }
    double probe_motion = 0.0;  // probe speed now plus what the force imbalance adds in a sample
    if (config.impact.enabled) {
      probe_motion = std::fabs(probe.velocity_mps) + std::fabs(drive.push_n - probe.normal_n) *
                                                         config.period_s / config.probe_mass_kg;
      if (pen_body) {  // the body moving, or its forces out of balance, would move the tip
        probe_motion += std::fabs(body_velocity_mps) +
                        std::fabs(drive.push_n - Push()) * config.period_s * body_inv_mass;
      }
    }
    // Σ amplitudes <= sqrt(count · Σ squares) (Cauchy–Schwarz); times the largest pickup gain.
    const double limit = kFrictionSkipAmplitude / (max_abs_gain * stroke_bound + 1e-300);
    return static_cast<double>(modes.count + 1) * (sum + probe_motion * probe_motion) <=
           limit * limit;
  }

  // `count` frames of the idle scene: zeros, and only the pen position moves (exactly as
  // RenderFrame moves it, one increment per frame). The increments are finite and bounded (speed
  // clamped, direction normalised), so a finite position stays finite: one check suffices.
  void IdleFrames(float* out, int count) {
    if (!std::isfinite(x_m) || !std::isfinite(y_m)) x_m = y_m = 0.0;
    for (int i = 0; i < count; ++i) {
      x_m += step_x_m;
      y_m += step_y_m;
    }
    std::fill(out, out + 2 * static_cast<std::ptrdiff_t>(count), 0.0f);
  }

  // The length of surface the probe touches along the stroke (the contact filter's length, see
  // RoughnessParams): scrape, the nib's Hertz contact diameter 2 sqrt(R x) under the push
  // (x = (F/k)^(1/α), Johnson, "Contact Mechanics", §4.2); rub, the probe's width; roll, the chord
  // 2 sqrt(2 r · 2σ) a ball of radius r spans over asperities 2σ high.
  double ContactLength() const {
    const RoughnessParams& r = material.roughness;
    double length = r.length_m;
    if (gesture.style == ProbeStyle::kRub) {
      length = gesture.width_mm * 1e-3;
    } else if (gesture.style == ProbeStyle::kRoll) {
      const double radius = std::max(material.probe.ball_radius_m, 0.5e-3 * gesture.width_mm);
      length = 2.0 * std::sqrt(4.0 * radius * r.rms_m);
    } else {
      length = HertzPatch(length);
    }
    return std::max(length, 1e-7);
  }

  // The nib's Hertz contact diameter under the push, or `otherwise` with no impact model or push.
  double HertzPatch(double otherwise) const {
    if (!config.impact.enabled || !(gesture.normal_force_n > 0.0)) return otherwise;
    const double x = std::pow(gesture.normal_force_n / config.impact.k, 1.0 / config.impact.alpha);
    return 2.0 * std::sqrt(material.probe.ball_radius_m * x);
  }

  // Coefficients of the spatial processes for the current gesture: an Ornstein–Uhlenbeck step over
  // the distance ds = v / fs (keep = e^(-ds/ℓ), input sqrt(1 - keep²) for a stationary variance)
  // and the contact filter's first-order step 1 - e^(-ds/L). Not moving: frozen.
  void SetSpatialSteps() {
    const RoughnessParams& r = material.roughness;
    const double ds = gesture.tip_down ? gesture.velocity_mps / fs : 0.0;
    if (!r.enabled || !(r.length_m > 0.0)) {
      rough_keep = 1.0;
      rough_in = contact_step = 0.0;
      noise_keep = 0.0;  // white friction noise
      noise_in = 1.0;
      noise_junction_step = 0.0;
      return;
    }
    if (!(ds > 0.0)) {
      rough_keep = noise_keep = 1.0;
      rough_in = noise_in = contact_step = noise_junction_step = 0.0;
      return;
    }
    const double keep = std::exp(-ds / r.length_m);
    const double in = std::sqrt(std::max(1.0 - keep * keep, 0.0));
    rough_keep = keep;
    rough_in = std::max(r.rms_m, 0.0) * in;
    // The friction's own noise. An upright point ploughs through the asperities one by one, so
    // its force renews every correlation length; a tilted nib slides on its side, where the
    // friction is the adhesion of all the junctions in its Hertz patch, a population that renews
    // only once the patch has moved its own length (ploughing and adhesion terms of friction:
    // Bowden & Tabor, "The Friction and Lubrication of Solids", 1950, ch. V). So a rub's noise is
    // darker than a scrape's on the same surface, as a pencil's side sounds duller than its point.
    // A rolling ball's creep noise (kRollingCreep) comes from the junctions of its whole patch,
    // renewed as the patch rolls on by its own length, like a rub's.
    const bool patch_noise =
        gesture.style == ProbeStyle::kRub || gesture.style == ProbeStyle::kRoll;
    const double noise_length =
        gesture.style == ProbeStyle::kRub    ? std::max(r.length_m, HertzPatch(r.length_m))
        : gesture.style == ProbeStyle::kRoll ? std::max(r.length_m, ContactLength())
                                             : r.length_m;
    noise_keep = std::exp(-ds / noise_length);
    noise_in = std::sqrt(std::max(1.0 - noise_keep * noise_keep, 0.0));
    // Each junction's force builds up over a slip of about its own size, the asperity scale ℓ
    // (the critical slip distance of rock and metal friction is of the order of the contact
    // size: Rabinowicz, Proc. Phys. Soc. 71, 1958; Dieterich, J. Geophys. Res. 84, 1979). So a
    // rub's patch-long noise is also smoothed over ℓ: above v/(2πℓ) it falls off, and that
    // corner rises with the speed through the modes, so a faster rub is brighter as well as
    // louder. (A scrape's noise already renews every ℓ.) Only on a rough surface, where ℓ is
    // the asperities' scale: on a polished one (glass) the junctions are the nib's own.
    noise_junction_step =
        patch_noise && r.rms_m > 0.0 && noise_length > r.length_m
            ? 1.0 - std::exp(-ds / r.length_m)
            : 0.0;
    contact_step = 1.0 - std::exp(-ds / ContactLength());
  }

  // One sample of travel: the roughness the contact feels (m).
  double RoughnessStep() {
    if (contact_step > 0.0 && rough_in > 0.0) {
      rough_raw = rough_keep * rough_raw + rough_in * 1.7320508075688772 * Uniform();
      rough_c1 += contact_step * (rough_raw - rough_c1);
      rough_felt += contact_step * (rough_c1 - rough_felt);
    }
    return rough_felt;
  }

  // The glide's part of the felt height this sample (0 once it has ended).
  double GlideStep() {
    if (glide_pos >= glide_samples) return 0.0;
    ++glide_pos;
    const double phase = static_cast<double>(glide_pos) / glide_samples;
    return glide_m * 0.5 * (1.0 + std::cos(std::numbers::pi * phase));
  }

  void Release(double velocity_mps) {
    // The probe appears just touching the surface (x = 0) under the pen.
    glide_pos = glide_samples;
    surface_m = Felt(x_m, y_m) + rough_felt;
    probe = ProbeDynamics{};
    probe.active = true;
    probe.height_m = surface_m + modes.ContactDisplacement();
    probe.velocity_mps = velocity_mps;
    // The pen comes down whole, its sensor spring unloaded: the body meets the surface through
    // it a few milliseconds after the nib.
    body_height_m = probe.height_m;
    body_velocity_mps = velocity_mps;
  }

  // A burst's impulse (N s) on the probe, towards the surface.
  void Kick(double impulse_n_s) {
    probe.velocity_mps -= std::min(impulse_n_s / config.probe_mass_kg, kMaxSpeed);
  }

  // The pen's push on the tip (N, down; negative pulls it up). While unloading: the pulp spring,
  // compressed by the stroke's push at the lift, relaxed by the hand's rise, compressed again by
  // the tip's own rise (a surface springing back under it).
  // With a pen body, the push acts on the body, and the tip feels the sensor spring (TipPush).
  double Push() const {
    if (!gesture.tip_down) return 0.0;
    if (!unloading) return gesture.normal_force_n;
    return gesture.normal_force_n -
           kFingerPulpNPerM * (unload_hand_m - (HeldHeight() - unload_tip_m));
  }
  double HeldHeight() const { return pen_body ? body_height_m : probe.height_m; }

  // How fast the hand rises while unloading (m/s). With a pen body it gathers speed smoothly over
  // kMinUnloadS (a reach's bell-shaped speed, Flash & Hogan, J. Neurosci. 5(7), 1985): a step in
  // the hand's speed would set the body ringing on the fingers' pulp (~40 Hz for 15 g) by more
  // than the sensor spring is compressed, and the nib would be let go in a millisecond.
  double HandRiseMps() const {
    const double rise = Push() > 0.0 ? unload_rise_mps : kLiftSpeedMps;
    if (!pen_body) return rise;
    const double t = static_cast<double>(unload_samples) / (fs * kMinUnloadS);
    return t >= 1.0 ? rise : rise * t * t * (3.0 - 2.0 * t);
  }

  // What presses the tip down (N): the sensor spring, compressed as the body comes down on the
  // nib, or the push itself on a pen without a body.
  double TipPush() const {
    if (!pen_body) return Push();
    return body_spring_n_per_m * (probe.height_m - body_height_m) +
           body_damping_n_s_per_m * (probe.velocity_mps - body_velocity_mps);
  }

  // One sample of the body: the sensor spring pushes it up as hard as it pushes the nib down, the
  // hand pushes it down, the grip damps it (semi-implicit Euler: its resonance, ~130 Hz on a 15 g
  // body and 1e4 N/m, is far under the sample rate).
  void StepBody() {
    // The grip's damping acts between the fingers and the body: against the body's motion
    // relative to the hand, which rises while the pen is lifted.
    const double hand_mps = unloading ? HandRiseMps() : 0.0;
    const double acc =
        (TipPush() - Push() - kGripDampingNsPerM * (body_velocity_mps - hand_mps)) *
        body_inv_mass;
    body_velocity_mps += acc / fs;
    body_height_m += body_velocity_mps / fs;
  }

  // The unload is over: the tip has left, the pen-up command applies.
  void FinishUnload() {
    finishing_unload = true;
    Apply(unload_after);
    finishing_unload = false;
  }

  void Apply(const ProbeCommand& raw) {
    ProbeCommand c = raw;
    c.x_m = FiniteOr(c.x_m, x_m);
    c.y_m = FiniteOr(c.y_m, y_m);
    c.velocity_mps = std::clamp(FiniteOr(c.velocity_mps, 0.0), 0.0, kMaxSpeed);
    c.normal_force_n = std::max(FiniteOr(c.normal_force_n, 0.0), 0.0);
    c.width_mm = std::max(FiniteOr(c.width_mm, 0.5), 0.0);
    c.penetration_m = std::max(FiniteOr(c.penetration_m, 0.0), 0.0);
    c.landing_speed_mps = std::clamp(FiniteOr(c.landing_speed_mps, 0.0), 0.0, kMaxSpeed);
    c.burst_impulse_n_s = std::max(FiniteOr(c.burst_impulse_n_s, 0.0), 0.0);
    const double norm = std::hypot(FiniteOr(c.direction_x, 0.0), FiniteOr(c.direction_y, 0.0));
    if (norm > 0.0) {
      c.direction_x /= norm;
      c.direction_y /= norm;
    } else {
      c.direction_x = 1.0;
      c.direction_y = 0.0;
    }
    // A pen-up report while the tip presses the surface starts the unload (kLiftSpeedMps): the
    // stroke goes on with its push falling to zero, then the probe is parked. Stepping the load
    // away at once releases the surface's whole deflection in one sample, a pop louder than the
    // stroke on a soft material.
    if (unloading) {
      if (!c.tip_down) {  // the pen hovers on while the tip comes up
        unload_after = c;
        if (c.burst_impulse_n_s > 0.0) Kick(c.burst_impulse_n_s);
        return;
      }
      unloading = false;  // down again before the tip left: the stroke goes on
    } else if (!c.tip_down && gesture.tip_down && probe.active && !finishing_unload &&
               config.impact.enabled && gesture.normal_force_n > 0.0) {
      unloading = true;
      unload_samples = 0;
      unload_tip_m = HeldHeight();
      unload_hand_m = 0.0;
      unload_rise_mps =
          std::min(kLiftSpeedMps, gesture.normal_force_n / (kFingerPulpNPerM * kMinUnloadS));
      unload_after = c;
      if (c.burst_impulse_n_s > 0.0) Kick(c.burst_impulse_n_s);
      return;
    }
    const bool was_down = gesture.tip_down;
    const bool style_switch = was_down && c.tip_down && probe.active && c.style != gesture.style;
    // Friction is computed along the stroke: when the stroke turns, the bristle deflection keeps
    // its component along the new direction (a reversal flips its sign; a projection never adds
    // energy).
    const double turn = gesture.direction_x * c.direction_x + gesture.direction_y * c.direction_y;
    probe.bristle_m *= turn;
    probe.friction_n *= turn;
    gesture = c;
    step_x_m = c.velocity_mps * c.direction_x / fs;
    step_y_m = c.velocity_mps * c.direction_y / fs;
    x_m = c.x_m;
    y_m = c.y_m;
    if (style_switch) {
      // From the height felt last (the old style's, with any glide still under way) to the new
      // style's here.
      glide_m = surface_m - (Felt(x_m, y_m) + rough_felt);
      glide_pos = 0;
    }
    if (c.tip_down && !was_down) {
      Release(-c.landing_speed_mps);
      burst_flight = false;
      output.NewStroke();
    } else if (!c.tip_down && was_down) {
      probe = ProbeDynamics{};  // lifted: parked, bristle relaxed
    }
    if (c.burst_impulse_n_s > 0.0) {
      if (!probe.active) {
        Release(0.0);
        burst_flight = true;
        burst_touched = false;
        burst_samples = 0;
      }
      Kick(c.burst_impulse_n_s);
    }
    SetSpatialSteps();
    if (probe.active) idle = false;  // a touch or a burst wakes the idle scene
  }

  void RenderFrame(float* frame) {
    x_m += step_x_m;
    y_m += step_y_m;
    if (!std::isfinite(x_m) || !std::isfinite(y_m)) x_m = y_m = 0.0;
    if (probe.active) {
      const double next = FeltTracked(x_m, y_m) + RoughnessStep() + GlideStep();
      SampleDrive drive;
      drive.surface_begin_m = surface_m;
      drive.surface_end_m = next;
      drive.slide_velocity_mps = gesture.tip_down ? gesture.velocity_mps : 0.0;
      drive.push_n = TipPush();
      drive.friction_share = SurfaceReader::FrictionShare(gesture.style, gesture.width_mm);
      if (config.friction.enabled && config.friction.sigma3 > 0.0 &&
          drive.slide_velocity_mps > 0.0) {
        const double fn = drive.friction_share *
                          (config.impact.enabled ? std::max(probe.normal_n, 0.0) : drive.push_n);
        // Unit-variance noise scaled by sqrt(|v| f_N) (Avanzini et al. 2005): white on a smooth
        // material, the spatial process of its roughness on a rough one.
        noise_w = noise_keep * noise_w + noise_in * (1.7320508075688772 * Uniform());
        double w = noise_w;
        if (noise_junction_step > 0.0) {
          noise_junction += noise_junction_step * (noise_w - noise_junction);
          w = noise_junction;
        }
        drive.noise_n = config.friction.sigma3 * w * std::sqrt(drive.slide_velocity_mps * fn);
      }
      friction_skipped = skips.relaxed_friction && config.friction.enabled &&
                         drive.friction_share > 0.0 && FrictionIdle(drive);
      if (friction_skipped) drive.friction_share = 0.0;  // the kernel neither solves nor stores it
      surface_m = next;
      StepContactSample(config, modes, probe, drive);
      // The part of the friction's noise the transducer does not carry (felt_noise_share): in
      // the force only where the kernel solved the friction this sample.
      felt_adjust_n = !friction_skipped && probe.friction_n != 0.0
                          ? -(1.0 - felt_noise_share) * drive.noise_n
                          : 0.0;
      if (pen_body) StepBody();
      // Rolling: the creep's junction noise (kRollingCreep) on the surface at the contact, from
      // the friction noise's process (SetSpatialSteps: renewed as the patch rolls its length).
      if (gesture.style == ProbeStyle::kRoll && drive.slide_velocity_mps > 0.0 &&
          config.friction.enabled && config.friction.sigma3 > 0.0 && probe.normal_n > 0.0) {
        const double w = noise_junction_step > 0.0 ? noise_junction : noise_w;
        const double force = config.friction.sigma3 * w *
                             std::sqrt(kRollingCreep * drive.slide_velocity_mps * probe.normal_n);
        modes.Kick(-force / fs);
        // The tip takes the reaction, felt as a slide's noise is (felt_noise_share).
        felt_adjust_n += felt_noise_share * force;
      }
      // A grain of a crumbling crust broke under the tip: its flake flies off, the crust takes
      // the reaction (down).
      if (crumble.enabled() && drive.slide_velocity_mps > 0.0) {
        const double impulse =
            crumble.Slide(drive.slide_velocity_mps / fs, std::max(probe.normal_n, 0.0));
        if (impulse > 0.0) modes.Kick(-impulse);
      }
      // Last line of defence against absurd input: a non-finite probe is parked, never kept.
      if (!std::isfinite(probe.height_m + probe.velocity_mps + probe.bristle_m + probe.normal_n +
                         probe.friction_n + body_height_m + body_velocity_mps)) {
        probe = ProbeDynamics{};
        burst_flight = false;
      }
      if (burst_flight) {
        ++burst_samples;
        if (probe.touched || probe.compression_m > 0.0) burst_touched = true;
        if ((burst_touched && probe.compression_m < 0.0) || burst_samples > fs) {
          probe = ProbeDynamics{};
          burst_flight = false;
        }
      }
    } else {
      AdvanceModes(modes, modes.full, 0.0);
    }
    const double pickup = modes.PickupVelocity() + crumble.Ring();
    if (!std::isfinite(pickup)) modes.Reset();  // never let a NaN ring forever
    // The stylus carries the contact to the hand whether or not the surface rings in the
    // transducer's band (glass: modes from 683 Hz, all above 400 Hz). With a pen body, what the
    // hand holds is the body: its velocity along the pen, which follows the relief below the
    // body's resonance and the contact force's fluctuation above it. Along the stroke (and
    // without a body, for the whole force) the force as the velocity it gives the pen's mass at
    // 250 Hz, where the skin's Pacinian receptors are most sensitive (Verrillo, JASA 35(12) 1963).
    // The band-pass drops the steady part; what is felt is the fluctuation.
    double felt = 0.0;
    if (probe.active) {
      const double friction = probe.friction_n + felt_adjust_n;
      felt = pen_body ? body_velocity_mps + friction * felt_per_newton
                      : (probe.normal_n + friction) * felt_per_newton;
    }
    if (pending == kOutputChunk) FlushOutput();
    if (pending == 0) pending_out = frame;
    pending_pickup[pending] = pickup;
    pending_felt[pending] = felt;
    ++pending;
    if (unloading) {
      ++unload_samples;
      // The fingers let the load go gently; once it is gone the arm takes the pen away.
      unload_hand_m += HandRiseMps() / fs;
      // Off: the spring pulls and the tip has left the surface (or the bound is reached).
      const bool off = Push() < 0.0 && probe.compression_m < 0.0;
      if (off || !probe.active || unload_samples >= static_cast<int>(kMaxUnloadS * fs)) {
        unloading = false;
        FinishUnload();
      }
    }
  }
};

Scene::Scene() : impl_(std::make_unique<Impl>()) {}
Scene::~Scene() = default;
Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;

void Scene::Init(double sample_rate_hz) {
  impl_->fs = sample_rate_hz > 0.0 && std::isfinite(sample_rate_hz) ? sample_rate_hz : 48000.0;
  Prepare(impl_->material, impl_->output_params, HeightFieldView{});
}

void Scene::Prepare(const MaterialParams& material, const OutputParams& output,
                    const HeightFieldView& surface) {
  Impl& s = *impl_;
  s.material = material;
  s.output_params = output;
  MaterialParams& m = s.material;
  if (!(m.probe.mass_kg > 0.0) || !std::isfinite(m.probe.mass_kg)) m.probe.mass_kg = 0.01;
  if (!(m.impact.stiffness > 0.0) || !std::isfinite(m.impact.stiffness)) m.impact.enabled = false;
  m.impact.dissipation_s_per_m = std::max(FiniteOr(m.impact.dissipation_s_per_m, 0.0), 0.0);
  if (!(m.impact.shape_alpha >= 1.0) || !std::isfinite(m.impact.shape_alpha))
    m.impact.shape_alpha = 1.5;
  if (!(m.friction.bristle_stiffness > 0.0) || !std::isfinite(m.friction.bristle_stiffness))
    m.friction.enabled = false;
  m.friction.stribeck_velocity_mps =
      std::max(FiniteOr(m.friction.stribeck_velocity_mps, 0.1), 1e-9);
  m.friction.breakaway_ratio =
      std::clamp(FiniteOr(m.friction.breakaway_ratio, 0.1), 1e-6, 1.0 - 1e-6);
  if (!IsContactSchemeImplemented(m.impact.scheme)) m.impact.scheme = kDefaultContactScheme;
  s.config.scheme = m.impact.scheme;
  s.config.impact.Set(m.impact);
  s.config.friction.Set(m.friction);
  s.config.probe_mass_kg = m.probe.mass_kg;
  s.glide_samples = std::max(1, static_cast<int>(std::lround(kStyleGlideS * s.fs)));
  s.pen_body = m.impact.enabled && m.probe.body_mass_kg > 0.0 &&
               std::isfinite(m.probe.body_mass_kg) && m.probe.body_spring_n_per_m > 0.0 &&
               std::isfinite(m.probe.body_spring_n_per_m);
  if (s.pen_body) {
    s.body_inv_mass = 1.0 / m.probe.body_mass_kg;
    s.body_spring_n_per_m = m.probe.body_spring_n_per_m;
    // Loss factor η at the body's resonance ω = sqrt(k/m): c = η k / ω = η sqrt(k m).
    s.body_damping_n_s_per_m =
        kSensorLossFactor * std::sqrt(m.probe.body_spring_n_per_m * m.probe.body_mass_kg);
  }
  const double felt_mass = s.pen_body ? m.probe.body_mass_kg : m.probe.mass_kg;
  s.felt_per_newton = 1.0 / (felt_mass * 2.0 * std::numbers::pi * 250.0);
  s.felt_noise_share = std::isfinite(m.friction.felt_noise_share)
                           ? std::clamp(m.friction.felt_noise_share, 0.0, 1.0)
                           : 1.0;
  s.config.SetTiming(s.fs, ChooseContactOversample(m.impact, m.probe.mass_kg, s.fs));
  // Automatic oversampling adapts per compression (contact.h, ContactSubstepsForSpeed).
  const bool adaptive = m.impact.enabled && m.impact.oversample <= 0;
  s.modes.Prepare(m.resonator, s.fs, s.config.substeps, !s.skips.inaudible_modes, adaptive);
  s.config.adaptive = adaptive && s.modes.level_count > 1;
  s.config.SetLevels(m.impact, s.modes, s.fs);
  s.reader.Prepare(surface);
  s.crumble.Prepare(m.crumble, s.fs);
  s.output.Prepare(output, s.fs);
  s.low_vibration.store(output.low_vibration, std::memory_order_relaxed);
  s.output_gain = std::max(
      {std::fabs(s.output_params.sound_gain), std::fabs(s.output_params.haptic_gain), 1.0});
  s.release_gain = 0.0;
  s.max_abs_gain = 0.0;
  for (int i = 0; i < s.modes.count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    s.release_gain +=
        std::fabs(s.modes.gain[k]) / (s.modes.mass[k] * std::sqrt(s.modes.omega0_sq[k]));
    s.max_abs_gain = std::max(s.max_abs_gain, std::fabs(s.modes.gain[k]));
  }
  s.release_gain *= s.output_gain;
  s.max_abs_gain *= s.output_gain;
  s.Reset();
}

void Scene::SetSkips(const SceneSkips& skips) {
  impl_->skips = skips;
}

void Scene::Reset() {
  impl_->Reset();
}

void Scene::Process(const ProbeCommand* commands, int command_count, float* interleaved_out,
                    int frames) {
  DenormalGuard guard;
  Impl& s = *impl_;
  if (const bool low = s.low_vibration.load(std::memory_order_relaxed);
      low != s.output.low_vibration()) {
    s.output.SetLowVibration(low);
  }
  if (const double sound = s.stroke_sound_gain.load(std::memory_order_relaxed),
      haptic = s.stroke_haptic_gain.load(std::memory_order_relaxed);
      sound != s.output.stroke_sound_gain() || haptic != s.output.stroke_haptic_gain()) {
    s.output.SetStrokeGains(sound, haptic, s.stroke_ramp_s.load(std::memory_order_relaxed));
    if (s.idle) s.output.Reset();  // silent (its state is zero): the gains may jump
  }
  s.stroke_bound = s.output.StrokeGainBound();
  int next = 0;
  if (commands == nullptr) command_count = 0;
  for (int f = 0; f < frames; ++f) {
    while (next < command_count &&
           (commands[next].frame_offset <= static_cast<std::uint32_t>(f) || f == frames - 1)) {
      s.FlushOutput();
      s.Apply(commands[next]);
      ++next;
    }
    float* frame = interleaved_out + 2 * static_cast<std::ptrdiff_t>(f);
    if (s.idle) {
      // Idle: the whole run of frames up to the next command at once (the idle check below only
      // runs while not idle, so only the frame count has to follow).
      int run_end = frames;
      if (next < command_count) {
        run_end = static_cast<int>(std::min<std::uint32_t>(commands[next].frame_offset,
                                                           static_cast<std::uint32_t>(frames - 1)));
      }
      run_end = std::max(run_end, f + 1);
      s.IdleFrames(frame, run_end - f);
      s.frame_count += static_cast<std::uint64_t>(run_end - f);
      f = run_end - 1;
      continue;
    }
    s.RenderFrame(frame);
    // Idle check on absolute time (every kIdleCheckFrames frames since Reset), so that skipping
    // starts on the same frame whatever the block size. Entering idle zeroes the inaudible state:
    // the skipped frames then are exactly the zeros written.
    if (++s.frame_count % kIdleCheckFrames == 0) {
      s.FlushOutput();
      if (s.skips.idle_blocks && !s.idle && s.Silent()) {
        s.modes.Reset();
        s.crumble.Silence();
        s.output.Reset();
        s.idle = true;
      }
    }
  }
  s.FlushOutput();
}

void Scene::SetLowVibration(bool on) {
  impl_->low_vibration.store(on, std::memory_order_relaxed);
}

void Scene::SetStrokeGains(double sound, double haptic, double ramp_s) {
  impl_->stroke_ramp_s.store(ramp_s, std::memory_order_relaxed);
  impl_->stroke_sound_gain.store(sound, std::memory_order_relaxed);
  impl_->stroke_haptic_gain.store(haptic, std::memory_order_relaxed);
}

bool Scene::low_vibration() const {
  return impl_->low_vibration.load(std::memory_order_relaxed);
}

double Scene::ResonatorEnergy() const {
  return impl_->modes.Energy();
}

double Scene::TotalEnergy() const {
  const Impl& s = *impl_;
  double e = s.modes.Energy();
  if (s.probe.active) {
    const double m = s.config.probe_mass_kg;
    const double push = s.Push();
    e += 0.5 * m * s.probe.velocity_mps * s.probe.velocity_mps;
    if (s.pen_body) {  // the body's motion, the sensor spring and the hand's work on the body
      const double squeeze = s.probe.height_m - s.body_height_m;
      e += 0.5 * s.body_velocity_mps * s.body_velocity_mps / s.body_inv_mass +
           0.5 * s.body_spring_n_per_m * squeeze * squeeze + push * s.body_height_m;
    } else {
      e += push * s.probe.height_m;
    }
    // The energy the scheme holds in the contact: V(x) for the discrete gradient, its own
    // discrete (received / quadratised) energy for the others (synth/contact.h).
    if (s.config.impact.enabled) e += s.probe.contact_energy_j;
    e += 0.5 * s.config.friction.sigma0 * s.probe.bristle_m * s.probe.bristle_m;
  }
  return e;
}

bool Scene::IsIdle() const {
  return impl_->idle || impl_->Silent();
}

bool Scene::skipping_idle() const {
  return impl_->idle;
}

SceneProbeState Scene::probe_state() const {
  const Impl& s = *impl_;
  SceneProbeState st;
  st.unloading = s.unloading;
  st.gliding = s.probe.active && s.glide_pos < s.glide_samples;
  st.active = s.probe.active;
  st.height_m = s.probe.height_m;
  st.velocity_mps = s.probe.velocity_mps;
  st.compression_m = s.probe.compression_m;
  st.normal_force_n = s.probe.normal_n;
  st.friction_force_n = s.probe.friction_n;
  st.bristle_m = s.probe.bristle_m;
  st.surface_offset_m = s.surface_m;
  st.felt_profile_m = s.probe.active ? s.Felt(s.x_m, s.y_m) : 0.0;
  st.touched = s.probe.touched;
  st.x_m = s.x_m;
  st.y_m = s.y_m;
  st.substeps = s.probe.substeps_used;
  st.friction_skipped = s.probe.active && s.friction_skipped;
  return st;
}

double Scene::sample_rate_hz() const {
  return impl_->fs;
}
int Scene::contact_oversample() const {
  return impl_->config.substeps;
}
ContactScheme Scene::contact_scheme() const {
  return impl_->config.scheme;
}
bool Scene::adaptive_oversample() const {
  return impl_->config.adaptive;
}
int Scene::active_mode_count() const {
  return impl_->modes.count;
}

}  // namespace sas::synth
