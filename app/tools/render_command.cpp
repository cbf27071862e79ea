// `sketch-a-scratch render`: material + profile + gesture -> synth::Scene -> 2-channel WAV
// (see render_command.h for the command line and the material search order).
#include "tools/render_command.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>

#include "files/contact_choice.h"
#include "files/kiosk_config.h"
#include "kiosk/data_dirs.h"
#include "kiosk/device_configs.h"
#include "kiosk/gesture.h"
#include "kiosk/kiosk_engine.h"
#include "kiosk/virtual_visit.h"
#include "platform/audio/audio_input.h"
#include "sas/version.h"
#include "surface/audio_file.h"
#include "synth/scene.h"
#include "tools/builtin_profiles.h"
#include "tools/command_line.h"

namespace sas::kiosk {
namespace {

namespace fs = std::filesystem;

constexpr double kMaxRenderS = 600.0;
constexpr float kNormalizePeak = 0.891250938f;  // -1 dBFS

double Db(double linear) {
  return linear > 0.0 ? 20.0 * std::log10(linear) : -999.0;
}

std::string FormatDb(double linear) {
  char text[32];
  if (linear <= 0.0) return "-inf dBFS";
  std::snprintf(text, sizeof text, "%.1f dBFS", Db(linear));
  return text;
}

std::string Join(const std::vector<std::string>& items, const char* separator) {
  std::string joined;
  for (const auto& item : items) joined += (joined.empty() ? "" : separator) + item;
  return joined;
}

bool IsPassiveSweep(const std::string& name) {
  const auto builtin = FindBuiltinGesture(name);
  return builtin && builtin->name == "passive sweep";
}

Gesture LoadGesture(const std::string& name_or_path) {
  if (auto builtin = FindBuiltinGesture(name_or_path)) return *builtin;
  std::error_code error;
  if (!fs::exists(name_or_path, error)) {
    throw RenderError("gesture \"" + name_or_path + "\" is neither a built-in (" +
                      Join(BuiltinGestureNames(), ", ") + ") nor an existing CSV file");
  }
  return LoadGestureCsv(name_or_path);
}

bool IsKioskTextureName(const std::string& name) {
  const auto names = KioskTextureNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

// --profile: a built-in or a picture. A texture there would be its generator's height map, which
// is not what the kiosk plays, so it is only had by asking for it (--texture ... --true-height).
std::string ProfilePath(const std::string& name_or_path) {
  if (MakeBuiltinProfile(name_or_path)) return name_or_path;
  std::error_code error;
  const bool exists = fs::exists(name_or_path, error);
  if ((exists && fs::path(name_or_path).extension() == ".toml") ||
      (!exists && IsKioskTextureName(name_or_path))) {
    throw RenderError("\"" + name_or_path + "\" is a kiosk texture: --texture " + name_or_path +
                      " plays what the kiosk plays (the picture's relief, its gains and safety "
                      "stage); --texture " +
                      name_or_path + " --true-height plays its generator's height map");
  }
  return name_or_path;
}

// --texture: a folder holding texture.toml (a curator's own texture), the file itself, or a kiosk
// texture by the name the help offers (a path in the working folder wins over a name).
std::string TexturePath(const std::string& name_or_path) {
  std::error_code error;
  if (fs::is_directory(name_or_path, error)) {
    const fs::path file = fs::path(name_or_path) / "texture.toml";
    if (!fs::is_regular_file(file, error)) {
      throw RenderError("texture folder " + name_or_path + " holds no texture.toml");
    }
    return file.string();
  }
  if (fs::is_regular_file(name_or_path, error)) return name_or_path;
  if (!IsKioskTextureName(name_or_path)) {
    throw RenderError("texture \"" + name_or_path + "\" is neither a kiosk texture (" +
                      Join(KioskTextureNames(), ", ") +
                      ") nor a folder holding texture.toml nor a texture file");
  }
  const std::string file = FindTextureFile(name_or_path);
  if (file.empty()) {
    throw RenderError("kiosk texture \"" + name_or_path +
                      "\" not found in the data folders ($SAS_DATA_DIR/textures, the source tree, "
                      "the installed share/sketch-a-scratch/textures)");
  }
  return file;
}

}  // namespace

namespace {

// The render command line on the shared parser; `sweep_mps` is copied into options after parsing
// (CLI11 fills plain values, the option is optional).
struct RenderCli {
  CLI::App app{
      "Renders a material, a surface and a gesture through the kiosk's synth to a "
      "2-channel WAV (ch 1 sound, ch 2 haptic).",
      "render"};
  double sweep_mps = 0.05;
  std::string format = "float";
  std::string style = "auto";

