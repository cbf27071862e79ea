// Visitor-stroke benchmark: what the synth costs for the strokes visitors actually make. The four
// kiosk textures, each with its own material, height field (derived from the picture as the kiosk
// loads it) and output gains, play the seeded visitor population of the level-matching tools
// (calibration/texture_levels.h VisitorPopulation: scrape / rub / roll, 20–400 mm/s, pressure
// 0.1–0.9, any tilt in the style's range, 0.3–1.5 s, random places and directions). Each stroke is
// mapped as the kiosk maps the pen: screen fractions on the 1920 x 1080 screen -> the picture
// covering the screen (KioskEngine::ScreenToField's uniform scale and centred crop) -> a Gesture
// sampled at the tablet's 200 Hz -> GestureToCommands (force = pressure · 2 N, penetration =
// pressure · relief, width and style from the tilt). Bubble pops are not simulated (the kiosk's
// press detector is not part of the synth).
//
// Per stroke: the synth::Scene is rendered in 128-frame blocks from touch-down to lift (the
// stroke) and for kTailS after (the ring-out), timed with the thread's CPU clock, best of --reps
// runs after a warm-up. Cost = CPU time of the stroke's blocks over its duration, as a share of
// one core at 48 kHz. A second, untimed pass renders one frame at a time and reads the scene's
// probe state: the share of pen-down samples in contact (a contact force acted), whose felt
// profile is nonzero (the probe feels the texture, not just a flat pressed slide), the sub-step
// mix, and the share of the ring-out the scene spends idle (kernel skipped).
//
// Reports per texture: median, 95th percentile and worst stroke cost, the shares above, and the
// same over all strokes; exits 1 if a texture's strokes never feel its profile (the benchmark
// would not measure what visitors do). Targets: p95 <= 1 %, worst <= 2 % of one
// core. Writes docs/visitor-bench.md (--docs DIR).
//
// Usage: visitor_bench [--strokes N] [--seed S] [--reps N] [--docs DIR] [--quick] [--texture KEY]
// [--cost-only] (--texture plays one texture only and --cost-only times without counting, both
// for profiling; neither writes docs)
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "calibration/texture_levels.h"
#include "files/contact_scheme_names.h"
#include "files/kiosk_config.h"
#include "kiosk/gesture.h"
#include "kiosk/kiosk_engine.h"
#include "levels/output_gains.h"
#include "surface/image_surface.h"
#include "surface/texture_set.h"
#include "synth/scene.h"
#include "tools/builtin_profiles.h"
#include "tools/command_line.h"
#include "tools/render_command.h"

