#pragma once
// Loudness and vibration-strength matching of the kiosk textures (for a noisy room): the
// same stroke on any of the four textures should sound equally loud and vibrate equally strongly
// (within 1 dB), so that switching tokens never jumps in level. A texture's [gains] and [levels]
// in its texture.toml are what the kiosk corrects with (stroke_gain.h); this file measures and
// computes them ("Calibration" below).
//
// Measurement — through the kiosk's own path, so that what is matched is what visitors get:
// a KioskEngine (kiosk_engine.h) holding the one texture as the kiosk loads it (picture-derived
// height field, its material, the scene prepared and no cross-fade running), driven on its virtual
// clock by VirtualVisit (virtual_visit.h: the headless visit's loop) on the kiosk's 1920 x 1080
// screen with the kiosk's pen -> probe mapping. It plays the visitor strokes below one after the
// other, with the pen lifted between them, at the texture's gains `gains` plus `global` gains (the
// kiosk configuration's gains.sound_gain_db / haptic_gain_db, default 0). Over each stroke's
// pen-down span from kSettleS after touch-down (the sustained stroke, without the landing click;
// shifted by the engine's one-buffer pen-to-sound delay):
//   sound   channel 1, BS.1770 K-weighted loudness (LUFS, ungated) — surface/loudness.h says why
//   haptic  channel 2, skin-weighted RMS in dB re full scale (felt.h: the hand's threshold curve,
//           as the K-weighting is the ear's); the output stage has band-limited it to 40–400 Hz
//
// Calibration, per texture on its own (regenerating one texture must not depend on the others):
// the calibration strokes are a grid (CalibrationGrid: style scrape | rub x probe width x pen
// speed x pen pressure, spanning what visitors do). First one pair of gains ([gains]) brings the
// mean of the grid strokes' levels (in dB, each stroke counting once) to the common targets; then
// the levels of every grid stroke at those gains (mean over its places) are the texture's [levels]
// table. One gain pair cannot match every stroke: the textures' levels do not grow alike with speed
// and pressure (broken glass rubbed at 40 mm/s sticks and is nearly silent, at 350 mm/s it is the
// loudest), so with [gains] alone the same grid stroke differs by up to 25 dB (sound) and 37 dB
// (vibration) between textures. The kiosk removes that stroke by stroke from the tables
// (stroke_gain.h: towards the median of the loaded textures' levels for the stroke); the
// measurement here, on one texture loaded alone, sees no correction (its own table is the
// reference).
// The output stage applies the gain to the pickup signal before its soft limiter, so the level is
// exactly linear in the gain while the strokes' peaks stay below the limiter's knee: then one
// pass at 0 dB gives the answer. When a peak would reach the knee, the calibration plays the
// strokes again at the new gains until it converges (within 0.05 dB).
//
// The haptic gain is capped at kMaxHapticGainDb. A texture whose material has no mode in the
// transducer's band (a glass tile whose modes all lie above 3 kHz) vibrates only with the
// contact's low-frequency content, which between its cracks is next to nothing; measured on the
// sustained stroke (without the landing click) its gain would reach the cap. The cap only stops a
// broken material from getting an absurd gain (the output stage's haptic ceiling and soft limiter
// bound the transducer's peaks anyway); a capped texture vibrates weaker than the others on average
// and its [levels] say so, so the per-stroke correction (up to stroke_gain.h's limit) makes up the
// difference stroke by stroke. Offline only (texture_generator, tests).

#include <cstdint>
#include <string>
#include <vector>

#include "calibration/felt.h"
#include "kiosk/virtual_visit.h"
#include "levels/output_gains.h"
#include "surface/texture_file.h"

