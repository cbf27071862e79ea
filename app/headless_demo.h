#pragma once
// The headless default: on a machine with no display, `sketch-a-scratch` runs a
// scripted visit through the same KioskEngine and VisitView the kiosk uses, with the platform's
// offline audio loop in place of the sound card and a virtual clock in place of real time:
//   each of the four textures chosen by a token, then stroked once in each style (scrape: pen
//   upright; rub: pen tilted; roll), a token switch in the middle of a stroke (the sound
//   cross-fades), and a synthesised voice (a vowel-like glottal pulse train through formant
//   resonators, with syllables) recorded through the record-button flow, turned into a surface
//   and scratched; then the idle reset wipes it.
// Outputs, in the output folder: one 2-channel WAV per stroke (ch 1 sound, ch 2 haptic; the
// stroke and 1.5 s after the pen is lifted), a PNG snapshot per stroke taken with the tip still
// down (the dent visible), the plain pictures, and visit.txt saying what each file shows and where
// the strokes were. Exits 0 when everything was written.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

namespace sas::app {

struct HeadlessOptions {
  std::string out_dir = "sketch-a-scratch-demo";
  int width_px = 1280;  // the simulated screen
  int height_px = 720;
  bool quiet = false;
  // --quick (the sanitizer build's test): shorter strokes, tails, countdown and idle timeout;
  // the same visit otherwise.
  bool quick = false;
  // demo --config: the tokens' textures ([textures]) and the staff's own textures (staff_dir) of
  // that kiosk.toml; the rest of the visit (gains, timings, cues) stays the scripted one's.
  std::string config_path;
  // When set: exactly these texture files, in token order (texture preview).
  std::vector<std::string> texture_paths;
  double stroke_s() const { return quick ? 0.5 : 1.2; }
  // Glass rings longest (a 0.34 s decay): 2 s takes a loud rub some 50 dB down, below -45 dBFS.
  double tail_s() const { return 2.0; }
};

// Adds `--out DIR` and `--quick` to a command line built on the shared parser
// (tools/command_line.h): `demo` and the bare program take them.
void AddHeadlessOptions(CLI::App& app, HeadlessOptions& options);

// Runs the visit; returns the process exit code (0 ok, 1 failure). Never throws.
int RunHeadlessDemo(const HeadlessOptions& options, std::FILE* out, std::FILE* err);

// `texture preview`: the kiosk engine holding `texture_toml` with the shipped textures beside it
// (as the kiosk holds its four), the texture chosen by its token and stroked once in each style
// (scrape, rub, roll) through the same visit as the headless default: per stroke a 2-channel WAV
// and a PNG snapshot with the tip's dent, the plain picture, and preview.txt listing them with
// each stroke's loudness. Returns 0 when everything was written, 1 on failure. Never throws.
int RunTexturePreview(const std::string& texture_toml, const std::string& out_dir, std::FILE* out,
                      std::FILE* err);

}  // namespace sas::app