namespace {

using namespace sas;

constexpr double kFs = 48000.0;
constexpr int kBlock = 128;
// The smaller buffer the audio device may ask for: its slowest pen-down block is timed too (the
// callback's margin shrinks with the block, as the per-block work is spread over fewer frames).
constexpr int kSmallBlock = 64;
constexpr double kTailS = 0.3;
constexpr double kPenRateHz = 200.0;  // the tablet's report rate (VirtualVisit's default)
constexpr int kScreenW = 1920, kScreenH = 1080;

double CpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Texture {
  std::string name;
  surface::LoadedTexture loaded;
  synth::MaterialParams material;
  // Where its contact policy came from: contact_bench's table (meeting the error budget, or not:
  // docs/contact-budget.md) or the built-in one.
  std::string policy_source;
  synth::OutputParams output;
  double relief_m = 0.0;  // the kiosk's penetration at full pressure
};

// Screen fraction -> field millimetres: the picture covers the screen (uniform scale, centred
// crop), as KioskEngine::ScreenToField.
void ScreenToFieldMm(const surface::HeightField& field, double fx, double fy, double* x_mm,
                     double* y_mm) {
  const double sw = kScreenW, sh = kScreenH;
  const double scale = std::max(sw / field.width(), sh / field.height());
  const double crop_x = (field.width() * scale - sw) / 2.0;
  const double crop_y = (field.height() * scale - sh) / 2.0;
  const double mm = field.pitch_m() * 1e3;
  *x_mm = (fx * sw + crop_x) / scale * mm;
  *y_mm = (fy * sh + crop_y) / scale * mm;
}

std::vector<kiosk::TimedCommand> StrokeCommands(const kiosk::VisitorStroke& stroke,
                                                const surface::HeightField& field, double relief_m,
                                                long* pen_down_frames) {
  const kiosk::PenStroke& p = stroke.pen;
  kiosk::Gesture g;
  g.name = stroke.name;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  ScreenToFieldMm(field, p.x0, p.y0, &x0, &y0);
  ScreenToFieldMm(field, p.x1, p.y1, &x1, &y1);
  g.samples.push_back({0.0, x0, y0, p.pressure, p.tilt_deg});
  g.samples.push_back({p.duration_s, x1, y1, p.pressure, p.tilt_deg});
  kiosk::GestureMapping mapping;
  mapping.control_rate_hz = kPenRateHz;
  mapping.max_penetration_m = relief_m;
  mapping.style = p.style;
  auto commands = kiosk::GestureToCommands(g, mapping, kFs);
  *pen_down_frames = static_cast<long>(commands.back().frame);
  return commands;
}

// Sample counts of the instrumented pass: per stroke, summed per texture, and over all textures
// for the last row. The pen-down samples split into contact, felt and sub-step mix; the ring-out
// samples into idle or not.
struct Counts {
  long down = 0, contact = 0, felt = 0, tail = 0, idle = 0;
  std::map<int, long> mix;  // pen-down samples by sub-steps used

  void Add(const Counts& other) {
    down += other.down;
    contact += other.contact;
    felt += other.felt;
    tail += other.tail;
    idle += other.idle;
    for (const auto& [n, c] : other.mix) mix[n] += c;
  }
  static double Share(long part, long whole) {
    return static_cast<double>(part) / static_cast<double>(whole);
  }
  static double Percent(long part, long whole) {
    return 100.0 * static_cast<double>(part) / static_cast<double>(whole);
  }
};

struct StrokeResult {
  std::string style;
  double core_percent = 0.0;       // stroke (pen down)
  double tail_core_percent = 0.0;  // ring-out after the lift
  // The slowest pen-down block (each block's best over the reps) against the block's own
  // duration: the real-time margin the audio callback actually needs.
  double worst_block_percent = 0.0;
  double worst_small_block_percent = 0.0;  // the same at kSmallBlock frames
  Counts samples;
};

// Renders the commands in blocks; returns CPU seconds of the blocks before and after the lift,
// and each block's in *block_s.
// FNV-1a over the bytes of every output sample (--checksum: a speed-up that claims to leave the
// output bit for bit the same can be checked by running the benchmark before and after it).
void HashSamples(const float* samples, int count, std::uint64_t* hash) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(samples);
  for (std::size_t i = 0; i < static_cast<std::size_t>(count) * sizeof(float); ++i) {
    *hash = (*hash ^ bytes[i]) * 1099511628211ull;
  }
}

// `hash` (may be null): the rendered samples are hashed into it (outside the timed calls).
void TimedRender(synth::Scene& scene, const std::vector<kiosk::TimedCommand>& commands,
                 long pen_down, long frames, int block, std::vector<float>& out, double* down_s,
                 double* tail_s, std::vector<double>* block_s, std::uint64_t* hash = nullptr) {
  scene.Reset();
  std::size_t next = 0;
  std::vector<synth::ProbeCommand> pending;
  pending.reserve(16);
  *down_s = *tail_s = 0.0;
  block_s->clear();
  for (long start = 0; start < frames; start += block) {
    const int n = static_cast<int>(std::min<long>(block, frames - start));
    pending.clear();
    while (next < commands.size() && commands[next].frame < start + n) {
      synth::ProbeCommand c = commands[next].command;
      c.frame_offset = static_cast<std::uint32_t>(std::max<long>(0, commands[next].frame - start));
      pending.push_back(c);
      ++next;
    }
    const double t0 = CpuSeconds();
    scene.Process(pending.data(), static_cast<int>(pending.size()), out.data(), n);
    const double dt = CpuSeconds() - t0;
    if (hash != nullptr) HashSamples(out.data(), 2 * n, hash);
    (start < pen_down ? *down_s : *tail_s) += dt;
    block_s->push_back(dt);
  }
}