namespace sas::kiosk {

struct StrokeLevels {
  double sound_lufs = 0.0;
  double haptic_rms_db = 0.0;
  double sound_peak = 0.0;  // largest |sample| over the stroke (linear, full scale = 1)
  double haptic_peak = 0.0;
  // The loudest 400 ms of the sound (EBU R 128 momentary loudness: BS.1770 K-weighted, ungated,
  // windows every 100 ms) over the measured span; a span shorter than 400 ms is one window from
  // its start.
  double sound_momentary_max_lufs = 0.0;
  // Channel 2's figures (felt.h), when LevelMeasurement::felt_figures asks for them.
  FeltFigures felt;
};
inline constexpr double kMomentaryWindowS = 0.4;
// How long after its lift a whole stroke is measured (LevelMeasurement::whole_strokes): the pause
// before the next stroke.
inline constexpr double kGapAfterLiftS = 0.15;
inline constexpr double kMomentaryHopS = 0.1;

// A stroke of the calibration, as visitors make them at the kiosk.
// The screen the strokes are drawn on, in pixels (KioskEngineOptions' default).
inline constexpr int kScreenWidthPx = 1920;
inline constexpr int kScreenHeightPx = 1080;

struct VisitorStroke {
  std::string name;  // e.g. "scrape medium"
  PenStroke pen;     // screen fractions on the kiosk's 1920 x 1080 screen
};

// The calibration grid: probe widths (the pen's tilt: kiosk/gesture.h), pen speeds (mm/s) and
// pressures, for scrape (pen upright to ~17°, a 0.3–2 mm point) and rub (pen tilted further, a
// 2–6 mm wide probe). 40–350 mm/s spans slow to fast strokes; pressure 0.3–0.6 stays below the
// bubbles' pop force, so bubble wrap is stroked, not popped. Each axis is there because a level
// depends on it differently from texture to texture: wood's grain is louder under a narrow point
// and its scrape jumps by up to 17 dB between pressure 0.3 and 0.6 (the point starts to dig into
// the grain), so a coarser grid left held-out strokes up to 9 dB apart.
// Each grid point is stroked at `places` places on the picture, in different directions; its level
// is the mean (dB) over them: where a stroke runs changes its level too (broken glass: whether it
// crosses cracks, wood: whether it crosses the knot), and the table is meant to hold the
// texture's typical level for the stroke, so there must be enough places for their mean to settle
// (from place to place a stroke's level varies by a standard deviation of up to 4 dB in sound
// and 8 dB in vibration: 12 places put the table's sampling error near 1-2 dB at worst).
struct CalibrationGrid {
  std::vector<double> scrape_widths_mm = {0.3, 0.9, 1.9};
  std::vector<double> rub_widths_mm = {2.1, 4.0, 6.0};
  // Rolling (a ball following the relief) is far quieter than sliding on the soft textures; its
  // own rows let the kiosk match it across textures. The kiosk's roll is the pen's ball whatever
  // the tilt (kiosk/pen_mapping.h, ProbeWidthMm): one width. Empty: no roll rows. The texture's
  // [gains] come from scrape and rub only, so these rows change no gain.
  std::vector<double> roll_widths_mm = {0.3};
  std::vector<double> speeds_mm_s = {40.0, 80.0, 160.0, 350.0};
  std::vector<double> pressures = {0.3, 0.45, 0.6};
  int places = 12;
};

// The grid's strokes: for each grid point in the order of surface::StrokeLevelTable
// ([style][width][speed][pressure]) `places` strokes at places 0, 1, 2, ... (PlacedStroke), each
// kStrokeS long after kHoverS of hover.
std::vector<VisitorStroke> CalibrationStrokes(const CalibrationGrid& grid);
const std::vector<VisitorStroke>& CalibrationStrokes();  // the default grid's
inline constexpr double kStrokeS = 0.4;
// A stroke's level is measured over its pen-down span from this long after touch-down: the
// sustained stroke, not the landing click (texture_levels.cpp says why).
inline constexpr double kSettleS = 0.1;

// A stroke at place `place` (0, 1, 2, ...: spread over the screen, every place in a new direction,
// deterministic): the calibration uses the first places, tests take others.
VisitorStroke PlacedStroke(const char* name, int place, double speed_mm_s, double pressure,
                           double tilt_deg);
// The mean (dB) of each run of `places` consecutive strokes' levels (peaks: the largest).
std::vector<StrokeLevels> MeanOverPlaces(const std::vector<StrokeLevels>& levels, int places);
// Each stroke comes in hovering for this long (PenStroke::hover_s): the kiosk knows its speed at
// touch-down, so the landing click gets the stroke's correction too.
inline constexpr double kHoverS = 0.04;

// A visitor stroke of kStrokeS (after kHoverS of hover) from (x0, y0) (screen fractions) at
// `angle_deg` (0 = rightwards, positive = down the screen) and `speed_mm_s` on the kiosk's screen
// at the display's pixel pitch.
VisitorStroke MakeStroke(const char* name, double x0, double y0, double angle_deg,
                         double speed_mm_s, double pressure, double tilt_deg);

// A population of visitor strokes, drawn from `seed` (the same strokes on every machine): style
// scrape, rub or roll (a third each; scrape with the pen upright to the rub tilt, rub tilted from
// there to 60°, roll at any tilt), speed 20–400 mm/s log-uniform, pressure 0.1–0.9, 0.3–1.5 s long
// (shortened where the screen is too small for it), at a random place in a random direction.
// `duration_scale` shortens every stroke (a quick run of the same population).
std::vector<VisitorStroke> VisitorPopulation(int count, std::uint32_t seed,
                                             double duration_scale = 1.0);
// The p-quantile (0..1) of `values`, linear between neighbours (for the population's figures).
double Percentile(std::vector<double> values, double p);

struct LevelMeasurement {
  double global_sound_gain_db = 0.0;  // on top of the texture's gains
  double global_haptic_gain_db = 0.0;
  // The kiosk's stroke leveller (KioskConfig::stroke_cap_lu); off for the calibration, which
  // measures the strokes' own levels.
  double stroke_cap_lu = 0.0;
  std::vector<VisitorStroke> strokes = CalibrationStrokes();
  // Further textures loaded into the same engine, as in the kiosk (their [levels] tables join the
  // per-stroke reference); the measured texture is the engine's default one.
  std::vector<std::string> other_textures;
  // Strokes per visit (0: every stroke in one visit). Between visits the pen stays up past the
  // session's idle timeout (shortened to kVisitIdleTimeoutS), so the kiosk's own idle reset
  // un-pops the bubble wrap as it does between visitors: a population played as one visit would
  // measure a sheet its strokes have popped bare, which no visitor finds.
  int strokes_per_visit = 0;
  // Measure each stroke whole: from its touch-down (the landing included) to kGapS after its lift
  // (the lift and the ring it leaves), instead of the sustained span from kSettleS after
  // touch-down to the lift that the calibration matches.
  bool whole_strokes = false;
  // Also measure each stroke's vibration figures (StrokeLevels::felt; a periodogram per stroke).
  bool felt_figures = false;
};

// The population's visits (VisitorPopulation played through MeasureStrokeLevels): a visitor's
// strokes on one texture before the kiosk's idle reset. The soak's visitors (tests/kiosk) make
// 3-12 actions, about half of them strokes, over all the textures; ten strokes on one texture is a
// visitor who stays with it, so the bubble wrap is measured with more of its bubbles popped than
// most visitors leave (a third of the population presses hard enough to pop every bubble it
// crosses).
inline constexpr int kVisitStrokes = 10;
// The idle timeout of the measuring engine when strokes_per_visit is set (the kiosk's is 60 s:
// rendering a minute of silence between visits would only cost time).
inline constexpr double kVisitIdleTimeoutS = 1.0;

// The calibration targets for the strokes' mean at the texture gains only (global gains 0 dB).
// The loudest strokes' peaks lie up to ~26 dB above them (sound; bubble wrap: -9.7 dBFS), so
// with the kiosk's default +12 dB sound only the sharpest clicks pass the soft limiter's knee
// (-6 dBFS) while the average level is room-filling. The transducer carries the contact force
// too (synth::Scene), whose impacts on ridges and cracks are peakier still: its target sits lower
// so that the calibration strokes stay under the knee, and the kiosk's default +33 dB puts a
// typical stroke of every style within 15 dB of the transducer's ceiling (scrapes, the weakest,
// by a dB or less: population_levels), strong ones in the limiter's shoulder (the skin needs a
// strong, steady signal; clipping is felt, not heard).
inline constexpr double kTargetSoundLufs = kCalibratedSoundLufs;
inline constexpr double kTargetHapticRmsDb = -60.0;
// Largest haptic gain the calibration gives a texture (see above).
inline constexpr double kMaxHapticGainDb = 60.0;

// Plays `measurement.strokes` on the texture file `texture_toml` through the kiosk engine with
// texture gains `gains` (not the ones in the file: the caller chooses) and returns the levels of
// each stroke, in order (from kSettleS after touch-down). Throws on any problem.
std::vector<StrokeLevels> MeasureStrokeLevels(const std::string& texture_toml,
                                              const surface::TextureGains& gains,
                                              const LevelMeasurement& measurement = {});

// The mean of a set of strokes' levels (dB) and their largest peaks; `silent` when any is silent.
struct StrokeSetLevels {
  double sound_mean_lufs = 0.0;
  double haptic_mean_rms_db = 0.0;
  double sound_peak = 0.0;
  double haptic_peak = 0.0;
  bool silent = false;
};
StrokeSetLevels Summarise(const std::vector<StrokeLevels>& strokes);

// The texture gains that bring the grid strokes' mean levels to the targets (within 0.05 dB; the
// haptic gain at most kMaxHapticGainDb), rounded to 0.01 dB, and the grid strokes' levels at those
// gains (0.01 dB). `texture_toml` is measured alone; its own [levels] must be absent.
struct TextureCalibration {
  surface::TextureGains gains;
  surface::StrokeLevelTable levels;
};
TextureCalibration CalibrateTexture(const std::string& texture_toml,
                                    double target_sound_lufs = kTargetSoundLufs,
                                    double target_haptic_rms_db = kTargetHapticRmsDb,
                                    const CalibrationGrid& grid = {});

// A texture's [levels] table as texture.toml text (texture_generator, texture new): the axes, then
// per style one row per speed of one value per pressure, a block of rows per width.
std::string LevelTableToml(const surface::StrokeLevelTable& levels);

}  // namespace sas::kiosk
