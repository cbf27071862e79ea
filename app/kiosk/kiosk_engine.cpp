// The kiosk engine (see kiosk_engine.h): textures, session, scene switches, voice slot, staff
// settings and counters, on the control thread (the pen side is kiosk_pen.cpp; the audio side is
// the player).
#include "kiosk/kiosk_engine.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <future>
#include <optional>
#include <stdexcept>

#include "files/atomic_file.h"
#include "files/counters_file.h"
#include "files/material_file.h"
#include "kiosk/pen_mapping.h"
#include "levels/output_gains.h"
#include "platform/common/clock.h"
#include "platform/common/no_dump_buffer.h"
#include "platform/log/log.h"
#include "surface/image_surface.h"
#include "surface/sound_image.h"

namespace sas::kiosk {
namespace {

namespace fs = std::filesystem;

constexpr double kCountersSaveIntervalS = 10.0;

float StaffGain(double db) {
  return static_cast<float>(std::pow(10.0, db / 20.0));
}

}  // namespace

KioskEngine::KioskEngine(KioskEngineOptions options)
    : options_(std::move(options)), session_(SessionConfig{}) {
  LoadTextures();
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

  std::string cues_dir;
  if (options_.spoken_cues) {
    cues_dir = options_.cues_dir.empty() ? FindCuesDir() : options_.cues_dir;
  }
  KioskConfig cue_config = options_.config;
  if (!options_.staff_cues) cue_config.staff_dir.clear();
  cues_ = SpokenCues(cue_config,
                     options_.strings_dir.empty() ? FindStringsDir() : options_.strings_dir,
                     std::move(cues_dir), options_.spoken_cues, texture_keys_, texture_dirs_);
  SessionConfig session;
  session.texture_count = static_cast<int>(textures_.size());
  session.default_texture = default_texture_;
  session.idle_timeout_s = options_.config.idle_timeout_s;
  session.countdown_s = options_.countdown_s;
  session.record_max_s = options_.config.record_max_duration_s;
  session.staff_panel_timeout_s = options_.config.staff_panel_timeout_s;
  // The attract cycle's slots follow the invitations' lengths (spoken_cues.h).
  session.attract_slots_s = cues_.AttractSlotsS(options_.config.invitation_interval_s);
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

  if (!options_.staff_settings_path.empty()) {
    StaffSettingsLoad staff_load = LoadStaffSettings(options_.staff_settings_path);
    if (!staff_load.report.empty()) platform::DefaultLogger().Warn("staff", staff_load.report);
    staff_may_save_ = staff_load.may_save;
    staff_ = staff_load.settings;
    low_vibration_ = staff_.low_vibration;
  }
  player::PlayerSetup setup;
  setup.sample_rate_hz = options_.config.sample_rate_hz;
  setup.max_block_frames = options_.max_block_frames;
  setup.cross_fade_s = options_.cross_fade_s;
  if (!options_.virtual_clock) setup.now_ns = &platform::MonotonicNowNs;
  setup.speaker_ceiling = std::pow(10.0, options_.config.sound_ceiling_db / 20.0);
  setup.transducer_ceiling = std::pow(10.0, options_.config.haptic_ceiling_db / 20.0);
  setup.low_vibration_factor = std::pow(10.0, -options_.config.low_vibration_db / 20.0);
  setup.low_vibration = low_vibration_;
  setup.transducer_resonance_hz = options_.config.transducer_resonance_hz;
  setup.transducer_q = options_.config.transducer_q;
  // A restart comes up at the kept staff levels, not fading into them.
  setup.staff_sound_gain = StaffGain(staff_.volume_db);
  setup.staff_haptic_gain = StaffGain(staff_.vibration_db);
  const auto prepare_first = [this](synth::Scene& scene) {
    PrepareScene({false, default_texture_}, 0, scene);
  };
  player_ = std::make_unique<player::Player>(setup, cues_.TakeClipSamples(), prepare_first);
  audio_face_.player = &player_->audio();
}

void KioskEngine::LoadTextures() {
  if (options_.texture_paths.empty()) {
    // The tokens' textures as configured ([textures], the staff's own first), each with the
    // shipped texture of its place to fall back on.
    options_.texture_fallbacks.clear();
    for (const auto& token :
         ResolveTokenTextures(options_.config.token_textures, options_.config.staff_dir)) {
      options_.texture_paths.push_back(token.path.empty() ? token.fallback : token.path);
      options_.texture_fallbacks.push_back(token.path.empty() ? "" : token.fallback);
      staff_texture_.push_back(token.staff && !token.path.empty());
    }
    if (std::find(options_.texture_paths.begin(), options_.texture_paths.end(), "") !=
        options_.texture_paths.end()) {
      options_.texture_paths = FindTextureFiles();  // throws, saying where it looked
    }
  }
  staff_texture_.resize(options_.texture_paths.size(), false);
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
  // A texture and its material: a texture's own folder holds a material made for it.
  const auto complete = [&](const std::string& path, surface::LoadedTexture loaded, bool staff) {
    EngineTexture texture;
    texture.key = fs::path(path).parent_path().filename().string();
    texture.loaded = std::move(loaded);
    std::vector<std::string> search = dirs;
    search.insert(search.begin(), fs::path(path).parent_path().string());
    texture.material = FindMaterial(texture.loaded.file.material, search);
    // A staff texture is the curator's work: one never calibrated would play at its own level,
    // not matched to the others (texture new calibrates it; texture check says so).
    if (staff && !texture.loaded.file.levels) {
      throw std::runtime_error("it has no [levels] table (not calibrated: make it with "
                               "`sketch-a-scratch texture new`)");
    }
    return texture;
  };
  const auto fallbacks = options_.texture_fallbacks;
  std::string first_failure;
  for (std::size_t i = 0; i < pending.size(); ++i) {
    const std::string& path = options_.texture_paths[i];
    std::string key = fs::path(path).parent_path().filename().string();
    token_texture_.push_back(-1);
    std::optional<EngineTexture> texture;
    std::string loaded_from = path;
    try {
      texture = complete(path, pending[i].get(), staff_texture_[i]);
    } catch (const std::exception& error) {
      const std::string fallback = i < fallbacks.size() ? fallbacks[i] : "";
      const std::string token = "token " + std::to_string(i + 1);
      if (!fallback.empty()) {
        // The staff's texture is refused where they look (the journal); the token still shows
        // a texture, the shipped one of its place.
        platform::DefaultLogger().Warn(
            "textures", std::string(staff_texture_[i] ? "staff texture " : "texture ") + path +
                            " refused: " + error.what() + "; " + token + " shows the shipped " +
                            fs::path(fallback).parent_path().filename().string() + " instead");
        try {
          texture = complete(fallback, surface::LoadTexture(fallback, load), false);
          key = texture->key;
          loaded_from = fallback;
        } catch (const std::exception& also) {
          texture_failures_.push_back(key + ": " + also.what());
          if (first_failure.empty()) first_failure = also.what();
        }
      } else {
        texture_failures_.push_back(key + ": " + error.what());
        if (first_failure.empty()) first_failure = error.what();
        platform::DefaultLogger().Error(
            "textures", key + " left out (its token shows the default texture): " + error.what());
      }
    }
    counter_keys_.push_back(key);
    if (!texture) continue;
    if (texture->loaded.bubbles) bubble_texture_ = static_cast<int>(textures_.size());
    token_texture_.back() = static_cast<int>(textures_.size());
    texture_keys_.push_back(texture->key);
    texture_dirs_.push_back(fs::path(loaded_from).parent_path().string());
    textures_.push_back(std::move(*texture));
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
  if (found == texture_keys_.end()) {
    // A curator's texture took the default's token: the idle screen shows what that token shows.
    // A staff texture named as the default but refused: what its token shows instead.
    const auto shipped = KioskTextureNames();
    const auto& tokens = options_.config.token_textures;
    const auto place = std::find(shipped.begin(), shipped.end(), options_.config.default_texture);
    auto token = static_cast<std::size_t>(place - shipped.begin());
    if (place == shipped.end()) {
      token = static_cast<std::size_t>(
          std::find(tokens.begin(), tokens.end(), options_.config.default_texture) -
          tokens.begin());
    }
    if (token < token_texture_.size() && token_texture_[token] >= 0) {
      default_texture_ = token_texture_[token];
    }
  }
}

KioskEngine::~KioskEngine() {
  std::string error;
  SaveCounters(&error);
  recorder_ = nullptr;  // may already be gone: its owner wipes it
  WipeVoice();
}

// ---------------------------------------------------------------------------- cues and clips

void KioskEngine::PlayCue(const CuePick& pick) {
  if (pick.clip < 0) return;  // no file: carry on silently (the screen still says it)
  Play(pick.clip);
  if (cue_observer_) {
    cue_observer_({last_now_ns_, cues_.strings().code, pick.key, cues_.clip_text(pick.clip)});
  }
}

bool KioskEngine::NextLanguage(std::int64_t now_ns) {
  last_now_ns_ = std::max(last_now_ns_, now_ns);
  // On the attract screen the key chooses the language its texts and invitation are in now: a
  // visitor who has just read or heard their own language gets it with one press.
  const bool choose_shown = session_.mode() == SessionMode::kAttract && cues_.attract_cycles();
  if (!choose_shown && !cues_.NextLanguage()) return false;
  keep_language_ = true;  // leaving the attract screen this way keeps the choice
  ++language_choices_;
  session_.OnVisitorActivity(static_cast<double>(now_ns) * 1e-9);
  PlayCue(cues_.ForMessage("language"));  // in the new language: its own name
  return true;
}

std::string KioskEngine::TextureName(int texture) const {
  const auto t = static_cast<std::size_t>(std::clamp(texture, 0, int(textures_.size()) - 1));
  // A curator's texture names itself in the languages it was made for.
  const auto& names = textures_[t].loaded.file.names;
  if (const auto own = names.find(cues_.strings().code); own != names.end()) return own->second;
  return cues_.strings().CueText(texture_keys_[t] + "_name", textures_[t].loaded.file.name);
}

void KioskEngine::Play(int clip) {
  player_->control().Play(last_now_ns_, clip);
}

void KioskEngine::PlayTestTone() {
  Play(cues_.tone_clip());
}
void KioskEngine::PlayTransducerSweep() {
  Play(cues_.sweep_clip());
}

// ---------------------------------------------------------------------------- session

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
  auto& control = player_->control();
  // A pen held still sends few or no reports (a mouse none at all): the rest is timed here.
  if (rest_since_ns_ >= 0 && !rest_spoken_ && options_.config.describe_after_rest_s > 0.0 &&
      static_cast<double>(now_ns - rest_since_ns_) * 1e-9 >=
          options_.config.describe_after_rest_s) {
    rest_spoken_ = true;
    session_.OnPenRest(now_s);
  }
  session_.Tick(now_s);
  {
    const player::SpeakerTotals speaker = control.speaker();
    exposure_.Update(now_ns, speaker.energy, speaker.frames,
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
  const bool acknowledged = control.SwitchTaken();
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
  if (release_idle_slots_ && !pending_surface_ && control.Settled()) {
    // The idle reset has faded over to the default texture: the other slots' fields (the wiped
    // voice, flattened bubble wrap copies, the visit's textures) are let go, so an idle kiosk
    // holds the same memory after every visit and no voice lingers in a scene.
    release_idle_slots_ = false;
    for (int slot = 0; slot < player::kSceneSlots; ++slot) {
      if (!control.SlotInUse(slot)) slot_fields_[static_cast<std::size_t>(slot)].reset();
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
        PlayCue(cues_.ForAction(action));
        break;
      case Kind::kStartRecording:
        if (!recorder_present()) {
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
        cues_.ResetLanguage();  // the next visitor hears the configured language
        break;
      case Kind::kAttractLanguage:
        cues_.SetAttractLanguage(action.count);  // before its invitation (the next action)
        break;
      case Kind::kLeaveAttract:
        // A visit started by anything but the language key is in the configured language (the
        // attract cycle may have been showing any); the key chose one itself.
        if (!keep_language_) cues_.ResetLanguage();
        keep_language_ = false;
        break;
      case Kind::kStaffPanel:
        break;  // the UI's business
    }
  }
}

void KioskEngine::SetMicrophoneLive(std::int64_t now_ns, bool live) {
  if (live == microphone_live_) return;
  microphone_live_ = live;
  if (!live && recording_) {
    recording_ = false;
    if (recorder_) recorder_->Wipe();
    session_.OnRecordingFinished(static_cast<double>(now_ns) * 1e-9,
                                 RecordingOutcome::kNoMicrophone);
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
  // Speech is peaky: scaled to its single loudest sample, most of the take sits near mid-grey
  // and a light stroke, which feels only the top of the relief, feels none of it. The loudest
  // tenth clips to white and black instead, so the voice fills the picture and the relief.
  image.level_quantile = 0.9;
  return image;
}

RecordingOutcome KioskEngine::AcceptRecording(std::int64_t /*now_ns*/,
                                              std::span<const float> samples) {
  // The sound image is the recording row by row, and the field is that image as heights: both
  // are the visitor's voice, so they are made (and released, zeroed) in memory a core dump
  // leaves out. They are constructed in place, never assigned (height_field.h). So is the
  // speech cut out of the take: the picture shows the voice, not the wait before it or the
  // pauses in it (a late start left most of the rows flat grey).
  std::pmr::memory_resource* memory = platform::NoDumpMemory();
  RecordingOutcome outcome = RecordingOutcome::kOk;
  try {
    const std::pmr::vector<float> speech =
        surface::TrimToSpeech(samples, options_.config.sample_rate_hz, {}, memory);
    const surface::SoundImageOptions image = VoiceImageOptions(
        options_.config.sample_rate_hz, options_.config.record_max_duration_s, speech.size());
    surface::HeightField field = surface::SoundToHeightField(
        speech, image, kVoiceReliefMm, surface::DisplayGeometry{}.pixel_pitch_mm(), memory);
    voice_image_.reset();
    voice_image_.emplace(surface::SoundToImage(speech, image, memory));
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
  auto& control = player_->control();
  // One switch in flight at a time: the slot bookkeeping needs the audio side to have taken the
  // last one (with the device stopped, that waits until it runs again).
  if (!control.SwitchTaken()) {
    pending_surface_ = choice;
    return;
  }
  const int slot = control.FreeSlot();
  if (slot < 0 || !PrepareScene(choice, slot, control.scene(slot))) return;
  if (!control.Switch(last_now_ns_, slot)) pending_surface_ = choice;  // queue full: next Tick
}

StrokeCorrection KioskEngine::CorrectionFor(int texture) const {
  if (!stroke_.valid()) return {};
  return stroke_gains_.Correction(texture, stroke_style_, stroke_width_mm_, stroke_.speed_mm_s(),
                                  stroke_.pressure());
}

bool KioskEngine::PrepareScene(const SurfaceChoice& choice, int slot, synth::Scene& scene) {
  std::shared_ptr<const surface::HeightField> field;
  const Material* material = &voice_material_;
  surface::TextureGains gains{};
  int texture = -1;
  if (choice.voice) {
    field = voice_.Recall(kVoiceSlot);
    if (!field) return false;
  } else {
    const auto& loaded = textures_[static_cast<std::size_t>(choice.texture)];
    field = loaded.loaded.bubbles ? loaded.loaded.bubbles->field() : loaded.loaded.field;
    material = &loaded.material;
    gains = loaded.loaded.file.gains;
    texture = choice.texture;
  }
  // Configuration + texture loudness-matching gains + the ambient gain, the transducer ceiling and
  // the staff's low-vibration mode: one builder for every path (output_gains.h).
  const synth::OutputParams output =
      KioskOutputParams(options_.config, gains, ambient_gain_db_, low_vibration_);
  ambient_gain_applied_db_ = ambient_gain_db_;
  auto& kept = slot_fields_[static_cast<std::size_t>(slot)];
  kept = field;
  // The new scene starts at the correction for the last stroke (Prepare takes it at once).
  stroke_texture_ = texture;
  stroke_correction_ = CorrectionFor(texture);
  scene.SetStrokeGains(std::pow(10.0, stroke_correction_.sound_db / 20.0),
                       std::pow(10.0, stroke_correction_.haptic_db / 20.0));
  if (passive_down_) {
    const double gain = std::pow(10.0, kPassiveGainDb / 20.0);  // the passive stroke goes on
    scene.SetStrokeGains(gain, gain);
  }
  scene.Prepare(material->params, output, kept->View());
  current_field_ = std::move(field);
  current_relief_m_ = surface::ReliefM(*current_field_);
  return true;
}

void KioskEngine::SetAudioRunning(bool running) {
  player_->control().SetDeviceRunning(running, last_now_ns_);
}

void KioskEngine::SetLowVibration(bool on) {
  // Every prepared scene follows at once (an atomic each scene reads per block, 20 ms ramp);
  // scenes prepared later get it through their output parameters.
  low_vibration_ = on;
  if (staff_.low_vibration != on) {
    staff_.low_vibration = on;
    SaveStaffSettings();
  }
  player_->control().SetLowVibration(on);
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
  player_->control().SetStaffGains(StaffGain(staff_.volume_db), StaffGain(staff_.vibration_db));
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

UsageCounters KioskEngine::PersistedCounters() const {
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
  return all;
}

bool KioskEngine::SaveCounters(std::string* error) const {
  if (options_.counters_path.empty()) return true;
  if (!counters_may_save_) {
    // Reported once at start: a damaged file that could not be moved aside is never replaced.
    if (error) *error = options_.counters_path + " is damaged and could not be moved aside";
    return false;
  }
  const UsageCounters all = PersistedCounters();
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
  return player_->control().stats();
}

}  // namespace sas::kiosk