StrokeResult RunStroke(const Texture& tex, synth::Scene& scene, const kiosk::VisitorStroke& stroke,
                       int reps, bool stats, std::uint64_t* hash) {
  StrokeResult r;
  r.style = stroke.name;
  long pen_down = 0;
  const auto commands = StrokeCommands(stroke, *tex.loaded.field, tex.relief_m, &pen_down);
  const long frames = pen_down + static_cast<long>(kTailS * kFs);
  std::vector<float> out(2 * kBlock);
  double best_down = std::numeric_limits<double>::infinity(), best_tail = best_down;
  std::vector<double> blocks, best_blocks, best_small_blocks;
  const auto keep_best = [](const std::vector<double>& run, std::vector<double>* best) {
    if (best->empty()) *best = run;
    for (std::size_t b = 0; b < run.size(); ++b) (*best)[b] = std::min((*best)[b], run[b]);
  };
  // The slowest pen-down block of `best` (block frames each) in % of its own period.
  const auto slowest = [&](const std::vector<double>& best, int block) {
    double worst = 0.0;
    for (std::size_t b = 0; b < best.size(); ++b) {
      const long start = static_cast<long>(b) * block;
      if (start >= pen_down) break;
      const double period_s = static_cast<double>(std::min<long>(block, frames - start)) / kFs;
      worst = std::max(worst, 100.0 * best[b] / period_s);
    }
    return worst;
  };
  for (int rep = 0; rep <= reps; ++rep) {  // rep 0: warm-up
    double down = 0.0, tail = 0.0;
    TimedRender(scene, commands, pen_down, frames, kBlock, out, &down, &tail, &blocks,
                rep == 0 ? hash : nullptr);
    if (rep == 0) continue;
    best_down = std::min(best_down, down);
    best_tail = std::min(best_tail, tail);
    keep_best(blocks, &best_blocks);
    // The small blocks in the same round (the output does not depend on the block size).
    double small_down = 0.0, small_tail = 0.0;
    TimedRender(scene, commands, pen_down, frames, kSmallBlock, out, &small_down, &small_tail,
                &blocks);
    keep_best(blocks, &best_small_blocks);
  }
  r.worst_block_percent = slowest(best_blocks, kBlock);
  r.worst_small_block_percent = slowest(best_small_blocks, kSmallBlock);
  r.samples.down = pen_down;
  r.core_percent = 100.0 * best_down / (static_cast<double>(pen_down) / kFs);
  r.tail_core_percent = 100.0 * best_tail / kTailS;
  if (!stats) return r;
  // Instrumented pass, one frame at a time (the output does not depend on the block size).
  scene.Reset();
  std::size_t next = 0;
  for (long f = 0; f < frames; ++f) {
    std::size_t first = next;
    while (next < commands.size() && commands[next].frame <= f) ++next;
    std::vector<synth::ProbeCommand> now;
    for (std::size_t i = first; i < next; ++i) {
      now.push_back(commands[i].command);
      now.back().frame_offset = 0;
    }
    scene.Process(now.data(), static_cast<int>(now.size()), out.data(), 1);
    const synth::SceneProbeState st = scene.probe_state();
    if (f < pen_down) {
      if (st.touched) ++r.samples.contact;
      if (st.felt_profile_m > 0.0) ++r.samples.felt;
      ++r.samples.mix[st.active ? st.substeps : 0];
    } else {
      ++r.samples.tail;
      if (scene.skipping_idle()) ++r.samples.idle;
    }
  }
  return r;
}

