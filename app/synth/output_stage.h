#pragma once
// Output stage: channel 1 drives the speaker, channel 2 the vibrotactile
// transducer on the stylus. The paper (§4) drives the transducer with the low-frequency part of the
// synthesized audio; here it gets the contact force on the tip instead (`felt`), which carries the
// relief, the cracks and the bubbles where the surface's own ring (glass: all above 400 Hz) does
// not. Chain: inputs pickup velocity and felt (m/s, where 1 m/s = full scale)
//   ch 1: NaN/Inf -> 0, × sound_gain × stroke sound gain, soft limiter
//   ch 2: NaN/Inf -> 0, 4th-order Butterworth high-pass at `low` (the contact force's slow part,
//         the relief's shape under the hand, is not vibration) and low-pass at `high` (so that the
//         limiter judges the peaks the transducer gets: a crack's or a landing's force is a sharp
//         pulse whose broadband peak is many times its peak in the band, and a limiter fed
//         the whole pulse squeezed strokes whose output stayed 19 dB under the ceiling),
//         × haptic_gain × low-vibration trim
//         × stroke haptic gain, soft limiter scaled to the haptic ceiling (c · SoftLimit(x / c):
//         linear up to kKnee · c, never reaching c), then the final band limit: 2nd-order
//         Butterworth high-pass at `low` and 16th-order Butterworth low-pass at `high` (RBJ
//         biquads), so the limiter's own products (its harmonics, and the slow swing it leaves
//         when it squeezes one-sided pulses) never reach the transducer: the skin's band,
//         40-400 Hz (its threshold rises steeply above ~400 Hz, Verrillo 1963). Skipped (zeros)
//         when haptic_enabled is false.
//         The band limit may lift a limited peak over c, by at most the sum of its impulse
//         response's magnitudes (BandLimitGain(), 2.2 at 48 kHz; square waves at 50-300 Hz come
//         out at 1.3-1.9): the kiosk's gains keep strokes well under the ceiling, and the final
//         safety stage (a smooth look-ahead gain, no waveshaping) holds the ceiling for every
//         source. Scaling the limiter down by that bound instead cost broken glass, whose felt
//         cracks are its peaks, 5 dB of its level (measured over the visitor population).
// Stroke leveller (sound_level_cap > 0): the running mean square of the gained sound, K-weighted
// (BS.1770, as the textures' loudness is measured) (one-pole,
// kLevellerWindowS, about a syllable: short enough to catch one loud stroke, long enough to leave
// clicks and the texture's own rhythm alone) sets a gain of min(1, cap / RMS), which the sound
// follows fast going down (kLevellerAttackS) and slowly back up (kLevellerReleaseS), so the level
// of a loud stroke is brought towards the cap without pumping. When the pen lands for a new stroke
// (NewStroke, from the scene) the gain lets go at the attack's pace: one stroke's level is not
// carried into the next. A burst (a crack struck, a knot crossed: tens of milliseconds) is over
// before that window has heard it, so a second detector with a short window (kBurstWindowS) holds
// bursts to kBurstOverCapDb above the cap, with a gain that comes back as fast as the burst went
// (kBurstReleaseS): a squeak or a crack still stands out of the stroke, it no longer blasts.
// Peaks are the soft limiter's and the final safety stage's job.
// Soft limiter: linear up to kKnee, then a tanh shoulder approaching 1: C¹, odd, |y| < 1 for
// every finite input, so "exaggerated" gains never clip hard and never overflow.
// Low-vibration trim: 1, or low_vibration_gain while the mode is on; a change ramps linearly over
// kLowVibrationRampS (no click on the transducer) and then holds the exact value.
// Stroke gains (the kiosk's per-stroke loudness matching, levels/stroke_gain.h): two linear factors
// in [0, kMaxStrokeGain] set at run time; a change ramps linearly over the time asked for
// (kLowVibrationRampS by default, kMinStrokeRampS at least; on the transducer the two multiply into
// one ramped factor), Reset() jumps to them.

