#pragma once
// How the sound and the vibration answer the hand: one straight stroke on a surface, played with a
// chosen style, speed and pressure through the same synth::Scene and the same pen -> probe mapping
// as the kiosk (kiosk_pen.cpp: force = pressure · 2 N, penetration = pressure · relief, width
// from tilt), measured on the sustained stroke. For blind visitors the sound is the texture, so the
// synth must make faster strokes louder and brighter, harder strokes louder, and the three styles
// audibly different; GestureResponseGrid plays the grid that checks it (tests and the
// gesture_response tool, which writes docs/gesture-response.md).
//
// A stroke: the pen rests on the surface (landing at 5 mm/s, so no landing click), waits
// kRestS for the contact to settle, then moves kPathMm along a straight line at constant speed
// and is lifted. The same path at every speed: only the hand changes. The measured span is the
// motion itself; its level is the RMS of channel 1 (sound) and channel 2 (haptic, skin-weighted:
// felt.h) at gain 0 dB, in dB re full scale (1 m/s pickup velocity); its spectrum is a Hann-windowed DFT.
// Styles as visitors make them: scrape = upright pen (a 0.3 mm point), rub = tilted 40° (a 4 mm
// wide probe, kiosk/gesture.h), roll = upright with the roll style (a ball following the relief).

#include <array>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "surface/height_field.h"
#include "synth/material_params.h"
#include "synth/probe_command.h"