// The 1, 5 and 15 minute load averages ("" where /proc is not there).
std::string LoadAverage() {
  std::ifstream in("/proc/loadavg");
  double one = 0.0, five = 0.0, fifteen = 0.0;
  if (!(in >> one >> five >> fifteen)) return "";
  char text[64];
  std::snprintf(text, sizeof text, "%.2f / %.2f / %.2f (1 / 5 / 15 min)", one, five, fifteen);
  return text;
}

std::string SubstepMix(const std::map<int, long>& mix, long total) {
  std::ostringstream s;
  bool first = true;
  for (const auto& [n, count] : mix) {
    const double share = 100.0 * static_cast<double>(count) / static_cast<double>(total);
    if (share < 0.05) continue;
    char item[48];
    std::snprintf(item, sizeof item, "%s×%d %.1f %%", first ? "" : ", ", n, share);
    s << item;
    first = false;
  }
  return s.str();
}

struct Options {
  int strokes = 200;
  unsigned seed = 2026;
  int reps = 3;
  bool quick = false;
  bool stats = true;  // --cost-only: no instrumented pass (profiling)
  bool checksum = false;  // --checksum: print a hash of each texture's output
  std::string docs = SAS_DOCS_DIR;
  std::string textures = SAS_TEXTURES_DIR;
  std::string only;  // --texture: one texture's key (its folder name), for profiling
  std::string load;  // the load average while measured (/proc/loadavg), for the page
};

// -1 when the bench should run, else the exit code (--help, a usage error).
int ParseArgs(int argc, char** argv, Options& o) {
  CLI::App app{
      "What visitors cost: the seeded visitor-stroke population on the four kiosk "
      "textures through synth::Scene.",
      "visitor_bench"};
  app.add_option("--strokes", o.strokes, "population size (default 200)")
      ->check(CLI::Range(3, 100000));
  app.add_option("--seed", o.seed, "population seed (default 2026)");
  app.add_option("--reps", o.reps, "repetitions, best taken (default 3)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--docs", o.docs, "where visitor-bench.md goes (default docs/; -: nowhere)");
  app.add_option("--textures", o.textures, "the kiosk textures (default the source tree's)");
  app.add_flag("--quick", o.quick, "at most 30 strokes, one repetition");
  app.add_option("--texture", o.only, "play this texture only (its folder name; profiling)");
  app.add_flag("--checksum", o.checksum, "print a hash of each texture's rendered output");
  bool cost_only = false;
  app.add_flag("--cost-only", cost_only, "time without counting (profiling)");
  if (const int code = sas::kiosk::ParseProgramCommandLine(app, argc, argv); code >= 0) return code;
  o.stats = !cost_only;
  if (!o.only.empty()) o.docs = "-";  // one texture is not the benchmark's page
  if (o.quick) {
    o.strokes = std::min(o.strokes, 30);
    o.reps = 1;
  }
  return -1;
}

// The four kiosk textures as the kiosk loads them: picture-derived field, material, output gains.
std::vector<Texture> LoadKioskTextures(const std::string& folder, const std::string& only) {
  const kiosk::KioskConfig config;
  const auto dirs = kiosk::MaterialSearchDirs("");
  std::vector<Texture> textures;
  for (const std::string& key : kiosk::KioskTextureNames()) {
    if (!only.empty() && key != only) continue;
    Texture t;
    t.loaded =
        surface::LoadTexture((std::filesystem::path(folder) / key / "texture.toml").string());
    t.name = t.loaded.file.name;
    const kiosk::Material material = kiosk::FindMaterial(t.loaded.file.material, dirs);
    t.material = material.params;
    t.policy_source = !material.contact_from_benchmark ? "built-in"
                      : material.contact_budget_met    ? "benchmark"
                                                       : "benchmark, budget not met";
    t.output = kiosk::KioskOutputParams(config, t.loaded.file.gains);
    t.relief_m = surface::ReliefM(*t.loaded.field);
    textures.push_back(std::move(t));
  }
  return textures;
}