#include <algorithm>
#include <array>
#include <cmath>

#include "synth/material_params.h"

namespace sas::synth {

struct Biquad {
  double b0 = 1.0, b1 = 0.0, b2 = 0.0, a1 = 0.0, a2 = 0.0;  // normalised (a0 = 1)
  double s1 = 0.0, s2 = 0.0;                                // transposed direct form II state
  double Process(double x) {
    const double y = b0 * x + s1;
    s1 = b1 * x - a1 * y + s2;
    s2 = b2 * x - a2 * y;
    return y;
  }
};

// The K-weighting of ITU-R BS.1770-4 (Annex 1): a +4 dB high shelf above ~1.7 kHz (the head),
// then a ~38 Hz high-pass (the RLB curve), as two biquads for sample rate `fs`. The standard gives
// the 48 kHz coefficients; this designs them from the filters' analogue parameters (shelf
// 1681.97 Hz, +4.00 dB, Q 0.7072; high-pass 38.14 Hz, Q 0.5003), which reproduce that table.
std::array<Biquad, 2> KWeighting(double fs);

// Slow level control of one channel (see the stroke leveller above): cap is a K-weighted RMS
// (BS.1770: 10^((LUFS + 0.691) / 20) for a cap in LUFS), 0 = off. The detector hears the sound as
// the loudness measure does, so a bright sound (broken glass: most modes above 2 kHz, where the
// shelf adds up to 4 dB) is held to the same loudness as a dull one, not to the same RMS.
struct Leveller {
  double cap_square = 0.0;
  double level_square = 0.0;  // running mean square of the K-weighted input
  double gain = 1.0;
  double level_step = 0.0, attack_step = 0.0, release_step = 0.0;
  double burst_cap_square = 0.0;  // cap_square raised by the burst allowance
  double burst_square = 0.0;      // the same mean square over the short window
  double burst_gain = 1.0;
  double burst_step = 0.0, burst_attack_step = 0.0, burst_release_step = 0.0;
  bool landing = false;   // a new stroke: let go at the attack's pace (NewStroke)
  int landing_samples = 0;  // the landing's length in samples (Prepare)
  int landing_left = 0;     // samples of the current landing the detector still ignores
  std::array<Biquad, 2> weighting{};

