#pragma once
// Plain parameter structs for one material (the resonating surface) and the probe touching it,
// filled by the control side (material files, texture files, configuration) and handed to the
// synth by const&. SI units throughout unless a name says otherwise.
//
// Sources: Hunt–Crossley impact and modal resonator as in the paper §4 and the Sound Design
// Toolkit; elasto-plastic friction after Dupont, Hayward, Armstrong & Altpeter, "Single state
// elastoplastic friction models", IEEE TAC 47(5), 2002, used for sound by Avanzini, Serafin &
// Rocchesso, IEEE TSAP 13(5), 2005.

#include <array>
#include <cstdint>

namespace sas::synth {

inline constexpr int kMaxModes = 64;

// One mode of the resonating object.
struct ModeParams {
  double frequency_hz = 440.0;  // the ringing (damped) frequency heard, Hz
  double decay_s = 0.5;  // 1/e time constant of the amplitude envelope: |a(t)| ∝ exp(-t / decay_s)
                         // (the 60 dB decay time T60 is ln(1000) ≈ 6.91 times longer)
  double mass_kg = 0.01;  // modal mass seen at the contact point
  double gain = 1.0;      // pickup gain: output = Σ gain · modal velocity (m/s) at the pickup
};

struct ResonatorParams {
  int mode_count = 0;
  std::array<ModeParams, kMaxModes> modes{};
};

// Numerical scheme for the probe/contact ODE (contact_bench measures them). All four
// share the exact mode/probe maps and differ only in the contact force held over a sub-step; see
// synth/contact.h for each method and its source.
enum class ContactScheme : std::uint8_t {
  kExplicitPassive,    // explicit force with an energy (passivity) clamp, as in the SDT
  kTrapezoidNewton,    // trapezoidal / K-method with a safeguarded Newton solve
  kDiscreteGradient,   // energy-conserving discrete gradient (Chatziioannou & van Walstijn)
  kEnergyQuadratised,  // non-iterative IEQ/SAV (Ducceschi & Bilbao)
};

// The scheme a material gets unless its file says otherwise: the cheapest one that meets the
// 1e-4 restitution target at 48 kHz (measured; the numbers are in synth/contact.h and docs/contact-bench.md).
inline constexpr ContactScheme kDefaultContactScheme = ContactScheme::kDiscreteGradient;

// Update of the elasto-plastic bristle deflection z over a step (friction.md, numerical trap 1).
enum class BristleUpdate : std::uint8_t {
  kExponential,    // exact exponential relaxation at frozen velocity: stable for any step
  kExplicitEuler,  // forward Euler: chatters once T |v| / |z_ss| > 2 (benchmark comparison only)
};

// Hunt–Crossley: f = -k x^α - λ x^α ẋ for x > 0, with μ = λ / k.
struct ImpactParams {
  bool enabled = true;
  double stiffness = 1e7;            // k, N/m^α
  double dissipation_s_per_m = 0.5;  // μ = λ / k
  double shape_alpha = 1.5;          // α
  ContactScheme scheme = kDefaultContactScheme;
  // Contact sub-steps per sample (1, 2, 4, 8, 16, ... any whole number); 0 = automatic: enough
  // for the scheme's accuracy target at this material's samples per contact (see contact.h).
  int oversample = 0;
  // The automatic setting's sub-step policy, chosen per material from the benchmark
  // (contact_bench --choose: the cheapest that meets the kiosk's error budget); 0 = the scheme's
  // built-in figure. Sub-steps an impact at 1 m/s gets per contact (TargetContactSamples), and the
  // most a pressed contact keeps (kSustainedContactSubsteps); see synth/contact.h.
  double target_contact_samples = 0.0;
  int sustained_substeps = 0;
  // true: sustained_substeps is also the fewest a pressed contact gets while friction acts (a
  // floor as well as a cap). A pen dragged slowly over a stiff plate closes at mm/s, where the
  // impact rule asks for one sub-step, yet its stick-slip follows modes up to 0.45 fs: with the
  // friction force held over a whole sample the slip lags them and the squeal comes out louder
  // (glass rubbed at 40 mm/s: +1.2 dB at 1-2 sub-steps, within 0.1 dB at 8).
  bool pressed_floor = false;
};

// Elasto-plastic bristle friction: f = σ0 z + σ1 ż + σ2 v + σ3 w.
struct FrictionParams {
  bool enabled = true;
  double bristle_stiffness = 1000.0;   // σ0, N/m
  double bristle_damping = 10.0;       // σ1, N s/m
  double viscous_friction = 10.0;      // σ2, N s/m
  double noise_coefficient = 0.5;      // σ3
  double static_coefficient = 0.8;     // μ_s
  double dynamic_coefficient = 0.2;    // μ_d
  double stribeck_velocity_mps = 0.1;  // v_s
  double breakaway_ratio = 0.1;        // c_ba, 0 < c_ba < 1
  // The share of σ3 w that the transducer carries (the sound always gets all of it). The felt
  // channel is designed for the skin: the friction noise that gives every slide its hiss is alike
  // on every material and, felt whole, it hides the relief, the cracks and the bubbles that tell
  // the textures apart; a material whose grit is its feel (dry soil) keeps it.
  double felt_noise_share = 1.0;
  BristleUpdate bristle_update = BristleUpdate::kExponential;
};

// The stylus tip as a point mass, and the shape that rolls (roll style).
struct ProbeParams {
  double mass_kg = 0.01;  // what strikes the surface: the nib, or the whole pen without a body
  double ball_radius_m = 2e-3;
  // The pen's body, held by the hand, riding on the nib through the pressure sensor's spring. 0:
  // no body, the hand's push reaches the tip as a steady force (a rigid pen of mass_kg). Only
  // with the impact model on (the spring needs a tip that can move).
  double body_mass_kg = 0.0;
  double body_spring_n_per_m = 1e4;
};

// Output stage: channel 1 speaker, channel 2 vibrotactile transducer.
struct OutputParams {
  double sound_gain = 1.0;  // linear; may be "exaggerated" (noisy room): the limiter keeps |y| <= 1
  double haptic_gain = 1.0;
  bool haptic_enabled = true;   // false when no transducer is configured: the path is skipped
  double haptic_low_hz = 40.0;  // transducer band
  double haptic_high_hz = 400.0;
  // Peak ceiling of the transducer channel (linear, (0, 1]): the haptic limiter saturates here
  // instead of at full scale, so no gain can drive the transducer harder (sensitive visitors).
  double haptic_ceiling = 1.0;
  // Haptic factor while the staff-selected low-vibration mode is on (linear, [0, 1]); applied
  // before the limiter, ramped over kLowVibrationRampS. Switched at run time by
  // Scene::SetLowVibration(); `low_vibration` is the state after Prepare().
  double low_vibration_gain = 0.25;
  bool low_vibration = false;
  // Stroke leveller on the sound (linear K-weighted RMS, BS.1770; 0 = off): where the sound's
  // running K-weighted RMS (after the gains) rises over this, its gain comes down to meet it, so a
  // squeak or a fast hard scrape stands out without blasting. See OutputStage.
  double sound_level_cap = 0.0;
};

// Micro-roughness: the surface detail below the picture's pixel (grain, fibres, asperities) that
// a moving tip feels, as a random profile in the distance travelled, so that its spectrum in time
// scales with the speed: a stroke twice as fast is an octave brighter (rolling and scraping noise;
// Remington, JASA 81(6) 1987; Thompson, "Railway Noise and Vibration", 2009, ch. 5). The profile is
// an Ornstein–Uhlenbeck process in distance (RMS height `rms_m`, correlation length `length_m`:
// a k^-2 spectrum above 1/length_m, self-affine like measured surfaces), seen through the contact:
// the probe cannot follow wavelengths shorter than its contact patch ("contact filter", two
// first-order low-passes in distance over the patch length: the nib's Hertz contact for scrape,
// the probe width for rub, the chord a ball of radius r spans over the asperities for roll). The
// friction's noise term σ3 w is a process of the same kind (its own draw), so grit also brightens
// with speed.
// Not enabled: w white, as in Avanzini et al. 2005, and no roughness under the probe.
struct RoughnessParams {
  bool enabled = false;
  double rms_m = 0.0;
  double length_m = 1e-4;
};

// A crust that crumbles under the tip (synth/crumble.h): grains along the stroke break under the
// tip's load, each freeing a loose flake that rings. Off unless the material has [crumble].
struct CrumbleParams {
  bool enabled = false;
  double grain_spacing_m = 5e-4;  // mean path between grains the tip meets
  double strength_n = 0.5;        // Weibull scale of a grain's breaking load (63 % break)
  double weibull_modulus = 3.0;   // spread of the grains' strengths
  double flake_low_hz = 2000.0;   // ring of the largest flake ...
  double flake_high_hz = 12000.0;  // ... and of the smallest
  double size_exponent = 2.5;      // fragment sizes: N(> a) ∝ a^-D
  double flake_mass_kg = 2e-3;     // mass of the largest flake
  double flake_speed_ratio = 0.2;  // a breaking grain's flake's speed over the tip's
  double flake_loss_factor = 0.15;  // η of a flake's ring
  double flake_gain = 0.2;          // pickup weight of a flake's ring
};

struct MaterialParams {
  ResonatorParams resonator;
  ImpactParams impact;
  FrictionParams friction;
  ProbeParams probe;
  RoughnessParams roughness;
  CrumbleParams crumble;
};

}  // namespace sas::synth