struct Summary {
  std::string name, material;
  double median = 0, p95 = 0, worst = 0, tail_median = 0, worst_block = 0, worst_small_block = 0;
  std::string worst_stroke;
  double contact = 0, felt = 0, idle = 0;
  std::string mix;
  std::map<std::string, std::vector<double>> by_style;
  int oversample = 1;
  std::string scheme;  // what the scene runs: its contact scheme and sub-step policy
  bool counted = false;  // the instrumented pass ran (not --cost-only)
};

// "#index style, speed, pressure, tilt, duration": enough to replay the worst stroke by hand.
std::string DescribeStroke(std::size_t index, const std::string& style, const kiosk::PenStroke& p) {
  char what[160];
  std::snprintf(what, sizeof what, "#%zu %s, %.0f mm/s, p %.2f, tilt %.0f°, %.2f s", index,
                style.c_str(),
                std::hypot((p.x1 - p.x0) * kScreenW, (p.y1 - p.y0) * kScreenH) *
                    surface::DisplayGeometry{}.pixel_pitch_mm() / p.duration_s,
                p.pressure, p.tilt_deg, p.duration_s);
  return what;
}

// Plays the whole population on one texture; the stroke costs go to *costs, the sample counts to
// *counts.
Summary MeasureTexture(const Texture& tex, const std::vector<kiosk::VisitorStroke>& population,
                       const Options& opt, std::vector<double>* costs, Counts* counts) {
  synth::Scene scene;
  scene.Init(kFs);
  scene.Prepare(tex.material, tex.output, tex.loaded.field->View());
  Summary s;
  s.name = tex.name;
  s.material = tex.loaded.file.material;
  s.oversample = scene.contact_oversample();
  s.scheme = std::string(kiosk::ContactSchemeName(scene.contact_scheme())) +
             (scene.adaptive_oversample() ? " ×1–×" : " ×") + std::to_string(s.oversample) +
             (scene.adaptive_oversample() ? " adaptive" : "") + " (" + tex.policy_source + ")";
  std::vector<double> tails;
  double worst = -1.0;
  std::uint64_t hash = 1469598103934665603ull;
  for (std::size_t i = 0; i < population.size(); ++i) {
    const StrokeResult r = RunStroke(tex, scene, population[i], opt.reps, opt.stats, &hash);
    costs->push_back(r.core_percent);
    s.by_style[r.style].push_back(r.core_percent);
    tails.push_back(r.tail_core_percent);
    s.worst_block = std::max(s.worst_block, r.worst_block_percent);
    s.worst_small_block = std::max(s.worst_small_block, r.worst_small_block_percent);
    if (r.core_percent > worst) {
      worst = r.core_percent;
      s.worst_stroke = DescribeStroke(i, r.style, population[i].pen);
    }
    counts->Add(r.samples);
  }
  if (opt.checksum) {
    std::printf("%-16s output checksum %016llx\n", s.name.c_str(),
                static_cast<unsigned long long>(hash));
  }
  s.median = sas::kiosk::Percentile(*costs, 0.5);
  s.p95 = sas::kiosk::Percentile(*costs, 0.95);
  s.worst = worst;
  s.tail_median = sas::kiosk::Percentile(tails, 0.5);
  s.contact = counts->Share(counts->contact, counts->down);
  s.felt = counts->Share(counts->felt, counts->down);
  s.idle = counts->Share(counts->idle, counts->tail);
  s.counted = opt.stats;
  s.mix = s.counted ? SubstepMix(counts->mix, counts->down) : std::string();
  return s;
}

