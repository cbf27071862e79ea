// The kiosk's languages and spoken cues (see spoken_cues.h).
#include "kiosk/spoken_cues.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "kiosk/staff_cues.h"
#include "platform/log/log.h"
#include "surface/audio_file.h"
#include "surface/cue_library.h"

namespace sas::kiosk {
namespace {

namespace fs = std::filesystem;

const char* CueKey(Cue cue) {
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

}  // namespace

SpokenCues::SpokenCues(const KioskConfig& config, const std::string& strings_dir,
                       std::string cues_dir, bool spoken_cues,
                       std::vector<std::string> texture_keys,
                       std::vector<std::string> texture_dirs)
    : cues_dir_(std::move(cues_dir)),
      texture_keys_(std::move(texture_keys)),
      texture_dirs_(std::move(texture_dirs)) {
  LoadLanguages(config, strings_dir);
  LoadCues(config, spoken_cues);
}

int SpokenCues::AddClip(std::string name, std::vector<float> mono, int channel) {
  clips_.push_back({std::move(name), {}});
  clip_samples_.push_back({std::move(mono), channel});
  return static_cast<int>(clips_.size()) - 1;
}

void SpokenCues::LoadLanguages(const KioskConfig& config, const std::string& strings_dir) {
  // The configured language first (index 0 is the one an idle reset returns to), then the
  // visitor's choices in their order.
  std::vector<std::string> codes = {config.language};
  for (const auto& code : config.visitor_languages) {
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
    if (std::find(config.visitor_languages.begin(), config.visitor_languages.end(), code) !=
        config.visitor_languages.end()) {
      visitor_languages_.push_back(static_cast<int>(i));
    }
  }
  if (std::find(config.visitor_languages.begin(), config.visitor_languages.end(),
                config.language) != config.visitor_languages.end()) {
    visitor_languages_.insert(visitor_languages_.begin(), 0);
  }
  attract_languages_ = {0};
  if (visitor_languages_.size() >= 2) {
    for (const int language : visitor_languages_) {
      if (language != 0) attract_languages_.push_back(language);
    }
  }
}

void SpokenCues::LoadCues(const KioskConfig& config, bool spoken_cues) {
  const double fs_hz = config.sample_rate_hz;
  // Staff recordings replace the synthetic cue of their language and key (staff_cues.h).
  StaffCueMap staff;
  if (spoken_cues && !config.staff_dir.empty()) {
    std::vector<std::string> codes, keys(CueKeys());
    for (const auto& language : languages_) codes.push_back(language.table.code);
    for (const auto& key : texture_keys_) {
      keys.push_back(key + "_name");
      keys.push_back(key + "_description");
    }
    staff = LoadStaffCues((fs::path(config.staff_dir) / kStaffCuesFolder).string(), codes, keys,
                          fs_hz, platform::DefaultLogger());
  }
  // A curator's texture brings its own name and description cues; the staff's recordings of
  // the same keys (above) come first.
  if (spoken_cues) {
    std::vector<std::string> codes;
    for (const auto& language : languages_) codes.push_back(language.table.code);
    for (std::size_t t = 0; t < texture_dirs_.size() && t < texture_keys_.size(); ++t) {
      const fs::path own = fs::path(texture_dirs_[t]) / kStaffCuesFolder;
      std::error_code error;
      if (texture_dirs_[t].empty() || !fs::is_directory(own, error)) continue;
      const std::string& key = texture_keys_[t];
      // Its refusals reach the journal; the per-language counts would only repeat what
      // `texture check` said when it was installed.
      platform::Logger quiet;
      quiet.SetEchoToStderr(false);
      auto found = LoadStaffCues(own.string(), codes, {key + "_name", key + "_description"}, fs_hz,
                                 quiet);
      for (const auto& line : quiet.Recent()) {
        if (line.level >= platform::LogLevel::kWarn) {
          platform::DefaultLogger().Warn(line.component, line.message);
        }
      }
      for (auto& [code, cues] : found) {
        for (auto& [cue_key, cue] : cues) staff[code].emplace(cue_key, std::move(cue));
      }
    }
  }
  const LanguageTable* table = nullptr;  // the language being loaded
  const auto load = [&](const fs::path& dir, const std::string& key) -> int {
    if (const auto language = staff.find(table->code); language != staff.end()) {
      if (const auto found = language->second.find(key); found != language->second.end()) {
        const int index = AddClip(key, std::move(found->second.samples), 0);
        // Without a .txt of their own, the sentence is the table's, which the synthetic cue's
        // .txt holds (the table has no English texture names: those are texture.toml's).
        std::string& text = clips_.back().text;
        text = found->second.text;
        if (text.empty() && !cues_dir_.empty()) {
          std::ifstream synthetic(dir / (key + ".txt"));
          std::getline(synthetic, text);
        }
        if (text.empty()) text = table->CueText(key);
        ++staff_cues_;
        return index;
      }
    }
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
      if (l != 0 && !staff.count(language.table.code)) continue;
      if (l == 0) dir = cues_dir_;
    }
    table = &language.table;
    for (const auto& key : texture_keys_) {
      language.name_cues.push_back(load(dir, key + "_name"));
      language.description_cues.push_back(load(dir, key + "_description"));
    }
    for (const auto& key : CueKeys()) language.message_cues[key] = load(dir, key);
    if (const int clip = language.message_cues["invitation"]; clip >= 0) {
      language.invitation_s =
          static_cast<double>(clip_samples_[static_cast<std::size_t>(clip)].samples.size()) / fs_hz;
    }
    expected += static_cast<int>(texture_keys_.size() * 2 + CueKeys().size());
  }
  // For a blind visitor the cues are the only way to know which texture is under the pen: a box
  // without them must say so where staff look (journal at warning, staff panel's CUES line).
  if (spoken_cues) {
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
  // 40 -> 400 Hz (the skin's band, which the vibration path uses) at -6 dBFS on ch 2. 10 ms
  // raised-cosine edges.
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
    const double f0 = 40.0, f1 = 400.0, length_s = 2.0;
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

std::vector<player::PlayerClip> SpokenCues::TakeClipSamples() {
  return std::move(clip_samples_);
}

int SpokenCues::cues_loaded() const {
  return static_cast<int>(clips_.size()) - 3;  // minus the test signals and the record tone
}

CuePick SpokenCues::ForAction(const SessionAction& action) const {
  if (action.cue == Cue::kCount) {
    return ForMessage("count_" + std::to_string(std::clamp(action.count, 1, 3)));
  }
  if (action.cue == Cue::kRecordTone) return {record_tone_clip_, "tone"};
  return ForCue(action.cue, action.surface.texture);
}

CuePick SpokenCues::ForCue(Cue cue, int texture) const {
  const auto& language = languages_[static_cast<std::size_t>(language_)];
  const auto t = static_cast<std::size_t>(std::clamp(texture, 0, int(texture_keys_.size()) - 1));
  if (cue == Cue::kTextureName) {
    return {t < language.name_cues.size() ? language.name_cues[t] : -1, texture_keys_[t] + "_name"};
  }
  if (cue == Cue::kTextureDescription) {
    return {t < language.description_cues.size() ? language.description_cues[t] : -1,
            texture_keys_[t] + "_description"};
  }
  return ForMessage(CueKey(cue));
}

CuePick SpokenCues::ForMessage(const std::string& key) const {
  const auto& cues = languages_[static_cast<std::size_t>(language_)].message_cues;
  const auto found = cues.find(key);
  return {found == cues.end() ? -1 : found->second, key};
}

bool SpokenCues::NextLanguage() {
  if (visitor_languages_.size() < 2) return false;
  const auto at = std::find(visitor_languages_.begin(), visitor_languages_.end(), language_);
  language_ = at == visitor_languages_.end() || at + 1 == visitor_languages_.end()
                  ? visitor_languages_.front()
                  : *(at + 1);
  return true;
}

std::vector<double> SpokenCues::AttractSlotsS(double quiet_s) const {
  std::vector<double> slots;
  if (quiet_s <= 0.0) return slots;
  double cycle_s = 0.0;
  for (const int language : attract_languages_) {
    const double spoken_s = languages_[static_cast<std::size_t>(language)].invitation_s;
    slots.push_back(spoken_s > 0.0 ? spoken_s + quiet_s : kNoInvitationSlotS);
    cycle_s += slots.back();
  }
  if (cycle_s < kMinAttractCycleS) {
    for (auto& slot : slots)
      slot += (kMinAttractCycleS - cycle_s) / static_cast<double>(slots.size());
  }
  return slots;
}

void SpokenCues::SetAttractLanguage(int slot) {
  if (attract_languages_.empty()) return;
  language_ = attract_languages_[static_cast<std::size_t>(slot) % attract_languages_.size()];
}

const LanguageTable& SpokenCues::strings() const {
  return languages_[static_cast<std::size_t>(language_)].table;
}

const std::string& SpokenCues::clip_text(int clip) const {
  return clips_[static_cast<std::size_t>(clip)].text;
}

}  // namespace sas::kiosk