  explicit RenderCli(RenderOptions& options) {
    app.add_option("--material", options.material,
                   "material file NAME.toml (default: the texture's, else wood)");
    app.add_option("--texture", options.texture,
                   "what the kiosk plays on a texture: a kiosk texture by name (" +
                       Join(KioskTextureNames(), ", ") +
                       "), a folder holding texture.toml, or the file (the kiosk engine: the "
                       "picture's relief, bubbles, material, gains and safety stage; no cues)");
    app.add_flag("--true-height", options.true_height,
                 "with --texture: its generator's height map through a bare scene instead");
    app.add_option("--voice", options.voice_path,
                   "what the kiosk plays on a voice: a recording (WAV, FLAC, OGG) goes through "
                   "the record button and becomes the voice surface");
    app.add_option("--config", options.config_path,
                   "with --texture or --voice: the kiosk configuration whose gains apply "
                   "(default: the built-in defaults, as shipped)");
    app.add_option("--profile", options.profile,
                   "a material on a test surface: built-in profile (" +
                       Join(BuiltinProfileNames(), ", ") +
                       ") or a picture (gray-level changes -> ridges); default grating");
    app.add_option("--gesture", options.gesture,
                   "built-in gesture (" + Join(BuiltinGestureNames(), ", ") +
                       ") or a CSV file t,x,y,pressure,tilt (s, mm, mm, 0..1, degrees); default "
                       "\"slow stroke\"");
    AddNumberOption(app, "--sweep-mps", sweep_mps, 0.001, 2.0,
                    "speed of the \"passive sweep\" gesture, m/s (default 0.05)");
    app.add_option("--out", options.out_path, "2-channel WAV: ch 1 sound, ch 2 haptic")->required();
    app.add_option("--fs", options.sample_rate_hz, "sample rate, Hz (default 48000)")
        ->check(CLI::Range(8000, 192000));
    AddNumberOption(app, "--tail-s", options.tail_s, 0.0, 600.0,
                    "seconds rendered after the pen is lifted (default 2)");
    app.add_option("--materials-dir", options.materials_dir,
                   "searched before $SAS_DATA_DIR/materials, the source tree and the installed "
                   "share/sketch-a-scratch/materials");
    app.add_option("--format", format, "WAV sample format (default float)")
        ->check(CLI::IsMember({"float", "pcm24"}));
    app.add_option("--style", style, "probe style (default auto: from the pen's tilt)")
        ->check(CLI::IsMember({"auto", "scrape", "rub", "roll"}));
    AddNumberOption(app, "--gain-db", options.sound_gain_db, -120.0, 60.0,
                    "sound output gain, dB (default 0)");
    AddNumberOption(app, "--haptic-gain-db", options.haptic_gain_db, -120.0, 60.0,
                    "haptic output gain, dB (default 0)");
    app.add_flag("--normalize", options.normalize,
                 "scale each channel to a -1 dBFS peak after rendering");
    app.add_flag("--verbose", options.verbose,
                 "also print the contact scheme and sub-steps the material runs (chosen by "
                 "contact_bench from the error budget, docs/contact-budget.md)");
  }