  // Times in seconds; burst_over_db is how far over the cap a burst may go.
  struct Times {
    double window_s, attack_s, release_s, landing_s;
    double burst_window_s, burst_attack_s, burst_release_s, burst_over_db;
  };
  void Prepare(double cap, const Times& times, double fs);
  void Reset() {
    level_square = 0.0;
    gain = 1.0;
    burst_square = 0.0;
    burst_gain = 1.0;
    landing = false;
    landing_left = 0;
    for (auto& section : weighting) section.s1 = section.s2 = 0.0;
  }
  // The pen lands for a new stroke. The level measured so far was the last stroke's, and the gain
  // that held it down comes back within a few attack times instead of the slow release, so a
  // soft stroke after a loud one is not muted for a second (the slow release is there to keep a
  // stroke from pumping, not to carry one stroke's level into the next). The landing click itself
  // is a tap, not the stroke's level: the slow detector ignores it, else a click 7 LU over the cap
  // (wood) pulled the whole stroke after it down by 2-4 dB through the slow release. The burst
  // detector hears it, as it hears a crack: let through whole, a firm landing on cracked ground
  // was the loudest 400 ms of a visit, 15 LU over the texture's median stroke.
  void NewStroke() {
    level_square = 0.0;
    burst_square = 0.0;
    landing = gain < 1.0;
    landing_left = landing_samples;
  }
  double Apply(double y) {
    if (!(cap_square > 0.0)) return y;
    return ApplyHeard(y, weighting[1].Process(weighting[0].Process(y)));
  }
  // Apply() after the K-weighting: `heard` is y through `weighting` (OutputStage::ProcessBlock
  // runs that filter over a block first, with its state in registers).
  double ApplyHeard(double y, double heard) {
    if (landing_left > 0) {
      --landing_left;
    } else {
      level_square += level_step * (heard * heard - level_square);
    }
    burst_square += burst_step * (heard * heard - burst_square);
    const double want = level_square > cap_square ? std::sqrt(cap_square / level_square) : 1.0;
    if (want < gain) {
      landing = false;
      gain += attack_step * (want - gain);
    } else {
      gain += (landing ? attack_step : release_step) * (want - gain);
      if (landing && gain > 0.999) landing = false;
    }
    // The burst detector hears the input after the slow gain, so the two do not both pull the
    // same sustained excess down.
    const double after_slow = burst_square * gain * gain;
    const double burst_want =
        after_slow > burst_cap_square ? std::sqrt(burst_cap_square / after_slow) : 1.0;
    burst_gain += (burst_want < burst_gain ? burst_attack_step : burst_release_step) *
                  (burst_want - burst_gain);
    return y * gain * burst_gain;
  }
};

class OutputStage {
 public:
  static constexpr double kKnee = 0.5;
  static constexpr double kLowVibrationRampS = 0.02;
  static constexpr double kMaxStrokeGain = 10.0;  // +20 dB
  static constexpr double kMinStrokeRampS = 0.001;
  static constexpr double kLevellerWindowS = 0.05;
  static constexpr double kLevellerAttackS = 0.005;
  static constexpr double kLevellerReleaseS = 0.5;
  // How long after the pen lands the leveller ignores the sound (the landing click and the first
  // of its ring). Shorter, wood's ring (still ~10 LU over the stroke 50 ms after landing) trips
  // it; longer, a short loud stroke plays that much longer before the leveller catches it.
  static constexpr double kLevellerLandingS = 0.075;
  // The burst detector: a window of about one crack's ring, and an allowance that keeps a glass
  // crack or a wood knot audibly over the stroke.
  static constexpr double kBurstWindowS = 0.01;
  static constexpr double kBurstAttackS = 0.001;
  static constexpr double kBurstReleaseS = 0.05;
  static constexpr double kBurstOverCapDb = 3.0;

  void Prepare(const OutputParams& params, double sample_rate_hz);
  void Reset();

  // Below the knee (the usual sample, and false for NaN) inline; the rest out of line.
  static double SoftLimit(double x) { return std::fabs(x) <= kKnee ? x : SoftShoulder(x); }

  // One frame of sound alone: the transducer gets nothing from the pickup (its haptic sample is
  // the band limit's ring of what came before).
  void Process(double pickup, float* sound, float* haptic) { Process(pickup, 0.0, sound, haptic); }
  // The same with `felt` (m/s, like the pickup) added to the transducer's input only: what the
  // stylus itself carries from the contact (Scene: the contact force).
  void Process(double pickup, double felt, float* sound, float* haptic) {
    if (!std::isfinite(pickup)) pickup = 0.0;
    if (!std::isfinite(felt)) felt = 0.0;
    if (stroke_sound_ != stroke_sound_target_) {
      stroke_sound_ += stroke_sound_step_;
      if ((stroke_sound_step_ > 0.0) == (stroke_sound_ >= stroke_sound_target_)) {
        stroke_sound_ = stroke_sound_target_;
      }
    }
    *sound =
        static_cast<float>(SoftLimit(sound_leveller_.Apply(sound_gain_ * stroke_sound_ * pickup)));
    if (!haptic_enabled_) {
      *haptic = 0.0f;
      return;
    }
    double y = felt;
    for (auto& section : pre_) y = section.Process(y);
    if (!std::isfinite(y)) {  // as below: never let a poisoned filter state stay
      Reset();
      *haptic = 0.0f;
      return;
    }
    if (trim_ != trim_target_) {
      trim_ += trim_step_;
      if ((trim_step_ > 0.0) == (trim_ >= trim_target_)) trim_ = trim_target_;
    }
    y = haptic_ceiling_ * SoftLimit(haptic_drive_ * trim_ * y);
    for (auto& section : sections_) y = section.Process(y);
    if (!std::isfinite(y)) {  // cannot happen for finite input, but never let NaN reach a device
      Reset();
      y = 0.0;
    }
    *haptic = static_cast<float>(y);
  }