namespace sas::kiosk {

// A surface as the kiosk plays it: its height field and material.
struct ResponseSurface {
  std::string name;  // "wooden board", ..., "voice"
  std::shared_ptr<const surface::HeightField> field;
  synth::MaterialParams material;
};

// The four kiosk textures (textures_dir/<name>/texture.toml, their pictures turned into height
// fields as the kiosk does) and the voice surface (the synthetic voice through the kiosk's voice
// path, with the kiosk's voice material). Materials are looked up as `render` does
// (MaterialSearchDirs("")). Throws on missing files.
std::vector<ResponseSurface> LoadResponseSurfaces(const std::string& textures_dir);

struct HandStroke {
  synth::ProbeStyle style = synth::ProbeStyle::kScrape;
  double speed_mm_s = 100.0;
  double pressure = 0.5;  // 0..1
};

// Third-octave bands 100 Hz .. 10 kHz (ISO 266 centres).
inline constexpr int kThirdOctaveBands = 21;

struct StrokeResponse {
  double sound_db = -300.0;   // RMS of channel 1 over the motion
  // Channel 2 over the motion: its skin-weighted RMS (calibration/felt.h) and the texture's
  // detail in it, the range its 10 ms envelope spans (90th minus 10th percentile, dB): bumps,
  // cracks and grain lines move the envelope, a smooth slide or a limited buzz does not.
  double haptic_db = -300.0;
  double haptic_detail_db = 0.0;
  double centroid_hz = 0.0;   // power-weighted mean frequency of channel 1, 20 Hz .. 20 kHz
  // Channel 1's band levels (dB) relative to its total level: the spectrum's shape alone.
  std::array<double, kThirdOctaveBands> band_db{};
  // Channel 1's RMS for the same stroke with the relief alone (friction, the material's
  // micro-roughness and its crumbling crust off): how much of the sound the felt profile itself
  // makes.
  double relief_db = -300.0;
  // The relief alone's centroid: whether the felt profile on its own brightens with speed.
  double relief_centroid_hz = 0.0;
  // Channel 1's character (calibration/character.h): spectral flatness 100 Hz - 10 kHz, crest
  // factor (dB) and onsets per second.
  double flatness = 0.0;
  double crest_db = 0.0;
  double onsets_per_s = 0.0;
  // Channel 1's DIN 45692 sharpness (acum, calibration/sharpness.h) heard at kListeningDbSpl:
  // brightness as listeners judge it, where the power centroid stays on a few strong low modes.
  double sharpness_acum = 0.0;
};

// The level every stroke is scaled to before its sharpness is taken: a typical stroke as the
// kiosk plays it (each stroke is brought near its textures' median, -36 LUFS at the texture's
// gains, and the kiosk adds +12 dB: about 70 dB SPL, calibration/sharpness.h). Taking every
// stroke at one level keeps the hearing threshold from deciding which quiet high bands count,
// so sharpness measures the spectrum's shape as heard; its own level dependence is weak.
inline constexpr double kListeningDbSpl = 70.0;

inline constexpr double kRestS = 0.15;
inline constexpr double kPathMm = 20.0;

// Places per measured stroke. The sound depends on where the pen goes (a crack, a bubble, a grain
// line), so every figure is the median over this many places: seeded positions and directions
// over the surface's middle, none of them a place the level calibration strokes.
inline constexpr int kResponsePlaces = 8;

// Where place `index` of a surface w × h mm lies: the stroke's centre (mm) and direction (a unit
// vector). Seeded, so every run measures the same places.
struct StrokePlace {
  double cx_mm = 0.0, cy_mm = 0.0, dx = 1.0, dy = 0.0;
};
StrokePlace ResponsePlace(int index, double width_mm, double height_mm);

// Plays `stroke` at `places` places and returns the median of each figure over the places
// (each band of the band shape on its own).
StrokeResponse MeasureStroke(const ResponseSurface& surface, const HandStroke& stroke,
                             int places = kResponsePlaces, double fs_hz = 48000.0);

// Mean absolute difference (dB) of two band shapes.
double SpectralDistanceDb(const StrokeResponse& a, const StrokeResponse& b);

// The grid of the gesture-response check and figure.
inline constexpr std::array<synth::ProbeStyle, 3> kResponseStyles = {
    synth::ProbeStyle::kScrape, synth::ProbeStyle::kRub, synth::ProbeStyle::kRoll};
inline constexpr std::array<double, 3> kResponseSpeedsMmS = {30.0, 100.0, 300.0};
inline constexpr std::array<double, 2> kResponsePressures = {0.2, 0.8};

struct ResponseCell {
  HandStroke stroke;
  StrokeResponse response;
};

// Every style × speed × pressure of the grid on one surface, in that nesting order.
std::vector<ResponseCell> MeasureResponseGrid(const ResponseSurface& surface,
                                              int places = kResponsePlaces);

// One stroke whose speed rises steadily from kRampFromMmS to kRampToMmS over kRampS (a hand
// speeding up across the picture, the landing at rest before it as in every stroke): the sound's
// level and sharpness in kRampWindows equal windows, each the median over the places, and how
// well each follows the speed (Spearman's rank correlation of the window's mean speed with its
// level, and with its sharpness).
inline constexpr double kRampFromMmS = 20.0;
inline constexpr double kRampToMmS = 400.0;
inline constexpr double kRampS = 0.8;  // 168 mm: across the middle of the picture
inline constexpr int kRampWindows = 12;
struct RampResponse {
  synth::ProbeStyle style = synth::ProbeStyle::kScrape;
  double pressure = 0.5;
  std::array<double, kRampWindows> speed_mm_s{};
  std::array<double, kRampWindows> sound_db{};
  std::array<double, kRampWindows> sharpness_acum{};
  double sound_rho = 0.0;
  double sharpness_rho = 0.0;
};
RampResponse MeasureRamp(const ResponseSurface& surface, synth::ProbeStyle style, double pressure,
                         int places = kResponsePlaces, double fs_hz = 48000.0);
// Every style at both pressures of the grid.
std::vector<RampResponse> MeasureRamps(const ResponseSurface& surface,
                                       int places = kResponsePlaces);

// Spearman's rank correlation (ties get their mean rank); 0 where either side is constant.
double SpearmanRho(std::span<const double> a, std::span<const double> b);

// One failed relation of the grid: `key` names it ("wooden board/speed-centroid/roll/p0.8"),
// `text` says it with figures ("wooden board, roll, p 0.8: speed 30 -> 300 mm/s moves the centroid
// 568 -> 653 Hz (x1.15), needs x1.30").
//
// Where pressure does not raise the sound, the physics may say it should not: when the relief
// alone plays at least sliding_noise_margin_db under the stroke at both pressures, what is heard
// is the sliding contact's own noise (the probe bridges the relief or does not reach it), and the
// level of that roughness noise is set by the surfaces' roughness, the sliding speed and the
// bodies' dynamics, not by a light load (Ben Abdelounis, Le Bot, Perret-Liaudet & Zahouani, "An
// experimental study on roughness noise of dry rough flat surfaces", Wear 268, 2010; Le Bot &
// Bou Chakra, Tribology Letters 37, 2010: the level follows the nominal contact area, not the
// load). Such a relation is reported as exempt, with its figures, as long as the firmer stroke is
// not quieter by more than sliding_noise_min_rise_db; a quieter firm stroke is a failure whatever
// the noise.
struct ResponseLimits {
  double speed_sound_db = 6.0;
  double speed_sharpness_ratio = 1.15;
  double speed_haptic_db = 0.0;  // "rises": more than this
  double pressure_sound_db = 3.0;
  double style_distance_db = 3.0;
  double sliding_noise_margin_db = 20.0;
  double sliding_noise_min_rise_db = -1.0;
  double ramp_rho = 0.6;
};
struct ResponseFailure {
  std::string key;
  std::string text;
};
struct ResponseCheck {
  std::vector<ResponseFailure> failures;
  std::vector<ResponseFailure> exemptions;  // pressure relations the sliding noise explains
};
// Every relation of the grid on one surface: speed 30 -> 300 mm/s raises the sound level by
// speed_sound_db, the sharpness by speed_sharpness_ratio and the vibration (per style and
// pressure);
// pressure 0.2 -> 0.8 raises the sound by pressure_sound_db (per style and speed), or is exempt
// (above); every two styles' band shapes differ by style_distance_db (per speed and pressure).
// Returns the ones that fail and the exempt ones.
ResponseCheck CheckResponseGrid(const std::string& surface_name,
                                const std::vector<ResponseCell>& grid,
                                const ResponseLimits& limits = {});
// How many relations CheckResponseGrid checks on one surface.
int ResponseRelationCount();
// The accelerating strokes' relations: level and sharpness each follow the speed with Spearman's
// rho >= ramp_rho. Keys "<surface>/ramp-sound/<style>/p0.2", ".../ramp-sharpness/...".
std::vector<ResponseFailure> CheckRamps(const std::string& surface_name,
                                        const std::vector<RampResponse>& ramps,
                                        const ResponseLimits& limits = {});
// How many relations CheckRamps checks on one surface.
int RampRelationCount();

// How sharp a surface sounds at one speed of the grid: the median sharpness of its cells at that
// speed (every style and pressure).
double SharpnessAtSpeed(const std::vector<ResponseCell>& grid, double speed_mm_s);
// Broken glass is the sharpest of the kiosk textures at every speed of the grid (the voice surface
// is not a texture and is left out): one relation per speed, key
// "character/glass-sharpest/<speed>mm/s", its text naming the sharper textures with figures.
// `names[i]` is the surface of `grids[i]`.
std::vector<ResponseFailure> CheckSharpestTexture(
    const std::vector<std::string>& names, const std::vector<std::vector<ResponseCell>>& grids);
inline constexpr int kSharpestRelationCount = static_cast<int>(kResponseSpeedsMmS.size());

// A level for the figures: "-42.5", or "< -150" where the render is silent and what is left is
// the float residue of a decaying ring (-220 dB is not a level anyone hears). A print floor, not
// surface::kSilenceDb (the value Loudness returns for digital silence).
inline constexpr double kPrintFloorDb = -150.0;
std::string LevelText(double db);

}  // namespace sas::kiosk