  // After a successful parse: the choices CLI11 checked, and the cross-option rule.
  void Finish(RenderOptions& options) const {
    const auto given = [&](const char* name) { return app.count(name) > 0; };
    if (given("--texture") + given("--voice") + given("--profile") > 1) {
      throw RenderError("--texture, --voice and --profile each name the surface: give one");
    }
    if (options.true_height && !given("--texture")) {
      throw RenderError("--true-height goes with --texture");
    }
    if (options.ThroughKiosk() && given("--material")) {
      throw RenderError(
          "the kiosk plays a texture's own material and the voice's: --material "
          "goes with --profile or --texture ... --true-height");
    }
    if (!options.ThroughKiosk() && given("--config")) {
      throw RenderError("--config goes with --texture or --voice (the kiosk's gains)");
    }
    options.format = format == "pcm24" ? surface::WavFormat::kPcm24 : surface::WavFormat::kFloat32;
    options.style = synth::ParseProbeStyle(style);  // "auto": none
    if (app.count("--sweep-mps") > 0) {
      if (!IsPassiveSweep(options.gesture)) {
        throw RenderError("--sweep-mps applies to --gesture \"passive sweep\" only");
      }
      options.sweep_mps = sweep_mps;
    }
  }
};

}  // namespace

RenderOptions ParseRenderArgs(const std::vector<std::string>& args) {
  RenderOptions options;
  RenderCli cli(options);
  try {
    cli.app.parse(std::vector<std::string>(args.rbegin(), args.rend()));
  } catch (const CLI::ParseError& error) {
    throw RenderError(error.what());
  }
  cli.Finish(options);
  return options;
}

namespace {

// A material on a test surface through a bare scene (render_command.h); fills `audio` with
// `total_frames` frames.
void RenderBareScene(const RenderOptions& options, const Gesture& gesture,
                     std::int64_t total_frames, std::vector<float>& audio, RenderSummary& summary) {
  if (options.block_frames < 1) throw RenderError("block size must be positive");
  std::string material_name = options.material;
  const std::string profile =
      options.true_height ? TexturePath(options.texture) : ProfilePath(options.profile);
  if (material_name.empty()) material_name = ProfileMaterial(profile);
  if (material_name.empty()) material_name = "wood";
  const Material material = FindMaterial(material_name, MaterialSearchDirs(options.materials_dir));
  summary.material_file = material.name;
  summary.contact_policy = ContactPolicyText(material.params, material.contact_from_benchmark,
                                               material.contact_budget_met);
  const surface::HeightField field = LoadProfile(profile);
  const double fs_hz = options.sample_rate_hz;

  GestureMapping mapping;
  mapping.style = options.style;
  // Full pressure feels the whole relief of this surface, light pressure only its peaks.
  mapping.max_penetration_m = surface::ReliefM(field);
  const std::vector<TimedCommand> commands = GestureToCommands(gesture, mapping, fs_hz);

  // A gesture leaving the surface is not an error (the synth clamps to the edge) but worth saying.
  double max_x_mm = 0.0;
  double max_y_mm = 0.0;
  for (const auto& row : gesture.samples) {
    max_x_mm = std::max(max_x_mm, row.x_mm);
    max_y_mm = std::max(max_y_mm, row.y_mm);
  }
  const double width_mm = field.width() * field.pitch_m() * 1e3;
  const double height_mm = field.height() * field.pitch_m() * 1e3;
  if (max_x_mm > width_mm || max_y_mm > height_mm) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "the gesture reaches (%.1f, %.1f) mm but the profile is %.1f x %.1f mm", max_x_mm,
                  max_y_mm, width_mm, height_mm);
    summary.warnings.emplace_back(text);
  }

  synth::OutputParams output;
  output.sound_gain = std::pow(10.0, options.sound_gain_db / 20.0);
  output.haptic_gain = std::pow(10.0, options.haptic_gain_db / 20.0);

  synth::Scene scene;
  scene.Init(fs_hz);
  scene.Prepare(material.params, output, field.View());
  scene.Reset();

