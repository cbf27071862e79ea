#pragma once
// Per-stroke loudness matching of the kiosk textures (for a noisy room): the same stroke should
// sound equally loud and vibrate equally strongly on any of the four textures (within 1 dB), so
// that switching tokens never jumps in level. One gain pair per texture ([gains] in texture.toml,
// calibration/texture_levels.h) matches the textures on average only: their levels grow with stroke
// speed and pressure at different rates (glass spans 17 dB from a slow firm rub to a fast light
// scrape, wood 6 dB). So each texture also carries its measured stroke levels over a grid
// (texture.toml [levels]: style scrape | rub x probe width x pen speed x pen pressure,
// surface::StrokeLevelTable), and the kiosk corrects every stroke by the difference between the
// reference level for that stroke and the texture's own:
//
//   reference(style, width, speed,    = median over the loaded textures' tables (dB), moved just
//             pressure)                 enough that every texture reaches it within
//                                       kMaxStrokeCorrectionDb
//   correction(texture, ...)          = reference - table(texture), each interpolated
//
// so the stroke dynamics (faster and harder = louder) stay those of the typical texture and only
// the texture-to-texture differences go. The median (of four: the mean of the middle two), so an
// outlier does not set the level for all; but where one texture lies more than
// kMaxStrokeCorrectionDb from it (broken glass rubbed slowly sticks and stays ~25 dB below the
// others; its vibration, cracks only, is capped by kMaxHapticGainDb) the reference moves towards
// it just far enough that it can still be matched, and halfway between the extremes when the
// textures span more than twice the limit (then the two extremes stay apart by the excess). The
// reference is formed at load time from the tables, so each texture's table is measured on its own
// (regenerating one texture does not depend on the others); a texture without a table, or with a
// grid that differs from the first table's, gets no correction (0 dB) and is left out of the
// reference. Interpolation: linear in probe width (within the style's widths), in log speed and in
// pressure (trilinear), held at the grid's edge outside it; style by the probe's style (rub for a
// rub, scrape for a scrape or roll). The sound levels are interpolated as powers (10^(L/10)), the
// vibration levels in dB. Between two grid points where a texture changes regime (broken glass
// rubbed at p0.3 on the flat squeaks at 60 mm/s, -39 dB, and sticks nearly silent at 40 mm/s,
// -74 dB) a dB average put the stroke between the two and boosted it as if it were half-silent,
// while it squeaks: a rub at 60 mm/s, p0.25 came out 10 dB louder than on the other textures. The
// power average is the level of a mixture of the two regimes, dominated by the loud one (0.97 dB
// apart then; over the eight held-out strokes the sound spreads summed 20.2 dB instead of 27.9).
// Where the levels change smoothly the two differ by a fraction of a dB. For vibration the dB
// average stays: glass's vibration comes from the cracks a stroke crosses, and there the power
// average did worse (summed spreads 57.7 dB instead of 53.6). A level table cannot follow every
// regime change between its points (docs/engineering.md, "Textures, loudness matching and spoken
// cues", gives what it leaves).
//
// Run time (KioskEngine, control thread): the pen's speed and pressure are smoothed (StrokeTracker:
// one-pole, kStrokeSmoothingS; a new stroke starts from its first measured speed), the correction
// for the texture under the pen goes to the scene as linear gains (synth::Scene::SetStrokeGains),
// which the audio thread applies before the limiters, ramped over 20 ms. While the pen is up the
// last correction holds, so a stroke's tail rings out at the gain it started with.

#include <vector>

#include "surface/texture_file.h"
#include "synth/probe_command.h"

namespace sas::kiosk {

struct StrokeCorrection {
  double sound_db = 0.0;
  double haptic_db = 0.0;
};

// The reference level of one grid point from the textures' levels there (as above).
double ReferenceLevel(std::vector<double> levels);

// How one channel's levels are averaged between grid points (above).
enum class LevelBlend { kDecibels, kPower };

// The table's levels at (style, probe width, speed, pressure), interpolated as above: sound as
// `sound_blend` says, vibration in dB.
StrokeCorrection InterpolateLevels(const surface::StrokeLevelTable& table, synth::ProbeStyle style,
                                   double width_mm, double speed_mm_s, double pressure,
                                   LevelBlend sound_blend = LevelBlend::kDecibels);

// Largest correction applied either way (dB): beyond it a table is broken, not a texture quieter.
inline constexpr double kMaxStrokeCorrectionDb = 18.0;

class StrokeGainMap {
 public:
  StrokeGainMap() = default;
  // One entry per texture (nullptr or a table); the reference is the mean of those that agree on
  // the first table's grid.
  explicit StrokeGainMap(const std::vector<const surface::StrokeLevelTable*>& tables);

  // The correction for texture `texture` (an index into the constructor's list; out of range or
  // without a table: 0 dB), clamped to +-kMaxStrokeCorrectionDb.
  StrokeCorrection Correction(int texture, synth::ProbeStyle style, double width_mm,
                              double speed_mm_s, double pressure) const;
  // Textures that take part in the reference.
  int matched_textures() const { return matched_; }

 private:
  std::vector<surface::StrokeLevelTable> levels_;  // per texture: its own table (or empty)
  surface::StrokeLevelTable reference_;            // the reference level per grid point
  int matched_ = 0;
};

// The pen's smoothed speed and pressure over a stroke (control thread, per pen sample). The speed
// at touch-down comes from the pen's last report before it (hovering, kMaxReportGapS ago at
// most): a hand comes in moving, so the landing click already gets the stroke's correction.
// Without such a report (touch, a pen brought from out of range) the last stroke's speed holds
// until the second sample.
inline constexpr double kStrokeSmoothingS = 0.05;
inline constexpr double kMaxReportGapS = 0.05;
inline constexpr double kMaxPenSpeedMmS =
    2000.0;  // faster: a jump (out of range and back), not a stroke
class StrokeTracker {
 public:
  // A pen sample: tip down or not, the pen's speed since its previous report (mm/s; `has_speed`
  // false when there is none within kMaxReportGapS or it is implausible), pressure 0..1, time
  // since the previous report (s).
  void Update(bool tip_down, bool has_speed, double speed_mm_s, double pressure, double dt_s);
  bool valid() const { return valid_; }  // the pen has touched down since the start
  double speed_mm_s() const { return speed_mm_s_; }
  double pressure() const { return pressure_; }

 private:
  bool valid_ = false;
  bool down_ = false;
  double speed_mm_s_ = 0.0;
  double pressure_ = 0.0;
};

}  // namespace sas::kiosk