  // `n` frames at once, interleaved into `out` (sound, haptic): the same arithmetic in the same
  // order per channel as Process() called frame by frame, so the same samples bit for bit (the
  // scene's deferred frames). Each channel runs as its own loops, the filters (K-weighting,
  // band-pass) a few sections at a time with their state in registers: per frame, the sections'
  // dependency chain and its state round trip through memory made this stage a tenth of the
  // scene's time.
  void ProcessBlock(const double* pickup, const double* felt, float* out, int n);

  // Real-time safe: the pen landed for a new stroke (Leveller::NewStroke).
  void NewStroke() { sound_leveller_.NewStroke(); }

  // Real-time safe: starts the ramp to the low-vibration trim (on) or back to 1 (off).
  void SetLowVibration(bool on);
  bool low_vibration() const { return low_vibration_; }

  // Real-time safe: starts the ramps to the stroke gains (linear, clamped to [0, kMaxStrokeGain];
  // non-finite: 1).
  void SetStrokeGains(double sound, double haptic, double ramp_s = kLowVibrationRampS);
  double stroke_sound_gain() const { return stroke_sound_target_; }
  double stroke_haptic_gain() const { return stroke_haptic_; }
  // The largest stroke gain (current or ramp target, at least 1): bounds the output's gain over
  // the pickup until the next SetStrokeGains (for the scene's silence and skip bounds).
  double StrokeGainBound() const {
    return std::max({1.0, stroke_sound_, stroke_sound_target_, trim_, trim_target_});
  }

  // The most the band limit after the limiter can lift a peak (the L1 norm of its impulse
  // response): the transducer's output never exceeds haptic_ceiling × this. Not real-time.
  double BandLimitGain() const;

  // Largest magnitude held in the filter state (for idle detection).
  double FilterActivity() const;

 private:
  // Before the limiter: 2 high-pass + 2 low-pass biquads; after it: 1 high-pass + 8 low-pass.
  static constexpr int kPreSections = 4;
  static constexpr int kSections = 9;
  std::array<Biquad, kPreSections> pre_{};
  std::array<Biquad, kSections> sections_{};
  double sound_gain_ = 1.0;
  double haptic_gain_ = 1.0;
  double haptic_ceiling_ = 1.0;
  double haptic_drive_ = 1.0;  // haptic_gain_ / haptic_ceiling_
  double sample_rate_hz_ = 48000.0;
  double low_vibration_gain_ = 0.25;
  double ramp_samples_ = 960.0;
  bool low_vibration_ = false;
  double trim_ = 1.0;
  double trim_target_ = 1.0;
  double trim_step_ = 0.0;
  double stroke_sound_ = 1.0;  // ramped sound factor, its target and step
  double stroke_sound_target_ = 1.0;
  double stroke_sound_step_ = 0.0;
  double stroke_haptic_ = 1.0;  // requested haptic factor (part of the trim's target)
  bool haptic_enabled_ = true;
  Leveller sound_leveller_;

  void StartTrimRamp(double samples);
  static double SoftShoulder(double x);  // SoftLimit above the knee, and non-finite input
  // Up to kBlockFrames of ProcessBlock; returns how many frames it finished (fewer when the
  // band-pass guard reset the stage: the rest is run again from the reset state).
  static constexpr int kBlockFrames = 64;
  int ProcessRun(const double* pickup, const double* felt, float* out, int n);
};

}  // namespace sas::synth
