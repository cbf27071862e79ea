#pragma once
// The offline renderer behind `sketch-a-scratch render`, a 2-channel WAV (ch 1 sound, ch 2 haptic)
// plus a one-line summary, in two ways:
// - What the kiosk plays: `--texture NAME|FOLDER|texture.toml` or `--voice take.wav` runs the
//   kiosk engine itself on its virtual clock (kiosk/virtual_visit.h), started on that texture (or,
//   for a voice, after the take went through the record button, the recorder and the voice
//   surface): the picture's relief, the bubble state and its pops, the texture's material and
//   gains, the configuration's gains (--config, else the defaults), the per-stroke level matching
//   and the final safety stage. The gesture's millimetres are on the texture's field and become
//   pen reports on the kiosk's 1920 x 1080 screen at a tablet's 200 Hz. No spoken cues.
// - A material on a test surface: `--profile` (a built-in profile or a picture), or a texture's
//   generator height map with `--texture NAME --true-height`, through a bare synth::Scene, block
//   by block with commands placed on their exact frames, at 0 dB gains and without the safety
//   stage.
//
//   sketch-a-scratch render (--texture NAME [--true-height] | --voice FILE | --profile P
//                           [--material M]) [--gesture G] --out out.wav [--fs 48000] [--tail-s 2]
//                           [--config kiosk.toml] [--materials-dir DIR] [--format float|pcm24]
//                           [--style auto|scrape|rub|roll] [--gain-db 0] [--haptic-gain-db 0]
//                           [--normalize] [--sweep-mps V]
//
// Materials are looked up by name in, in order: --materials-dir, $SAS_DATA_DIR/materials, the
// source tree's textures/materials, <install prefix>/share/sketch-a-scratch/materials; the first
// directory holding <name>.toml wins. Every problem is a RenderError (or one of the loaders'
// errors) with a message naming the file and, for data files, line and key.

#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "files/material_file.h"
#include "surface/wav_writer.h"
#include "synth/probe_command.h"

namespace sas::kiosk {

class RenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RenderOptions {
  std::string material;             // empty: the texture's material (--true-height), else "wood"
  std::string profile = "grating";  // built-in name or picture file
  // A kiosk texture (name, folder holding texture.toml, or the file): played by the kiosk engine,
  // or with true_height its generator height map through a bare scene.
  std::string texture;
  bool true_height = false;
  std::string voice_path;   // a recording (WAV, FLAC, OGG) made the voice surface by the kiosk
  std::string config_path;  // kiosk.toml for the kiosk engine's gains; empty: the defaults
  std::string gesture = "slow stroke";  // built-in name or CSV file
  // The passive mode at a set velocity (m/s): with gesture "passive sweep", replaces its 5 cm/s.
  std::optional<double> sweep_mps;
  std::string out_path;       // required
  std::string materials_dir;  // optional, searched first
  int sample_rate_hz = 48000;
  double tail_s = 2.0;  // rendered after the pen is lifted
  surface::WavFormat format = surface::WavFormat::kFloat32;
  std::optional<synth::ProbeStyle> style;  // empty: by probe width (pen tilt)
  double sound_gain_db = 0.0;
  double haptic_gain_db = 0.0;
  // Scale each channel after rendering so its peak is at -1 dBFS (for listening to quiet
  // renders; the synth's own scale is 1 m/s pickup velocity = full scale).
  bool normalize = false;
  int block_frames = 256;  // the bare scene's block size (output does not depend on it)
  bool verbose = false;    // also print the contact scheme and sub-steps the material runs

  // Whether the kiosk engine plays the render (texture without true_height, or a voice).
  bool ThroughKiosk() const { return !voice_path.empty() || (!texture.empty() && !true_height); }
};

struct ChannelStats {
  double peak = 0.0;  // max |sample|
  double rms = 0.0;
};

struct RenderSummary {
  std::string material_file;
  // The contact scheme and sub-step policy the material runs (files/contact_choice.h).
  std::string contact_policy;
  double duration_s = 0.0;
  double gesture_s = 0.0;
  ChannelStats channels[2];
  double normalize_gain[2] = {1.0, 1.0};  // applied by --normalize (linear)
  double tail_end_peak = 0.0;             // max |sample| over both channels in the last 100 ms
  double compute_s = 0.0;                 // wall time spent in Scene::Process
  double realtime_factor = 0.0;           // compute_s / duration_s (< 1: faster than real time)
  // Through the kiosk on bubble wrap: the bubbles the gesture popped (the kiosk's bubble state).
  int popped_bubbles = 0;
  std::vector<std::string> warnings;
};

// Renders and writes options.out_path. Throws on any problem (nothing is written then).
RenderSummary Render(const RenderOptions& options);
// Renders into `audio` (2 interleaved channels: sound, haptic) without writing anything;
// options.out_path is ignored. Throws on any problem.
RenderSummary RenderToMemory(const RenderOptions& options, std::vector<float>& audio);
// "out.wav: 4.10 s, wood on grating, slow stroke | ch1 peak -6.0 dBFS rms -21.3 dBFS | ch2 ..."
std::string FormatSummary(const RenderOptions& options, const RenderSummary& summary);

// Parses `args` (everything after "render") with the shared parser (command_line.h). Throws
// RenderError naming the option on bad args.
RenderOptions ParseRenderArgs(const std::vector<std::string>& args);
// The whole subcommand: parse, render, print the summary to `out`, errors to `err`. Returns the
// process exit code (0 ok, 1 render failed, 2 bad command line). Never throws.
int RunRenderCommand(const std::vector<std::string>& args, std::FILE* out, std::FILE* err);

}  // namespace sas::kiosk