  audio.assign(static_cast<std::size_t>(total_frames) * 2, 0.0f);
  std::vector<synth::ProbeCommand> block_commands;
  block_commands.reserve(commands.size());
  std::size_t next_command = 0;
  const auto start = std::chrono::steady_clock::now();
  for (std::int64_t block_start = 0; block_start < total_frames;
       block_start += options.block_frames) {
    const auto frames =
        static_cast<int>(std::min<std::int64_t>(options.block_frames, total_frames - block_start));
    block_commands.clear();
    while (next_command < commands.size() && commands[next_command].frame < block_start + frames) {
      synth::ProbeCommand command = commands[next_command].command;
      command.frame_offset = static_cast<std::uint32_t>(
          std::max<std::int64_t>(0, commands[next_command].frame - block_start));
      block_commands.push_back(command);
      ++next_command;
    }
    scene.Process(block_commands.data(), static_cast<int>(block_commands.size()),
                  audio.data() + block_start * 2, frames);
  }
  summary.compute_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The visitor records `path` as the kiosk takes a voice: the record button, the countdown, the
// take into the microphone, the button again, and the voice surface shown once its cross-fade
// has run. Waits are for the engine's events on its virtual clock, bounded by `limit_s`.
void RecordVoice(const std::string& path, double cross_fade_s, KioskEngine& engine,
                 VirtualVisit& visit, platform::FakeAudioInput& microphone,
                 RenderSummary& summary) {
  const KioskConfig& config = engine.config();
  surface::AudioReadLimits limits;
  limits.target_rate_hz = config.sample_rate_hz;
  const surface::AudioClip clip = surface::ReadAudioFile(path, limits);
  if (clip.silent) {
    throw RenderError(path + " is silent: the kiosk would ask the visitor to record again");
  }
  if (clip.duration_s() > config.record_max_duration_s) {
    char text[160];
    std::snprintf(text, sizeof text, "%s lasts %.1f s; the kiosk keeps its first %.1f s",
                  path.c_str(), clip.duration_s(), config.record_max_duration_s);
    summary.warnings.emplace_back(text);
  }
  engine.SetRecorder(&microphone.recorder());
  microphone.Start();
  visit.SetMicrophone(&microphone);
  visit.SetVoice(clip.samples);
  const double limit_s = visit.now_s() + 60.0 + clip.duration_s();
  const auto press = [&] {
    engine.OnRecordButton(visit.now_ns(), true);
    visit.Advance(0.05);
    engine.OnRecordButton(visit.now_ns(), false);
  };
  const auto mode = [&] { return engine.session().mode(); };
  press();
  while (mode() != SessionMode::kRecording && visit.now_s() < limit_s) visit.Advance(0.01);
  while (mode() == SessionMode::kRecording && visit.voice_left() > 0 && visit.now_s() < limit_s) {
    visit.Advance(0.01);
  }
  if (mode() == SessionMode::kRecording) press();  // the take ended before the kiosk's limit
  while (!(engine.has_voice() && engine.surface().voice) && visit.now_s() < limit_s) {
    visit.Advance(0.01);
  }
  if (!engine.has_voice() || !engine.surface().voice) {
    throw RenderError(path +
                      ": the kiosk made no voice surface of it (too quiet or clipped: it "
                      "asks the visitor to record again)");
  }
  visit.Advance(cross_fade_s + 0.1);
}

// What the kiosk plays (render_command.h): its engine on the virtual clock, fed pen reports made
// from the gesture. Fills `audio` with `total_frames` frames from the gesture's start.
void RenderThroughKiosk(const RenderOptions& options, const Gesture& gesture,
                        std::int64_t total_frames, std::vector<float>& audio,
                        RenderSummary& summary) {
  KioskEngineOptions engine_options;
  if (!options.config_path.empty()) engine_options.config = LoadKioskConfig(options.config_path);
  KioskConfig& config = engine_options.config;
  config.sample_rate_hz = options.sample_rate_hz;
  config.sound_gain_db += options.sound_gain_db;
  config.haptic_gain_db += options.haptic_gain_db;
  engine_options.materials_dir = options.materials_dir;
  engine_options.spoken_cues = false;
  engine_options.virtual_clock = true;
  // The kiosk's own set: the per-stroke level matching takes its reference from every loaded
  // texture (levels/stroke_gain.h), so one texture alone would play at other gains. A texture of
  // another folder stands in for the kiosk's texture of the same name, or joins the set.
  engine_options.texture_paths = FindTextureFiles();
  auto key = [](const std::string& file) {
    return fs::path(file).parent_path().filename().string();
  };
  if (!options.texture.empty()) {
    const std::string texture_file = TexturePath(options.texture);
    auto& paths = engine_options.texture_paths;
    const auto same = std::find_if(paths.begin(), paths.end(), [&](const std::string& path) {
      return key(path) == key(texture_file);
    });
    if (same != paths.end()) {
      *same = texture_file;
    } else {
      paths.push_back(texture_file);
    }
    config.default_texture = key(texture_file);
  }  // a voice: the kiosk stands on its default texture until the take becomes a surface
  KioskEngine engine(engine_options);
  if (!engine.texture_failures().empty()) throw RenderError(engine.texture_failures().front());
  VirtualVisit visit(engine);
  platform::FakeAudioInput microphone(RecorderConfigFor(config));
  if (!options.voice_path.empty()) {
    RecordVoice(options.voice_path, engine_options.cross_fade_s, engine, visit, microphone,
                summary);
    summary.material_file = kVoiceMaterial;
  } else {
    const auto& material =
        engine.textures()[static_cast<std::size_t>(engine.default_texture())].material;
    summary.material_file = material.name;
    summary.contact_policy = ContactPolicyText(material.params, material.contact_from_benchmark,
                                               material.contact_budget_met);
  }

  // A gesture off the screen is not an error (the kiosk clamps the pen to the picture) but worth
  // saying, with the part of the field the screen shows.
  const double pitch_mm = engine.current_field()->pitch_m() * 1e3;
  const double width_px = engine_options.screen_width_px;
  const double height_px = engine_options.screen_height_px;
  for (const auto& row : gesture.samples) {
    double x_px = 0.0, y_px = 0.0;
    engine.FieldToScreen(row.x_mm / pitch_mm, row.y_mm / pitch_mm, &x_px, &y_px);
    if (x_px >= 0.0 && x_px <= width_px && y_px >= 0.0 && y_px <= height_px) continue;
    double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
    engine.ScreenToField(0.0, 0.0, &x0, &y0);
    engine.ScreenToField(width_px, height_px, &x1, &y1);
    char text[200];
    std::snprintf(text, sizeof text,
                  "the gesture reaches (%.1f, %.1f) mm; the screen shows x %.1f..%.1f mm, "
                  "y %.1f..%.1f mm of this surface",
                  row.x_mm, row.y_mm, x0 * pitch_mm, x1 * pitch_mm, y0 * pitch_mm, y1 * pitch_mm);
    summary.warnings.emplace_back(text);
    break;
  }

  visit.ClearOutput();
  const auto start = std::chrono::steady_clock::now();
  visit.Advance(static_cast<double>(total_frames) / visit.sample_rate_hz(),
                GesturePenScript(gesture, engine, visit.now_s(), options.style));
  summary.compute_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  summary.popped_bubbles = engine.surface().voice ? 0 : engine.popped_bubbles();
  audio.assign(visit.output().begin(),
               visit.output().begin() + static_cast<std::ptrdiff_t>(total_frames) * 2);
}

}  // namespace

RenderSummary RenderToMemory(const RenderOptions& options, std::vector<float>& audio) {
  RenderSummary summary;
  // The passive mode: 70 mm along x at the set velocity with a steady push (gesture.h).
  const Gesture gesture = options.sweep_mps && IsPassiveSweep(options.gesture)
                              ? PassiveSweep(*options.sweep_mps, 70.0, 0.4)
                              : LoadGesture(options.gesture);
  const double fs_hz = options.sample_rate_hz;
  summary.gesture_s = gesture.duration_s();
  // Everything is rendered to memory before the WAV is written: keep that bounded.
  if (summary.gesture_s + options.tail_s > kMaxRenderS) {
    throw RenderError("gesture plus tail is " + std::to_string(summary.gesture_s + options.tail_s) +
                      " s; the renderer stops at " + std::to_string(kMaxRenderS) + " s");
  }
  const auto total_frames =
      static_cast<std::int64_t>(std::ceil((summary.gesture_s + options.tail_s) * fs_hz));
  if (options.ThroughKiosk()) {
    RenderThroughKiosk(options, gesture, total_frames, audio, summary);
  } else {
    RenderBareScene(options, gesture, total_frames, audio, summary);
  }
  summary.duration_s = static_cast<double>(total_frames) / fs_hz;
  summary.realtime_factor = summary.duration_s > 0.0 ? summary.compute_s / summary.duration_s : 0.0;

  if (options.normalize) {
    for (int channel = 0; channel < 2; ++channel) {
      float peak = 0.0f;
      for (std::int64_t i = 0; i < total_frames; ++i) {
        peak = std::max(peak, std::abs(audio[static_cast<std::size_t>(i * 2 + channel)]));
      }
      if (peak <= 0.0f) continue;  // a silent channel stays silent
      const float gain = kNormalizePeak / peak;
      for (std::int64_t i = 0; i < total_frames; ++i) {
        audio[static_cast<std::size_t>(i * 2 + channel)] *= gain;
      }
      summary.normalize_gain[channel] = gain;
    }
  }

  for (int channel = 0; channel < 2; ++channel) {
    double peak = 0.0;
    double sum_squares = 0.0;
    for (std::int64_t i = 0; i < total_frames; ++i) {
      const double sample = audio[static_cast<std::size_t>(i * 2 + channel)];
      peak = std::max(peak, std::abs(sample));
      sum_squares += sample * sample;
    }
    summary.channels[channel].peak = peak;
    summary.channels[channel].rms =
        total_frames > 0 ? std::sqrt(sum_squares / static_cast<double>(total_frames)) : 0.0;
  }
  const auto tail_frames = std::min<std::int64_t>(total_frames, std::llround(0.1 * fs_hz));
  for (std::int64_t i = (total_frames - tail_frames) * 2; i < total_frames * 2; ++i) {
    summary.tail_end_peak = std::max(
        summary.tail_end_peak, static_cast<double>(std::abs(audio[static_cast<std::size_t>(i)])));
  }

  return summary;
}

RenderSummary Render(const RenderOptions& options) {
  if (options.out_path.empty()) throw RenderError("no output file given");
  std::vector<float> audio;
  const RenderSummary summary = RenderToMemory(options, audio);
  surface::WriteWav(options.out_path, audio.data(), audio.size() / 2, 2, options.sample_rate_hz,
                    options.format);
  return summary;
}

namespace {

std::string SurfaceLabel(const RenderOptions& options) {
  if (!options.voice_path.empty()) return "the voice of " + options.voice_path;
  if (options.texture.empty()) return options.profile;
  return options.texture + (options.true_height ? " (its true height map)" : "");
}

}  // namespace

std::string FormatSummary(const RenderOptions& options, const RenderSummary& summary) {
  char normalized[96] = "";
  if (options.normalize) {
    std::snprintf(normalized, sizeof normalized, " | normalized %+.1f dB / %+.1f dB",
                  Db(summary.normalize_gain[0]), Db(summary.normalize_gain[1]));
  }
  char popped[48] = "";
  if (summary.popped_bubbles > 0) {
    std::snprintf(popped, sizeof popped, ", %d bubbles popped", summary.popped_bubbles);
  }
  char text[700];
  std::snprintf(
      text, sizeof text,
      "%s: %.2f s (gesture %.2f s) at %d Hz, %s on %s, %s%s | sound peak %s rms %s | "
      "haptic peak %s rms %s | last 100 ms %s%s | real-time factor %.4f",
      options.out_path.c_str(), summary.duration_s, summary.gesture_s, options.sample_rate_hz,
      summary.material_file.c_str(), SurfaceLabel(options).c_str(), options.gesture.c_str(), popped,
      FormatDb(summary.channels[0].peak).c_str(), FormatDb(summary.channels[0].rms).c_str(),
      FormatDb(summary.channels[1].peak).c_str(), FormatDb(summary.channels[1].rms).c_str(),
      FormatDb(summary.tail_end_peak).c_str(), normalized, summary.realtime_factor);
  return text;
}

int RunRenderCommand(const std::vector<std::string>& args, std::FILE* out, std::FILE* err) {
  RenderOptions options;
  RenderCli cli(options);
  if (const int code = ParseCommandLine(cli.app, args, out, err); code >= 0) return code;
  try {
    cli.Finish(options);
  } catch (const RenderError& error) {
    std::fprintf(
        err, "sketch-a-scratch render: %s\n(sketch-a-scratch render --help lists the options)\n",
        error.what());
    return kExitUsage;
  }
  try {
    const RenderSummary summary = Render(options);
    for (const auto& warning : summary.warnings) {
      std::fprintf(err, "sketch-a-scratch render: warning: %s\n", warning.c_str());
    }
    std::fprintf(out, "%s\n", FormatSummary(options, summary).c_str());
    if (options.verbose && !summary.contact_policy.empty()) {
      std::fprintf(out, "contact: %s: %s\n", summary.material_file.c_str(),
                   summary.contact_policy.c_str());
    }
    return kExitOk;
  } catch (const std::exception& error) {
    std::fprintf(err, "sketch-a-scratch render: error: %s\n", error.what());
    return kExitRuntimeError;
  }
}

}  // namespace sas::kiosk
