// The kiosk engine (see kiosk_engine.h): textures, scenes, session, voice slot and counters, the
// pen -> ProbeCommand mapping and the audio callback's render.
#include "kiosk/kiosk_engine.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <stdexcept>

#include "kiosk/atomic_file.h"
#include "kiosk/builtin_profiles.h"
#include "kiosk/counters_file.h"
#include "kiosk/output_gains.h"
#include "kiosk/pen_mapping.h"
#include "kiosk/render_command.h"
#include "platform/common/clock.h"
#include "platform/common/no_dump_buffer.h"
#include "platform/log/log.h"
#include "sas/version.h"
#include "surface/audio_file.h"
#include "surface/cue_library.h"
#include "surface/image_surface.h"
#include "surface/sound_image.h"

namespace sas::kiosk {
namespace {

namespace fs = std::filesystem;

// Token order: the paper's §5.2 order of the four textures.
const std::vector<std::string> kTextureKeys = {"bubble_wrap", "broken_glass", "wooden_board",
                                               "cracked_ground"};
// Impulse of a bubble's pop at strength 1 (N·s): a few tenths of a metre per second given to the
// probe, well above a tap's landing speed, so a pop stands out from the rubbing around it.
constexpr double kPopImpulseNs = 0.002;
// Tip force a pen's full pressure stands for when pressing a bubble (N). The synth's mapping tops
// out at 2 N (gesture.h: what a stroke feels), below the bubbles' 2.5 N pop force; a pen
// saturates its pressure scale at roughly 4 N of tip force, so a firm press (pressure > 0.6) pops.
constexpr double kBubblePressMaxForceN = 4.0;
constexpr double kCountersSaveIntervalS = 10.0;
// The pen counts as resting while it stays within this radius of where it settled (a hand holding
// a pen still drifts by a millimetre or two).
constexpr double kRestRadiusMm = 3.0;
// The passive stroke (attract): a gentle, slow stroke in bursts, with quiet gaps between them in
// which the microphone measures the room (ambient gain). Its sound is this far below a visitor's
// stroke of the same speed and pressure.
constexpr double kPassiveBurstS = 8.0;
constexpr double kPassiveGapS = 6.0;
constexpr double kPassiveRingOutS = 1.0;  // after a burst, before the room is measured again
constexpr double kPassiveSpeedMmS = 60.0;
constexpr double kPassivePressure = 0.35;
constexpr double kPassiveGainDb = -10.0;
// Per-stroke gain ramps (stroke_gain.h): while a stroke plays, over 20 ms (no audible step); for
// the first kLandingWindowS of a stroke over 1 ms, so the landing click gets the stroke's gain.
constexpr double kStrokeRampS = 0.02;
constexpr double kLandingRampS = 0.001;
constexpr double kLandingWindowS = 0.01;

std::vector<std::string> DataDirs(const std::string& sub) {
  std::vector<std::string> dirs;
  if (const char* data = std::getenv("SAS_DATA_DIR"); data != nullptr && *data) {
    dirs.push_back((fs::path(data) / sub).string());
  }
  dirs.push_back((fs::path(kSourceDir) / "textures" / (sub == "textures" ? "" : sub)).string());
  dirs.push_back((fs::path(kInstallPrefix) / "share" / "sketch-a-scratch" / sub).string());
  return dirs;
}

// The probe of an input without tilt (mouse, touch, the passive stroke): the texture's own, or a
// narrow scrape on the voice.
ProbeShape UntiltedProbe(const SurfaceChoice& choice, const std::vector<EngineTexture>& textures) {
  if (choice.voice) return {kVoiceWidthMm, synth::ProbeStyle::kScrape};
  const auto& probe = textures[static_cast<std::size_t>(choice.texture)].loaded.file.probe;
  return {probe.width_mm, probe.style};
}

}  // namespace

std::vector<std::string> FindTextureFiles() {
  std::string searched;
  for (const auto& dir : DataDirs("textures")) {
    std::vector<std::string> files;
    for (const auto& key : kTextureKeys) {
      const fs::path file = fs::path(dir) / key / "texture.toml";
      std::error_code error;
      if (fs::is_regular_file(file, error)) files.push_back(file.string());
    }
    if (files.size() == kTextureKeys.size()) return files;
    searched += (searched.empty() ? "" : ", ") + dir;
  }
  throw std::runtime_error("the four kiosk textures were not found (searched " + searched + ")");
}

std::vector<std::string> KioskTextureNames() {
  return kTextureKeys;
}

std::string FindTextureFile(const std::string& name) {
  if (std::find(kTextureKeys.begin(), kTextureKeys.end(), name) == kTextureKeys.end()) return {};
  for (const auto& dir : DataDirs("textures")) {
    const fs::path file = fs::path(dir) / name / "texture.toml";
    std::error_code error;
    if (fs::is_regular_file(file, error)) return file.string();
  }
  return {};
}

std::string FindStringsDir() {
  for (const auto& dir : DataDirs("strings")) {
    std::error_code error;
    if (fs::is_regular_file(fs::path(dir) / "en.toml", error)) return dir;
  }
  return {};
}

std::string FindCuesDir() {
  std::vector<std::string> dirs = DataDirs("cues");
  // The build generates the cues in its own tree (<build>/textures/cues, the binary being
  // <build>/app/sketch-a-scratch).
  std::error_code exe_error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", exe_error);
  if (!exe_error) dirs.push_back((exe.parent_path().parent_path() / "textures" / "cues").string());
  for (const auto& dir : dirs) {
    std::error_code error;
    if (fs::is_directory(dir, error)) return dir;
  }
  return {};
}

KioskEngine::KioskEngine(KioskEngineOptions options)
    : options_(std::move(options)),
      session_(SessionConfig{}),
      block_commands_(512),
      scratch_a_(static_cast<std::size_t>(std::max(1, options_.max_block_frames)) * 2),
      scratch_b_(scratch_a_.size()) {
  speaker_ceiling_ = std::pow(10.0, options_.config.sound_ceiling_db / 20.0);
  transducer_ceiling_ = std::pow(10.0, options_.config.haptic_ceiling_db / 20.0);
  low_vibration_factor_ = std::pow(10.0, -options_.config.low_vibration_db / 20.0);
  safety_.Prepare(options_.config.sample_rate_hz);
  safety_.SetCeilings(speaker_ceiling_, transducer_ceiling_);
  if (options_.texture_paths.empty()) options_.texture_paths = FindTextureFiles();
  const auto dirs = MaterialSearchDirs(options_.materials_dir);
  surface::TextureLoadOptions load;
  load.pixel_pitch_mm = surface::DisplayGeometry{}.pixel_pitch_mm();
  // Each texture loads on its own thread (as surface::LoadTextures does) but fails on its own: a
  // corrupt picture, texture.toml or material file leaves that texture out and the kiosk comes up
  // with the others, saying which one failed and why.
  std::vector<std::future<surface::LoadedTexture>> pending;
  for (const auto& path : options_.texture_paths) {
    pending.push_back(std::async(std::launch::async,
                                 [&path, &load] { return surface::LoadTexture(path, load); }));
  }
  std::string first_failure;
  for (std::size_t i = 0; i < pending.size(); ++i) {
    const std::string key = fs::path(options_.texture_paths[i]).parent_path().filename().string();
    counter_keys_.push_back(key);
    token_texture_.push_back(-1);
    try {
      EngineTexture texture;
      texture.key = key;
      texture.loaded = pending[i].get();
      texture.material = FindMaterial(texture.loaded.file.material, dirs);
      if (texture.loaded.bubbles) bubble_texture_ = static_cast<int>(textures_.size());
      token_texture_.back() = static_cast<int>(textures_.size());
      texture_keys_.push_back(texture.key);
      textures_.push_back(std::move(texture));
    } catch (const std::exception& error) {
      texture_failures_.push_back(key + ": " + error.what());
      if (first_failure.empty()) first_failure = error.what();
      platform::DefaultLogger().Error(
          "textures", key + " left out (its token shows the default texture): " + error.what());
    }
  }
  if (textures_.empty()) {
    throw std::runtime_error("no texture could be loaded (first error: " + first_failure + ")");
  }
  try {
    voice_material_ = FindMaterial(kVoiceMaterial, dirs);
  } catch (const std::exception&) {
    voice_material_ = textures_.front().material;
  }
  const auto found =
      std::find(texture_keys_.begin(), texture_keys_.end(), options_.config.default_texture);
  default_texture_ =
      found == texture_keys_.end() ? 0 : static_cast<int>(found - texture_keys_.begin());

  std::vector<const surface::StrokeLevelTable*> tables;
  for (const auto& texture : textures_) {
    tables.push_back(texture.loaded.file.levels ? &*texture.loaded.file.levels : nullptr);
  }
  stroke_gains_ = StrokeGainMap(tables);
  if (stroke_gains_.matched_textures() > 0 &&
      stroke_gains_.matched_textures() < static_cast<int>(textures_.size())) {
    platform::DefaultLogger().Warn(
        "textures", std::to_string(textures_.size() -
                                   static_cast<std::size_t>(stroke_gains_.matched_textures())) +
                        " texture(s) without a matching [levels] table: their strokes are not "
                        "loudness-matched stroke by stroke (texture.toml, regenerate_textures)");
  }

  SessionConfig session;
  session.texture_count = static_cast<int>(textures_.size());
  session.default_texture = default_texture_;
  session.idle_timeout_s = options_.config.idle_timeout_s;
  session.countdown_s = options_.countdown_s;
  session.record_max_s = options_.config.record_max_duration_s;
  session.staff_panel_timeout_s = options_.config.staff_panel_timeout_s;
  session.invitation_interval_s = options_.config.invitation_interval_s;
  session_ = Session(session);
  if (!options_.counters_path.empty()) {
    // Read under every texture's name, loaded or not: a texture left out today keeps its count.
    CountersRecovery recovery = RecoverCounters(options_.counters_path, counter_keys_);
    file_counters_ = recovery.counters;
    counters_may_save_ = recovery.may_save;
    if (!recovery.report.empty()) platform::DefaultLogger().Warn("counters", recovery.report);
    UsageCounters counters = file_counters_;
    counters.strokes_per_texture.assign(textures_.size(), 0);
    for (std::size_t i = 0; i < counter_keys_.size(); ++i) {
      if (token_texture_[i] >= 0) {
        counters.strokes_per_texture[static_cast<std::size_t>(token_texture_[i])] =
            file_counters_.strokes_per_texture[i];
      }
    }
    session_.RestoreCounters(counters);
  }
  saved_counters_ = session_.counters();

  if (options_.spoken_cues) {
    cues_dir_ = options_.cues_dir.empty() ? FindCuesDir() : options_.cues_dir;
  }
  LoadLanguages();
  LoadCues();
  fade_len_ = std::max(
      1, static_cast<int>(std::lround(options_.cross_fade_s * options_.config.sample_rate_hz)));
  for (auto& slot : slots_) slot.scene.Init(options_.config.sample_rate_hz);
  staff_smooth_ =
      static_cast<float>(1.0 - std::exp(-1.0 / (0.02 * options_.config.sample_rate_hz)));
  if (!options_.staff_settings_path.empty()) {
    StaffSettingsLoad staff_load = LoadStaffSettings(options_.staff_settings_path);
    if (!staff_load.report.empty()) platform::DefaultLogger().Warn("staff", staff_load.report);
    staff_may_save_ = staff_load.may_save;
    staff_ = staff_load.settings;
    // Where the ramps start: a restart comes up at the kept level, not fading into it.
    staff_sound_now_ = static_cast<float>(std::pow(10.0, staff_.volume_db / 20.0));
    staff_haptic_now_ = static_cast<float>(std::pow(10.0, staff_.vibration_db / 20.0));
    ApplyStaffGains();
    low_vibration_ = staff_.low_vibration;
    audio_low_vibration_.store(low_vibration_, std::memory_order_release);
  }
  ShowSurface({false, default_texture_});
  SetAudioRunning(false);  // no callback yet: take the first switch here
}

KioskEngine::~KioskEngine() {
  std::string error;
  SaveCounters(&error);
  recorder_ = nullptr;  // may already be gone: its owner wipes it
  WipeVoice();
}

// ---------------------------------------------------------------------------- cues and clips

int KioskEngine::AddClip(std::string name, std::vector<float> mono, int channel) {
  clips_.push_back({std::move(mono), channel, std::move(name), {}});
  return static_cast<int>(clips_.size()) - 1;
}

void KioskEngine::LoadLanguages() {
  const std::string strings_dir =
      options_.strings_dir.empty() ? FindStringsDir() : options_.strings_dir;
  // The configured language first (index 0 is the one an idle reset returns to), then the
  // visitor's choices in their order.
  std::vector<std::string> codes = {options_.config.language};
  for (const auto& code : options_.config.visitor_languages) {
    if (std::find(codes.begin(), codes.end(), code) == codes.end()) codes.push_back(code);
  }
  for (const auto& code : codes) {
    LanguageAssets assets;
    try {
      if (strings_dir.empty()) throw std::runtime_error("no strings folder found");
      assets.table = LoadLanguageTable(strings_dir, code);
    } catch (const std::exception& bad) {
      // The kiosk still runs: without its table a language has no texts or cues of its own.
      platform::DefaultLogger().Warn("strings",
                                     std::string(bad.what()) + "; language " + code + " left out");
      if (!languages_.empty()) continue;
      assets.table.code = code;
    }
    languages_.push_back(std::move(assets));
  }
  for (std::size_t i = 1; i < languages_.size(); ++i) {
    const auto& code = languages_[i].table.code;
    if (std::find(options_.config.visitor_languages.begin(),
                  options_.config.visitor_languages.end(),
                  code) != options_.config.visitor_languages.end()) {
      visitor_languages_.push_back(static_cast<int>(i));
    }
  }
  if (std::find(options_.config.visitor_languages.begin(), options_.config.visitor_languages.end(),
                options_.config.language) != options_.config.visitor_languages.end()) {
    visitor_languages_.insert(visitor_languages_.begin(), 0);
  }
}

void KioskEngine::LoadCues() {
  const double fs_hz = options_.config.sample_rate_hz;
  const auto load = [&](const fs::path& dir, const std::string& key) -> int {
    if (cues_dir_.empty()) return -1;
    const fs::path path = dir / (key + ".wav");
    std::error_code error;
    if (!fs::is_regular_file(path, error)) return -1;
    try {
      surface::AudioReadLimits limits;
      limits.target_rate_hz = fs_hz;
      limits.max_duration_s = 30.0;
      auto clip = surface::ReadAudioFile(path.string(), limits);
      if (const std::string problem = surface::CueLevelProblem(clip); !problem.empty()) {
        throw std::runtime_error(path.string() + ": " + problem);
      }
      const int index = AddClip(key, std::move(clip.samples), 0);
      // The sentence cue_maker spoke into it: reported with each play (CueEvent).
      std::ifstream text(dir / (key + ".txt"));
      std::getline(text, clips_.back().text);
      return index;
    } catch (const std::exception& bad) {
      platform::DefaultLogger().Warn("cues", std::string(bad.what()) + "; that cue stays silent");
      return -1;  // the visit goes on
    }
  };
  int expected = 0;
  for (std::size_t l = 0; l < languages_.size(); ++l) {
    auto& language = languages_[l];
    // <cues>/<language>/; a folder holding the files themselves serves the configured language.
    fs::path dir = fs::path(cues_dir_) / language.table.code;
    std::error_code error;
    if (!fs::is_directory(dir, error)) {
      if (l != 0) continue;
      dir = cues_dir_;
    }
    for (const auto& key : texture_keys_) {
      language.name_cues.push_back(load(dir, key + "_name"));
      language.description_cues.push_back(load(dir, key + "_description"));
    }
    for (const auto& key : CueKeys()) language.message_cues[key] = load(dir, key);
    expected += static_cast<int>(texture_keys_.size() * 2 + CueKeys().size());
  }
  // For a blind visitor the cues are the only way to know which texture is under the pen: a box
  // without them must say so where staff look (journal at warning, staff panel's CUES line).
  if (options_.spoken_cues) {
    expected = std::max(expected, static_cast<int>(texture_keys_.size() * 2 + CueKeys().size()));
    const int loaded = static_cast<int>(clips_.size());
    if (loaded < expected) {
      platform::DefaultLogger().Warn(
          "cues", "only " + std::to_string(loaded) + " of " + std::to_string(expected) +
                      " spoken cues found" +
                      (cues_dir_.empty() ? " (no cues folder found)" : " in " + cues_dir_) +
                      "; blind visitors will not hear those texture names and messages");
    }
  }

  // Staff test signals: 1 kHz at -12 dBFS on the speaker for 1 s; a 2 s exponential sweep
  // 40 -> 800 Hz (the transducer band) at -6 dBFS on ch 2. 10 ms raised-cosine edges.
  const auto edge = [&](std::size_t i, std::size_t n) {
    const double ramp = 0.01 * fs_hz;
    const double k =
        std::min({1.0, static_cast<double>(i) / ramp, static_cast<double>(n - i) / ramp});
    return 0.5 - 0.5 * std::cos(3.14159265358979 * k);
  };
  // A sine of `seconds` at `hz`, -12 dBFS, with the edges above.
  const auto tone = [&](double seconds, double hz) {
    const auto n = static_cast<std::size_t>(seconds * fs_hz);
    std::vector<float> out(n, 0.0f);
    for (std::size_t i = 0; i < n; ++i) {
      out[i] = static_cast<float>(
          0.25 * edge(i, n) *
          std::sin(2.0 * 3.14159265358979 * hz * static_cast<double>(i) / fs_hz));
    }
    return out;
  };
  tone_clip_ = AddClip("test tone", tone(1.0, 1000.0), 0);
  // The recording's tone: 0.25 s of 880 Hz, a clear "now" that the count leads up to (the same in
  // every language).
  record_tone_clip_ = AddClip("record tone", tone(0.25, 880.0), 0);
  {
    const auto n = static_cast<std::size_t>(2.0 * fs_hz);
    const double f0 = 40.0, f1 = 800.0, length_s = 2.0;
    const double k = std::log(f1 / f0);
    std::vector<float> sweep(n, 0.0f);
    for (std::size_t i = 0; i < n; ++i) {
      const double t = static_cast<double>(i) / fs_hz;
      const double phase =
          2.0 * 3.14159265358979 * f0 * length_s / k * (std::exp(t * k / length_s) - 1.0);
      sweep[i] = static_cast<float>(0.5 * edge(i, n) * std::sin(phase));
    }
    sweep_clip_ = AddClip("transducer sweep", std::move(sweep), 1);
  }
}

int KioskEngine::cues_loaded() const {
  return static_cast<int>(clips_.size()) - 3;  // minus the test signals and the record tone
}

const char* KioskEngine::CueKey(Cue cue) {
  switch (cue) {
    case Cue::kRecordCountdown:
      return "record_countdown";
    case Cue::kRecordingTooQuiet:
      return "too_quiet";
    case Cue::kRecordingTooLoud:
      return "too_loud";
    case Cue::kRecordingUnavailable:
      return "no_microphone";
    case Cue::kVoiceReady:
      return "voice_ready";
    case Cue::kInvitation:
      return "invitation";
    case Cue::kTextureName:
    case Cue::kTextureDescription:
    case Cue::kCount:
    case Cue::kRecordTone:
      break;
  }
  return "";
}

void KioskEngine::Speak(const SessionAction& action) {
  if (action.cue == Cue::kCount) {
    SpeakMessage("count_" + std::to_string(std::clamp(action.count, 1, 3)));
  } else if (action.cue == Cue::kRecordTone) {
    PlayCue(record_tone_clip_, "tone");
  } else {
    Speak(action.cue, action.surface.texture);
  }
}

void KioskEngine::Speak(Cue cue, int texture) {
  const auto& language = languages_[static_cast<std::size_t>(language_)];
  const auto t = static_cast<std::size_t>(std::clamp(texture, 0, int(textures_.size()) - 1));
  if (cue == Cue::kTextureName) {
    PlayCue(t < language.name_cues.size() ? language.name_cues[t] : -1, texture_keys_[t] + "_name");
  } else if (cue == Cue::kTextureDescription) {
    PlayCue(t < language.description_cues.size() ? language.description_cues[t] : -1,
            texture_keys_[t] + "_description");
  } else {
    SpeakMessage(CueKey(cue));
  }
}

void KioskEngine::SpeakMessage(const std::string& key) {
  const auto& cues = languages_[static_cast<std::size_t>(language_)].message_cues;
  const auto found = cues.find(key);
  PlayCue(found == cues.end() ? -1 : found->second, key);
}

void KioskEngine::PlayCue(int clip, const std::string& key) {
  if (clip < 0) return;  // no file: carry on silently (the screen still says it)
  Play(clip);
  if (cue_observer_) {
    cue_observer_({last_now_ns_, languages_[static_cast<std::size_t>(language_)].table.code, key,
                   clips_[static_cast<std::size_t>(clip)].text});
  }
}

bool KioskEngine::NextLanguage(std::int64_t now_ns) {
  last_now_ns_ = std::max(last_now_ns_, now_ns);
  if (visitor_languages_.size() < 2) return false;
  session_.OnVisitorActivity(static_cast<double>(now_ns) * 1e-9);
  const auto at = std::find(visitor_languages_.begin(), visitor_languages_.end(), language_);
  language_ = at == visitor_languages_.end() || at + 1 == visitor_languages_.end()
                  ? visitor_languages_.front()
                  : *(at + 1);
  SpeakMessage("language");  // in the new language: its own name
  return true;
}

const LanguageTable& KioskEngine::strings() const {
  return languages_[static_cast<std::size_t>(language_)].table;
}

std::string KioskEngine::TextureName(int texture) const {
  const auto t = static_cast<std::size_t>(std::clamp(texture, 0, int(textures_.size()) - 1));
  return strings().CueText(texture_keys_[t] + "_name", textures_[t].loaded.file.name);
}

void KioskEngine::Play(int clip) {
  Message message;
  message.kind = Message::Kind::kPlay;
  message.time_ns = last_now_ns_;
  message.slot = clip;
  Send(message);
}

void KioskEngine::PlayTestTone() {
  Play(tone_clip_);
}
void KioskEngine::PlayTransducerSweep() {
  Play(sweep_clip_);
}

// ---------------------------------------------------------------------------- control thread

void KioskEngine::Send(const Message& message) {
  if (!queue_.TryPush(message)) dropped_.fetch_add(1, std::memory_order_relaxed);
}

void KioskEngine::ScreenToField(double x_px, double y_px, double* fx, double* fy) const {
  // The picture covers the screen (picture_io.h ResizeToCover): uniform scale, centred crop.
  const auto& field = *current_field_;
  const double sw = options_.screen_width_px, sh = options_.screen_height_px;
  const double scale = std::max(sw / field.width(), sh / field.height());
  const double crop_x = (field.width() * scale - sw) / 2.0;
  const double crop_y = (field.height() * scale - sh) / 2.0;
  *fx = (x_px + crop_x) / scale;
  *fy = (y_px + crop_y) / scale;
}

void KioskEngine::FieldToScreen(double fx, double fy, double* x_px, double* y_px) const {
  const auto& field = *current_field_;
  const double sw = options_.screen_width_px, sh = options_.screen_height_px;
  const double scale = std::max(sw / field.width(), sh / field.height());
  *x_px = fx * scale - (field.width() * scale - sw) / 2.0;
  *y_px = fy * scale - (field.height() * scale - sh) / 2.0;
}

const surface::BubbleWrapState* KioskEngine::bubbles() const {
  if (bubble_texture_ < 0) return nullptr;
  const auto& state = textures_[static_cast<std::size_t>(bubble_texture_)].loaded.bubbles;
  return state ? &*state : nullptr;
}

int KioskEngine::popped_bubbles() const {
  const auto* state = bubbles();
  return state ? state->popped_count() : 0;
}

void KioskEngine::OnPen(const platform::PenReading& pen, std::optional<synth::ProbeStyle> style) {
  last_now_ns_ = std::max(last_now_ns_, pen.time_ns);
  session_.OnPen(static_cast<double>(pen.time_ns) * 1e-9, pen.tip_down);
  WatchPenRest(pen);
  if (passive_down_) {
    // The passive probe owns the scene until a visitor touches: a hover over the attract screen
    // must not lift it; a touch takes the probe over where the pen is (its command follows).
    if (!pen.tip_down && session_.mode() == SessionMode::kAttract) return;
    passive_down_ = false;
  }
  const auto& field = *current_field_;
  double fx = 0.0, fy = 0.0;
  ScreenToField(pen.x_px, pen.y_px, &fx, &fy);
  const double pitch = field.pitch_m();
  const double x_m = fx * pitch, y_m = fy * pitch;
  const double pressure = std::clamp(pen.pressure, 0.0, 1.0);

  synth::ProbeCommand command;
  command.tip_down = pen.tip_down && pressure > 0.0;
  command.x_m = x_m;
  command.y_m = y_m;
  if (command.tip_down && have_last_pen_ && last_pen_.tip_down) {
    const double dx = x_m - last_fx_, dy = y_m - last_fy_;
    const double distance = std::hypot(dx, dy);
    const double dt_s = std::max(1e-3, static_cast<double>(pen.time_ns - last_pen_.time_ns) * 1e-9);
    command.velocity_mps = distance / dt_s;
    if (distance > 1e-9) {
      dir_x_ = dx / distance;
      dir_y_ = dy / distance;
    }
  }
  command.direction_x = dir_x_;
  command.direction_y = dir_y_;
  const SurfaceChoice choice = session_.surface();
  ApplyPenReading(pen, current_relief_m_, UntiltedProbe(choice, textures_), style, mapping_,
                  command);

  // Per-stroke loudness matching (stroke_gain.h): the smoothed stroke's correction for the scene
  // the pen plays; held while the pen is up. The speed counts hover reports too (touch-down).
  {
    const double dt_s =
        have_last_pen_ ? static_cast<double>(pen.time_ns - last_pen_.time_ns) * 1e-9 : 0.0;
    const bool recent = have_last_pen_ && dt_s > 0.0 && dt_s <= kMaxReportGapS;
    const double speed_mm_s =
        recent ? std::hypot(x_m - last_fx_, y_m - last_fy_) / dt_s * 1e3 : 0.0;
    stroke_.Update(command.tip_down, recent, speed_mm_s, pressure, dt_s);
  }
  if (command.tip_down && !(have_last_pen_ && last_pen_.tip_down)) stroke_down_ns_ = pen.time_ns;
  if (command.tip_down && requested_slot_ >= 0) {
    stroke_style_ = command.style;
    stroke_width_mm_ = command.width_mm;
    stroke_correction_ = CorrectionFor(stroke_texture_);
    // Landing: the new stroke's gain must be in place when its landing click (the loudest part
    // of a slow stroke) sounds, one buffer from now, so it ramps over kLandingRampS; the scene
    // only rings out the last stroke's tail meanwhile. Then over the scene's 20 ms.
    const bool landing =
        static_cast<double>(pen.time_ns - stroke_down_ns_) * 1e-9 < kLandingWindowS;
    slots_[static_cast<std::size_t>(requested_slot_)].scene.SetStrokeGains(
        std::pow(10.0, stroke_correction_.sound_db / 20.0),
        std::pow(10.0, stroke_correction_.haptic_db / 20.0),
        landing ? kLandingRampS : kStrokeRampS);
  }

  // Bubble wrap: a hard enough press pops the bubble under the tip (a burst through the contact).
  if (command.tip_down && !choice.voice && choice.texture == bubble_texture_) {
    auto& state = textures_[static_cast<std::size_t>(bubble_texture_)].loaded.bubbles;
    if (state) {
      if (const auto pop = state->Press(fx, fy, pressure * kBubblePressMaxForceN)) {
        command.burst_impulse_n_s = kPopImpulseNs * pop->strength;
        bubbles_dirty_ = true;
      }
    }
  }

  Message message;
  message.kind = Message::Kind::kProbe;
  message.time_ns = pen.time_ns;
  message.command = command;
  Send(message);
  have_last_pen_ = true;
  last_pen_ = pen;
  last_fx_ = x_m;
  last_fy_ = y_m;
}

void KioskEngine::WatchPenRest(const platform::PenReading& pen) {
  if (!pen.tip_down || pen.pressure <= 0.0) {
    rest_since_ns_ = -1;
    return;
  }
  const double radius_px = kRestRadiusMm / surface::DisplayGeometry{}.pixel_pitch_mm();
  if (rest_since_ns_ < 0 || std::hypot(pen.x_px - rest_x_px_, pen.y_px - rest_y_px_) > radius_px) {
    // Touched down or moved on: a new place to rest, described again when the pen stops there.
    rest_x_px_ = pen.x_px;
    rest_y_px_ = pen.y_px;
    rest_since_ns_ = pen.time_ns;
    rest_spoken_ = false;
  }
}

void KioskEngine::PassiveStroke(std::int64_t now_ns) {
  const bool attract = session_.mode() == SessionMode::kAttract;
  if (!options_.attract_stroke || !attract) {
    passive_started_ns_ = -1;
    return;
  }
  if (passive_started_ns_ < 0) passive_started_ns_ = now_ns;
  const double t_s = static_cast<double>(now_ns - passive_started_ns_) * 1e-9;
  const double cycle_s = kPassiveBurstS + kPassiveGapS;
  const double in_cycle_s = std::fmod(t_s, cycle_s);
  // A quiet gap first, so the attract screen starts in silence after a visit.
  const bool down = in_cycle_s >= kPassiveGapS;
  if (!down) {
    if (passive_down_) {
      passive_down_ = false;
      passive_quiet_since_ns_ = now_ns;
      Message lift;
      lift.kind = Message::Kind::kProbe;
      lift.time_ns = now_ns;
      lift.command = last_passive_command_;
      lift.command.tip_down = false;
      lift.command.velocity_mps = 0.0;
      Send(lift);
    }
    return;
  }
  // Back and forth across the middle of the picture along a gentle wave: the whole burst covers
  // kPassiveSpeedMmS * kPassiveBurstS of the surface at a steady speed.
  const double pitch_mm = surface::DisplayGeometry{}.pixel_pitch_mm();
  const double sw = options_.screen_width_px, sh = options_.screen_height_px;
  const double span_px = 0.5 * sw;
  const double travelled_px = (in_cycle_s - kPassiveGapS) * kPassiveSpeedMmS / pitch_mm;
  const double leg = std::fmod(travelled_px, 2.0 * span_px);
  const double along = leg < span_px ? leg : 2.0 * span_px - leg;
  platform::PenReading pen;
  pen.time_ns = now_ns;
  pen.x_px = 0.25 * sw + along;
  pen.y_px = 0.5 * sh + 0.08 * sh * std::sin(2.0 * 3.14159265358979 * along / span_px);
  pen.pressure = kPassivePressure;
  pen.tip_down = true;
  double fx = 0.0, fy = 0.0;
  ScreenToField(pen.x_px, pen.y_px, &fx, &fy);
  const double pitch_m = current_field_->pitch_m();
  synth::ProbeCommand command;
  command.tip_down = true;
  command.x_m = fx * pitch_m;
  command.y_m = fy * pitch_m;
  if (passive_down_) {
    const double dx = command.x_m - last_passive_command_.x_m;
    const double dy = command.y_m - last_passive_command_.y_m;
    const double distance = std::hypot(dx, dy);
    const double dt_s = std::max(1e-3, static_cast<double>(now_ns - passive_pen_.time_ns) * 1e-9);
    command.velocity_mps = distance / dt_s;
    if (distance > 1e-12) {
      command.direction_x = dx / distance;
      command.direction_y = dy / distance;
    }
  } else if (requested_slot_ >= 0) {
    // The burst's level: the texture's own, this far down (a visitor's touch sets it anew).
    const double gain = std::pow(10.0, kPassiveGainDb / 20.0);
    slots_[static_cast<std::size_t>(requested_slot_)].scene.SetStrokeGains(gain, gain,
                                                                           kStrokeRampS);
  }
  // No tilt: the passive probe strokes with the texture's own probe.
  ApplyPenReading(pen, current_relief_m_, UntiltedProbe(session_.surface(), textures_), {},
                  mapping_, command);
  Message message;
  message.kind = Message::Kind::kProbe;
  message.time_ns = now_ns;
  message.command = command;
  Send(message);
  passive_down_ = true;
  passive_pen_ = pen;
  last_passive_command_ = command;
}

bool KioskEngine::AmbientListening() const {
  if (audio_clip_playing_.load(std::memory_order_relaxed) || passive_down_) return false;
  return static_cast<double>(last_now_ns_ - passive_quiet_since_ns_) * 1e-9 >= kPassiveRingOutS;
}

int KioskEngine::TokenForTexture(std::size_t texture_index) const {
  for (std::size_t token = 0; token < token_texture_.size(); ++token) {
    if (token_texture_[token] == static_cast<int>(texture_index)) return static_cast<int>(token);
  }
  return -1;
}

void KioskEngine::OnToken(std::int64_t now_ns, int token) {
  last_now_ns_ = std::max(last_now_ns_, now_ns);
  // A token whose texture could not be loaded counts as no token: the default texture.
  const int texture = token >= 0 && token < static_cast<int>(token_texture_.size())
                          ? token_texture_[static_cast<std::size_t>(token)]
                          : -1;
  session_.OnTokenSelection(static_cast<double>(now_ns) * 1e-9, texture);
}

void KioskEngine::OnRecordButton(std::int64_t now_ns, bool pressed) {
  last_now_ns_ = std::max(last_now_ns_, now_ns);
  session_.OnRecordButton(static_cast<double>(now_ns) * 1e-9, pressed);
}

void KioskEngine::OnStaffChord(std::int64_t now_ns) {
  last_now_ns_ = std::max(last_now_ns_, now_ns);
  session_.OnStaffChord(static_cast<double>(now_ns) * 1e-9);
}

void KioskEngine::OnStaffActivity(std::int64_t now_ns) {
  last_now_ns_ = std::max(last_now_ns_, now_ns);
  session_.OnStaffActivity(static_cast<double>(now_ns) * 1e-9);
}

std::vector<SessionAction> KioskEngine::Tick(std::int64_t now_ns) {
  last_now_ns_ = std::max(last_now_ns_, now_ns);
  const double now_s = static_cast<double>(now_ns) * 1e-9;
  if (!audio_running_) SetAudioRunning(false);  // keep the pool moving without a device
  // A pen held still sends few or no reports (a mouse none at all): the rest is timed here.
  if (rest_since_ns_ >= 0 && !rest_spoken_ && options_.config.describe_after_rest_s > 0.0 &&
      static_cast<double>(now_ns - rest_since_ns_) * 1e-9 >=
          options_.config.describe_after_rest_s) {
    rest_spoken_ = true;
    session_.OnPenRest(now_s);
  }
  session_.Tick(now_s);
  {
    const std::uint64_t frames = audio_speaker_frames_.load(std::memory_order_acquire);
    exposure_.Update(now_ns, audio_speaker_energy_.load(std::memory_order_relaxed), frames,
                     session_.mode() != SessionMode::kAttract);
  }
  std::vector<SessionAction> all;
  // Applying actions can produce more (a finished recording becomes a surface): loop.
  for (int round = 0; round < 4; ++round) {
    auto actions = session_.TakeActions();
    if (actions.empty()) break;
    ApplyActions(now_ns, actions);
    all.insert(all.end(), actions.begin(), actions.end());
  }
  PassiveStroke(now_ns);
  const bool acknowledged = switches_done_.load(std::memory_order_acquire) == switches_sent_;
  if (pending_surface_ && acknowledged) {
    const SurfaceChoice choice = *pending_surface_;
    pending_surface_.reset();
    ShowSurface(choice);
  } else if (bubbles_dirty_ && acknowledged && !last_pen_.tip_down) {
    // The pen is up: the bubble scene takes the flattened field (and rings out the old one).
    bubbles_dirty_ = false;
    const SurfaceChoice choice = session_.surface();
    if (!choice.voice && choice.texture == bubble_texture_) ShowSurface(choice);
  }
  if (release_idle_slots_ && acknowledged && !pending_surface_ &&
      audio_fade_from_.load(std::memory_order_acquire) < 0) {
    // The idle reset has faded over to the default texture: the other slots' fields (the wiped
    // voice, flattened bubble wrap copies, the visit's textures) are let go, so an idle kiosk
    // holds the same memory after every visit and no voice lingers in a scene.
    release_idle_slots_ = false;
    const int active = audio_active_.load(std::memory_order_acquire);
    for (int slot = 0; slot < kSceneSlots; ++slot) {
      if (slot != active && slot != requested_slot_) {
        slots_[static_cast<std::size_t>(slot)].field.reset();
      }
    }
  }
  if (!options_.counters_path.empty() && session_.counters() != saved_counters_ &&
      now_s - last_counters_save_s_ >= kCountersSaveIntervalS) {
    std::string error;
    SaveCounters(&error);  // a failure is reported once on the status board (storage)
    last_counters_save_s_ = now_s;
  }
  return all;
}

void KioskEngine::ApplyActions(std::int64_t now_ns, const std::vector<SessionAction>& actions) {
  using Kind = SessionAction::Kind;
  for (const auto& action : actions) {
    switch (action.kind) {
      case Kind::kShowSurface:
        ShowSurface(action.surface);
        break;
      case Kind::kSpeak:
        Speak(action);
        break;
      case Kind::kStartRecording:
        if (recorder_ == nullptr) {
          session_.OnRecordingFinished(static_cast<double>(now_ns) * 1e-9,
                                       RecordingOutcome::kNoMicrophone);
        } else {
          recorder_->Arm();
          recording_ = true;
        }
        break;
      case Kind::kStopRecording:
        FinishRecording(now_ns);
        break;
      case Kind::kCancelRecording:
        if (recorder_) recorder_->Wipe();
        recording_ = false;
        break;
      case Kind::kWipeVoice:
        WipeVoice();
        break;
      case Kind::kResetTextures:
        for (auto& texture : textures_) {
          if (texture.loaded.bubbles) texture.loaded.bubbles->Reset();
        }
        bubbles_dirty_ = false;  // the default texture's scene is prepared afresh below
        release_idle_slots_ = true;
        break;
      case Kind::kEnterAttract:
        language_ = 0;  // the next visitor hears the configured language
        break;
      case Kind::kLeaveAttract:
      case Kind::kStaffPanel:
        break;  // the UI's business
    }
  }
}

void KioskEngine::FinishRecording(std::int64_t now_ns) {
  if (!recording_ || recorder_ == nullptr) return;
  recording_ = false;
  recorder_->Stop();
  // The take is a view of the recorder's buffer: used in place, then wiped with it.
  const platform::VoiceTake take = recorder_->Take();
  RecordingOutcome outcome = RecordingOutcome::kOk;
  if (take.silent) {
    outcome = RecordingOutcome::kSilent;
  } else if (take.clipped) {
    outcome = RecordingOutcome::kClipped;
  } else {
    outcome = AcceptRecording(now_ns, take.samples);
  }
  recorder_->Wipe();
  session_.OnRecordingFinished(static_cast<double>(now_ns) * 1e-9, outcome);
}

surface::SoundImageOptions VoiceImageOptions(double rate_hz, double max_duration_s,
                                             std::size_t sample_count) {
  surface::SoundImageOptions image;
  image.sample_rate_hz = rate_hz;
  image.samples_per_row = static_cast<int>(std::lround(0.1 * rate_hz));
  image.max_duration_s = max_duration_s;
  const auto rows = static_cast<int>(
      (std::min(sample_count, static_cast<std::size_t>(std::lround(max_duration_s * rate_hz))) +
       static_cast<std::size_t>(image.samples_per_row) - 1) /
      static_cast<std::size_t>(image.samples_per_row));
  // Rows as bands (paper figure 3) so the image has the screen's shape.
  image.row_height_px = std::max(1, 1080 / std::max(1, rows));
  return image;
}

RecordingOutcome KioskEngine::AcceptRecording(std::int64_t /*now_ns*/,
                                              std::span<const float> samples) {
  const surface::SoundImageOptions image = VoiceImageOptions(
      options_.config.sample_rate_hz, options_.config.record_max_duration_s, samples.size());
  // The sound image is the recording row by row, and the field is that image as heights: both
  // are the visitor's voice, so they are made (and released, zeroed) in memory a core dump
  // leaves out. They are constructed in place, never assigned (height_field.h).
  std::pmr::memory_resource* memory = platform::NoDumpMemory();
  RecordingOutcome outcome = RecordingOutcome::kOk;
  try {
    surface::HeightField field = surface::SoundToHeightField(
        samples, image, kVoiceReliefMm, surface::DisplayGeometry{}.pixel_pitch_mm(), memory);
    voice_image_.reset();
    voice_image_.emplace(surface::SoundToImage(samples, image, memory));
    voice_.Store(kVoiceSlot, "voice", std::move(field));
  } catch (const std::invalid_argument&) {
    outcome = RecordingOutcome::kSilent;  // nothing to feel: ask again
  }
  return outcome;
}

void KioskEngine::WipeVoice() {
  // The image's and the field's memory is zeroed when the last holder lets it go (NoDumpMemory):
  // the image here, the field once no scene slot holds it any more (the idle reset's release).
  voice_.Clear(kVoiceSlot);
  voice_image_.reset();
  if (recorder_) recorder_->Wipe();
}

void KioskEngine::ShowSurface(const SurfaceChoice& choice) {
  if (audio_running_ && switches_done_.load(std::memory_order_acquire) != switches_sent_) {
    pending_surface_ = choice;  // the audio side has not taken the previous switch yet
    return;
  }
  if (choice.voice) {
    auto field = voice_.Recall(kVoiceSlot);
    if (!field) return;
    SwitchTo(std::move(field), voice_material_, {}, -1);
    return;
  }
  auto& texture = textures_[static_cast<std::size_t>(choice.texture)];
  auto field = texture.loaded.bubbles ? texture.loaded.bubbles->field() : texture.loaded.field;
  SwitchTo(std::move(field), texture.material, texture.loaded.file.gains, choice.texture);
}

StrokeCorrection KioskEngine::CorrectionFor(int texture) const {
  if (!stroke_.valid()) return {};
  return stroke_gains_.Correction(texture, stroke_style_, stroke_width_mm_, stroke_.speed_mm_s(),
                                  stroke_.pressure());
}

int KioskEngine::FreeSlot() const {
  const int active = audio_active_.load(std::memory_order_acquire);
  const int fading = audio_fade_from_.load(std::memory_order_acquire);
  for (int slot = 0; slot < kSceneSlots; ++slot) {
    if (slot != active && slot != fading && slot != requested_slot_) return slot;
  }
  return -1;  // cannot happen with 4 slots and at most 3 in use
}

void KioskEngine::SwitchTo(std::shared_ptr<const surface::HeightField> field,
                           const Material& material, const surface::TextureGains& gains,
                           int texture) {
  const int slot = FreeSlot();
  if (slot < 0) return;
  auto& target = slots_[static_cast<std::size_t>(slot)];
  // Configuration + texture loudness-matching gains + the ambient gain, the transducer ceiling and
  // the staff's low-vibration mode: one builder for every path (output_gains.h).
  const synth::OutputParams output =
      KioskOutputParams(options_.config, gains, ambient_gain_db_, low_vibration_);
  ambient_gain_applied_db_ = ambient_gain_db_;
  target.field = field;
  // The new scene starts at the correction for the last stroke (Prepare takes it at once).
  stroke_texture_ = texture;
  stroke_correction_ = CorrectionFor(texture);
  target.scene.SetStrokeGains(std::pow(10.0, stroke_correction_.sound_db / 20.0),
                              std::pow(10.0, stroke_correction_.haptic_db / 20.0));
  if (passive_down_) {
    const double gain = std::pow(10.0, kPassiveGainDb / 20.0);  // the passive stroke goes on
    target.scene.SetStrokeGains(gain, gain);
  }
  target.scene.Prepare(material.params, output, target.field->View());
  current_field_ = std::move(field);
  current_relief_m_ = ReliefM(*current_field_);
  Message message;
  message.kind = Message::Kind::kSwitch;
  message.time_ns = last_now_ns_;
  message.slot = slot;
  requested_slot_ = slot;
  ++switches_sent_;
  Send(message);
}

void KioskEngine::SetAudioRunning(bool running) {
  audio_running_ = running;
  if (running) return;
  // No callback can run: consume the queue here so switches take effect and nothing piles up.
  Message message;
  while (queue_.TryPop(message)) {
    if (message.kind == Message::Kind::kSwitch) {
      ApplySwitchOnAudio(message.slot);
      fade_from_ = -1;
      audio_fade_from_.store(-1, std::memory_order_release);
    }
  }
  playing_clip_ = -1;
}

void KioskEngine::SetLowVibration(bool on) {
  // Every prepared scene follows at once (an atomic each scene reads per block, 20 ms ramp);
  // scenes prepared later get it through their output parameters.
  low_vibration_ = on;
  if (staff_.low_vibration != on) {
    staff_.low_vibration = on;
    SaveStaffSettings();
  }
  for (auto& slot : slots_) slot.scene.SetLowVibration(on);
  // The transducer's ceiling comes down too, so nothing mixed after the scenes (the staff sweep,
  // a cue) can drive it harder than the mode allows.
  audio_low_vibration_.store(on, std::memory_order_release);
}

void KioskEngine::StepVolume(int steps) {
  staff_.volume_db = StepStaffDb(staff_.volume_db, steps);
  ApplyStaffGains();
  SaveStaffSettings();
}

void KioskEngine::StepVibration(int steps) {
  staff_.vibration_db = StepStaffDb(staff_.vibration_db, steps);
  ApplyStaffGains();
  SaveStaffSettings();
}

void KioskEngine::ApplyStaffGains() {
  audio_staff_sound_.store(static_cast<float>(std::pow(10.0, staff_.volume_db / 20.0)),
                           std::memory_order_relaxed);
  audio_staff_haptic_.store(static_cast<float>(std::pow(10.0, staff_.vibration_db / 20.0)),
                            std::memory_order_relaxed);
}

void KioskEngine::SaveStaffSettings() {
  if (options_.staff_settings_path.empty()) return;
  std::string why;
  if (!staff_may_save_) {
    why = "the damaged file could not be moved aside";
  } else if (kiosk::SaveStaffSettings(options_.staff_settings_path, staff_, &why)) {
    return;
  }
  // The change holds until the next restart; staff see why it will not last.
  const std::string message = "staff settings not saved to " + options_.staff_settings_path + " (" +
                              why + "); they hold until the kiosk restarts";
  if (board_) {
    board_->Set("storage", platform::DeviceState::kLost, message);
  } else {
    platform::DefaultLogger().Warn("staff", message);
  }
}

void KioskEngine::SetAmbientGainDb(double gain_db) {
  // The ambient gain only moves while nobody is at the box (attract screen), so no stroke hears
  // it change. It reaches the sound through a freshly prepared scene of the same surface (a
  // silent cross-fade), re-prepared only when it has moved by half a dB or more since the last
  // time, and otherwise with the next texture switch.
  ambient_gain_db_ = std::isfinite(gain_db) ? gain_db : 0.0;
  if (session_.mode() == SessionMode::kAttract &&
      std::fabs(ambient_gain_db_ - ambient_gain_applied_db_) >= 0.5) {
    ShowSurface(session_.surface());
  }
}

bool KioskEngine::SaveCounters(std::string* error) const {
  if (options_.counters_path.empty()) return true;
  if (!counters_may_save_) {
    // Reported once at start: a damaged file that could not be moved aside is never replaced.
    if (error) *error = options_.counters_path + " is damaged and could not be moved aside";
    return false;
  }
  // Session counts for the loaded textures, the file's own for any left out.
  UsageCounters all = session_.counters();
  all.strokes_per_texture = file_counters_.strokes_per_texture;
  all.strokes_per_texture.resize(counter_keys_.size(), 0);
  for (std::size_t i = 0; i < counter_keys_.size(); ++i) {
    if (token_texture_[i] >= 0) {
      all.strokes_per_texture[i] =
          session_.counters().strokes_per_texture[static_cast<std::size_t>(token_texture_[i])];
    }
  }
  std::string why;
  const bool saved = kiosk::SaveCounters(options_.counters_path, all, counter_keys_, &why);
  if (error) *error = why;
  // Staff see a failing save once (journal + panel), not every 10 s; and when it works again.
  if (!saved) {
    if (board_) {
      board_->Set("storage", platform::DeviceState::kLost,
                  "usage counters not saved (" + why + "); counting on in memory, retrying");
    } else {
      platform::DefaultLogger().Warn("counters", "not saved: " + why);
    }
    return false;
  }
  if (board_) {
    board_->Set("storage", platform::DeviceState::kOk,
                "usage counters saved to " + options_.counters_path);
  }
  saved_counters_ = session_.counters();
  return true;
}

EngineAudioStats KioskEngine::audio_stats() const {
  EngineAudioStats stats;
  stats.pen_to_sample_last_ns = latency_last_ns_.load(std::memory_order_relaxed);
  stats.pen_to_sample_max_ns = latency_max_ns_.load(std::memory_order_relaxed);
  stats.commands = commands_done_.load(std::memory_order_relaxed);
  stats.dropped_commands = dropped_.load(std::memory_order_relaxed);
  stats.switches = switches_done_.load(std::memory_order_relaxed);
  return stats;
}

// ---------------------------------------------------------------------------- audio thread

void KioskEngine::ApplySwitchOnAudio(int slot) noexcept {
  if (slot == active_) return;
  if (active_ >= 0) {
    fade_from_ = active_;
    fade_pos_ = 0;
    lift_fading_ = true;
  }
  active_ = slot;
  audio_active_.store(active_, std::memory_order_release);
  audio_fade_from_.store(fade_from_, std::memory_order_release);
  switches_done_.fetch_add(1, std::memory_order_acq_rel);
}

void KioskEngine::Render(float* interleaved, int frames, int channels) noexcept {
  const double fs_hz = options_.config.sample_rate_hz;
  if (const bool low = audio_low_vibration_.load(std::memory_order_acquire);
      low != safety_low_vibration_) {
    safety_low_vibration_ = low;
    safety_.SetCeilings(speaker_ceiling_,
                        transducer_ceiling_ * (low ? low_vibration_factor_ : 1.0));
  }
  const std::int64_t start_ns =
      options_.virtual_clock ? virtual_now_ns_ : platform::MonotonicNowNs();
  const int max_chunk = static_cast<int>(scratch_a_.size() / 2);
  for (int done = 0; done < frames; done += max_chunk) {
    const int n = std::min(max_chunk, frames - done);
    RenderChunk(interleaved + static_cast<std::ptrdiff_t>(done) * channels, n, channels,
                start_ns + static_cast<std::int64_t>(done * 1e9 / fs_hz));
  }
  if (options_.virtual_clock) {
    virtual_now_ns_ += static_cast<std::int64_t>(std::llround(frames * 1e9 / fs_hz));
  }
}

void KioskEngine::RenderSegment(float* out, int channels, int begin, int end,
                                int command_count) noexcept {
  const int frames = end - begin;
  if (frames <= 0) return;
  float* a = scratch_a_.data();
  float* b = scratch_b_.data();
  if (active_ >= 0) {
    slots_[static_cast<std::size_t>(active_)].scene.Process(block_commands_.data(), command_count,
                                                            a, frames);
  } else {
    std::fill(a, a + 2 * frames, 0.0f);
  }
  if (fade_from_ >= 0) {
    synth::ProbeCommand lift;
    lift.tip_down = false;
    auto& old = slots_[static_cast<std::size_t>(fade_from_)].scene;
    const auto state = old.probe_state();
    lift.x_m = state.x_m;
    lift.y_m = state.y_m;
    old.Process(&lift, lift_fading_ ? 1 : 0, b, frames);
    lift_fading_ = false;
    // Equal-power cross-fade: uncorrelated sounds keep their loudness through the switch.
    constexpr double kHalfPi = 1.5707963267948966;
    for (int i = 0; i < frames; ++i) {
      const double p = std::min(1.0, static_cast<double>(fade_pos_ + i) / fade_len_);
      const auto w_in = static_cast<float>(std::sin(kHalfPi * p));
      const auto w_out = static_cast<float>(std::cos(kHalfPi * p));
      a[2 * i] = a[2 * i] * w_in + b[2 * i] * w_out;
      a[2 * i + 1] = a[2 * i + 1] * w_in + b[2 * i + 1] * w_out;
    }
    fade_pos_ += frames;
    if (fade_pos_ >= fade_len_) {
      fade_from_ = -1;
      audio_fade_from_.store(-1, std::memory_order_release);
    }
  }
  if (playing_clip_ >= 0) {
    const auto& playing = clips_[static_cast<std::size_t>(playing_clip_)];
    const auto& clip = playing.samples;
    const std::size_t n = std::min(clip.size() - clip_pos_, static_cast<std::size_t>(frames));
    float* to = a + playing.channel;
    for (std::size_t i = 0; i < n; ++i) to[2 * i] += clip[clip_pos_ + i];
    clip_pos_ += n;
    if (clip_pos_ >= clip.size()) {
      playing_clip_ = -1;
      audio_clip_playing_.store(false, std::memory_order_relaxed);
    }
  }
  // Everything is mixed: the staff's volume and vibration, then the safety stage as the last step
  // (its ceilings hold for every source and every staff setting).
  const float sound_target = audio_staff_sound_.load(std::memory_order_relaxed);
  const float haptic_target = audio_staff_haptic_.load(std::memory_order_relaxed);
  float sound_gain = staff_sound_now_, haptic_gain = staff_haptic_now_;
  for (int i = 0; i < frames; ++i) {
    sound_gain += (sound_target - sound_gain) * staff_smooth_;
    haptic_gain += (haptic_target - haptic_gain) * staff_smooth_;
    a[2 * i] *= sound_gain;
    a[2 * i + 1] *= haptic_gain;
    safety_.Process(a + 2 * static_cast<std::ptrdiff_t>(i));
    speaker_energy_ += static_cast<double>(a[2 * i]) * a[2 * i];
    float* frame = out + static_cast<std::ptrdiff_t>(begin + i) * channels;
    for (int c = 0; c < channels; ++c) frame[c] = c < 2 ? a[2 * i + c] : 0.0f;
  }
  staff_sound_now_ = sound_gain;
  staff_haptic_now_ = haptic_gain;
  // The frames go out last, with release: a reader that sees them sees at least their energy.
  speaker_frames_ += static_cast<std::uint64_t>(frames);
  audio_speaker_energy_.store(speaker_energy_, std::memory_order_relaxed);
  audio_speaker_frames_.store(speaker_frames_, std::memory_order_release);
}

void KioskEngine::RenderChunk(float* out, int frames, int channels,
                              std::int64_t chunk_start_ns) noexcept {
  const double fs_hz = options_.config.sample_rate_hz;
  // A pen event from the last buffer period lands at the same place in this buffer: a constant
  // delay of one buffer (no jitter from when the callback happens to run). Older ones at 0.
  const double window_start_ns = static_cast<double>(chunk_start_ns) - frames * 1e9 / fs_hz;
  int segment_start = 0;
  int last_offset = 0;
  int count = 0;
  const int capacity = static_cast<int>(block_commands_.size());
  Message message;
  while (count < capacity && queue_.TryPop(message)) {
    const auto raw = static_cast<long long>(
        std::llround((static_cast<double>(message.time_ns) - window_start_ns) * fs_hz * 1e-9));
    const int offset = static_cast<int>(std::clamp<long long>(raw, last_offset, frames - 1));
    last_offset = offset;
    if (message.kind == Message::Kind::kProbe) {
      synth::ProbeCommand command = message.command;
      command.frame_offset = static_cast<std::uint32_t>(offset - segment_start);
      block_commands_[static_cast<std::size_t>(count++)] = command;
      commands_done_.fetch_add(1, std::memory_order_relaxed);
      // Due when it leaves the safety stage, kDelayFrames after the scene renders it.
      const std::int64_t due_ns =
          chunk_start_ns + static_cast<std::int64_t>(std::llround(
                               (offset + synth::SafetyStage::kDelayFrames) * 1e9 / fs_hz));
      const std::int64_t latency = due_ns - message.time_ns;
      latency_last_ns_.store(latency, std::memory_order_relaxed);
      if (latency > latency_max_ns_.load(std::memory_order_relaxed)) {
        latency_max_ns_.store(latency, std::memory_order_relaxed);
      }
      continue;
    }
    if (offset > segment_start) {  // else the commands so far go to the scene after the switch
      RenderSegment(out, channels, segment_start, offset, count);
      count = 0;
      segment_start = offset;
    }
    if (message.kind == Message::Kind::kSwitch) {
      ApplySwitchOnAudio(message.slot);
    } else if (message.slot >= 0 && message.slot < static_cast<int>(clips_.size())) {
      playing_clip_ = message.slot;
      clip_pos_ = 0;
      audio_clip_playing_.store(true, std::memory_order_relaxed);
    }
  }
  RenderSegment(out, channels, segment_start, frames, count);
}

}  // namespace sas::kiosk