void PrintSummary(const Summary& s) {
  if (!s.counted) {  // --cost-only: the shares would be 0 / 0
    std::printf(
        "%-16s [%s] median %.3f %%  p95 %.3f %%  worst %.3f %% (%s)  slowest block %.2f %% "
        "(%d frames), %.2f %% (%d frames) of its period (no counts: --cost-only)\n",
        s.name.c_str(), s.scheme.c_str(), s.median, s.p95, s.worst, s.worst_stroke.c_str(),
        s.worst_block, kBlock, s.worst_small_block, kSmallBlock);
    return;
  }
  std::printf(
      "%-16s [%s] median %.3f %%  p95 %.3f %%  worst %.3f %% (%s)  contact %.1f %%  felt "
      "%.1f %%  ring-out idle %.1f %%  slowest block %.2f %% (%d frames), %.2f %% (%d frames) "
      "of its period\n",
      s.name.c_str(), s.scheme.c_str(), s.median, s.p95, s.worst, s.worst_stroke.c_str(),
      100.0 * s.contact, 100.0 * s.felt, 100.0 * s.idle, s.worst_block, kBlock,
      s.worst_small_block, kSmallBlock);
  std::printf("  sub-steps (share of pen-down samples; ×0 = probe parked): %s\n", s.mix.c_str());
  for (const auto& [style, v] : s.by_style) {
    std::printf("  %-6s median %.3f %%  p95 %.3f %%  worst %.3f %%\n", style.c_str(),
                sas::kiosk::Percentile(v, 0.5), sas::kiosk::Percentile(v, 0.95),
                *std::max_element(v.begin(), v.end()));
  }
  std::fflush(stdout);
}

// The report: how the strokes were played and measured, a row per texture, the row over all
// strokes, and the targets.
std::string VisitorMarkdown(const Options& opt, const std::vector<Summary>& summaries,
                            const std::vector<double>& all_costs, const Counts& all) {
  const double p95 = sas::kiosk::Percentile(all_costs, 0.95);
  const double worst = *std::max_element(all_costs.begin(), all_costs.end());
  const double median = sas::kiosk::Percentile(all_costs, 0.5);
  const bool p95_ok = p95 <= 1.0, worst_ok = worst <= 2.0;
  double worst_block = 0.0, worst_small_block = 0.0;
  for (const Summary& s : summaries) {
    worst_block = std::max(worst_block, s.worst_block);
    worst_small_block = std::max(worst_small_block, s.worst_small_block);
  }
  const bool small_block_ok = worst_small_block <= 10.0;

  std::ostringstream md;
  char line[640];
  md << "# Synth cost over visitor strokes\n\n"
        "Written by `visitor_bench"
     << (opt.quick ? " --quick" : "") << "` (tests/bench/visitor_bench.cpp); do not edit. "
     << opt.strokes << " strokes from seed " << opt.seed
     << " (calibration/texture_levels.h VisitorPopulation, the population of `population_levels`: "
        "scrape / rub / roll, 20–400 mm/s, pressure 0.1–0.9, 0.3–1.5 s, random places and "
        "directions), each played on each kiosk texture (its picture-derived height field, its "
        "material, the kiosk's output gains) with the kiosk's pen mapping at 200 Hz, 48 kHz, "
        "128-frame blocks. Cost: thread CPU time of the pen-down span (best of "
     << opt.reps
     << " after a warm-up) over its duration, in % of one core of the build machine. Contact: "
        "pen-down samples where a contact force acted. Felt: pen-down samples where the felt "
        "profile (penetration threshold applied, micro-roughness excluded) is nonzero — the probe "
        "feels the texture. Sub-steps: share of pen-down samples by contact sub-steps per sample "
        "(×0: the probe parked). Scheme: the contact scheme the scene runs and its sub-steps per "
        "sample (adaptive: chosen per compression), and where it comes from (benchmark: "
        "contact_bench's table, docs/contact-budget.md). Slowest block: the pen-down 128-frame block "
        "with the most CPU time (each block's best over the repetitions), in % of that block's "
        "2.67 ms; 64 frames: the same with the stroke rendered in 64-frame blocks (1.33 ms), "
        "timed in the same rounds; the audio callback must stay under 100 %. Ring-out: the "
     << kTailS
     << " s after the lift; its idle share is the samples the scene skipped as silent. Bubble "
        "pops are not simulated."
     << (opt.load.empty() ? "" : " Load average of the machine while measured: " + opt.load + ".")
     << "\n\n"
        "| texture (material) | scheme | median % | p95 % | worst % (stroke) | slowest block % "
        "| slowest 64-frame block % | contact | felt | sub-steps | ring-out median % | ring-out "
        "idle |\n"
        "|---|---|---:|---:|---|---:|---:|---:|---:|---|---:|---:|\n";
  for (const Summary& s : summaries) {
    std::snprintf(
        line, sizeof line,
        "| %s (%s) | %s | %.3f | %.3f | %.3f (%s) | %.2f | %.2f | %.1f %% | %.1f %% | %s | %.3f "
        "| %.1f %% |\n",
        s.name.c_str(), s.material.c_str(), s.scheme.c_str(), s.median, s.p95, s.worst,
        s.worst_stroke.c_str(), s.worst_block, s.worst_small_block, 100.0 * s.contact,
        100.0 * s.felt, s.mix.c_str(), s.tail_median, 100.0 * s.idle);
    md << line;
  }
  std::snprintf(line, sizeof line,
                "| all | | %.3f | %.3f | %.3f | %.2f | %.2f | %.1f %% | %.1f %% | %s | | %.1f %% "
                "|\n\n"
                "Targets: 95th-percentile stroke ≤ 1 %% of one core: **%s** (%.3f %%); worst "
                "≤ 2 %%: **%s** (%.3f %%); slowest pen-down 64-frame block ≤ 10 %% of its "
                "period: **%s** (%.2f %%).\n",
                median, p95, worst, worst_block, worst_small_block,
                all.Percent(all.contact, all.down), all.Percent(all.felt, all.down),
                SubstepMix(all.mix, all.down).c_str(), all.Percent(all.idle, all.tail),
                p95_ok ? "holds" : "does not hold", p95, worst_ok ? "holds" : "does not hold",
                worst, small_block_ok ? "holds" : "does not hold", worst_small_block);
  md << line;
  return md.str();
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  if (const int code = ParseArgs(argc, argv, opt); code >= 0) return code;
  const auto population = kiosk::VisitorPopulation(opt.strokes, opt.seed);
  const std::string load_before = LoadAverage();
  const std::vector<Texture> textures = LoadKioskTextures(opt.textures, opt.only);
  if (textures.empty()) {
    std::fprintf(stderr, "no kiosk texture %s\n", opt.only.c_str());
    return 2;
  }
  std::vector<Summary> summaries;
  std::vector<double> all_costs;
  Counts all;
  bool unfelt = false;
  for (const Texture& tex : textures) {
    std::vector<double> costs;
    Counts counts;
    summaries.push_back(MeasureTexture(tex, population, opt, &costs, &counts));
    PrintSummary(summaries.back());
    all_costs.insert(all_costs.end(), costs.begin(), costs.end());
    all.Add(counts);
    if (counts.felt == 0) unfelt = true;
  }
  if (!opt.stats) return 0;  // the page's shares need the counts
  // CPU time on a shared machine is inflated by the others' work (caches, SMT siblings): the page
  // says how busy the machine was.
  if (!load_before.empty()) opt.load = load_before + " at the start, " + LoadAverage() + " at the end";
  const std::string md = VisitorMarkdown(opt, summaries, all_costs, all);
  std::printf("%s", md.c_str());
  if (opt.docs != "-") {
    std::filesystem::create_directories(opt.docs);
    const auto path = std::filesystem::path(opt.docs) / "visitor-bench.md";
    std::ofstream(path) << md;
    std::printf("wrote %s\n", path.c_str());
  }
  if (unfelt) {
    std::fprintf(stderr, "a texture's strokes never felt its profile: not a visitor benchmark\n");
    return 1;
  }
  return 0;
}
