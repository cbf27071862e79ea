// Staff-recorded spoken cues (see staff_cues.h).
#include "kiosk/staff_cues.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "common/text.h"
#include "files/strings.h"
#include "surface/audio_file.h"
#include "surface/cue_library.h"

namespace sas::kiosk {
namespace {

using text::Fixed;
using text::Joined;

namespace fs = std::filesystem;

// What a file must be read from: a header claiming more is refused before anything is decoded
// (the kind's own bound, below, then applies to the trimmed sound).
constexpr double kMaxFileDurationS = 60.0;
// Speech recorded this quietly has to be raised by more than 27 dB to the cues' level, and the
// room and the microphone's noise come up with it: re-record it instead.
constexpr double kMinLoudnessLufs = -50.0;
// Its peaks hold a recording's gain below the cues' loudness (a knock or a click in it): beyond
// this shortfall it would be heard clearly quieter than every other cue.
constexpr double kMaxShortfallLu = 6.0;

std::string Lower(std::string text) {
  for (auto& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

std::vector<fs::path> SortedEntries(const fs::path& dir) {
  std::vector<fs::path> entries;
  std::error_code error;
  for (fs::directory_iterator it(dir, error), end; !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string();
    if (!name.empty() && name[0] != '.') entries.push_back(it->path());  // editors' dot files
  }
  std::sort(entries.begin(), entries.end());
  return entries;
}

// The recording at `path` for cue `key`, levelled; throws std::runtime_error saying why not.
StaffCue ReadRecording(const fs::path& path, const std::string& key, double fs_hz) {
  std::error_code error;
  if (fs::is_directory(path, error)) throw std::runtime_error("a folder, not a sound file");
  if (!fs::is_regular_file(path, error)) throw std::runtime_error("not a regular file");
  // libsndfile says only "System error" for a file it may not open; say what the staff can fix.
  if (std::ifstream probe(path, std::ios::binary); !probe) {
    throw std::runtime_error(std::string("cannot be opened (") + std::strerror(errno) +
                             "): the kiosk user needs read permission, e.g. chmod 644");
  }
  surface::AudioReadLimits limits;
  limits.target_rate_hz = fs_hz;
  limits.max_duration_s = kMaxFileDurationS;
  surface::AudioClip clip;
  try {
    clip = surface::ReadAudioFile(path.string(), limits);
  } catch (const std::exception& bad) {
    // The reader's message starts with the path, which the warning already names.
    std::string why = bad.what();
    const std::string prefix = "audio '" + path.string() + "': ";
    if (why.rfind(prefix, 0) == 0) why.erase(0, prefix.size());
    while (!why.empty() && why.back() == '.') why.pop_back();  // libsndfile's full stop
    throw std::runtime_error(why);
  }
  if (clip.silent) throw std::runtime_error("silent (its peak is below -80 dBFS)");
  if (clip.clipped_fraction > surface::kMaxCueClippedFraction) {
    throw std::runtime_error(Fixed(clip.clipped_fraction * 100.0, 2) +
                             " % of its samples are at full scale (clipped): record it again at "
                             "a lower level");
  }
  auto shaped = surface::ShapeCue(std::move(clip.samples), fs_hz);
  if (shaped.source_loudness_lufs < kMinLoudnessLufs) {
    throw std::runtime_error("too quiet to be speech (" + Fixed(shaped.source_loudness_lufs, 1) +
                             " LUFS, at least " + Fixed(kMinLoudnessLufs, 0) +
                             "): record it closer to the microphone or at a higher level");
  }
  const double shortfall_lu =
      surface::kCueLoudnessLufs - (shaped.source_loudness_lufs + shaped.gain_db);
  if (shortfall_lu > kMaxShortfallLu) {
    throw std::runtime_error(
        "its peaks are far above its speech (a knock or click?): it would "
        "play " +
        Fixed(shortfall_lu, 1) + " LU below the other cues");
  }
  const double duration_s = static_cast<double>(shaped.samples.size()) / fs_hz;
  const CueDurationLimits bounds = DurationLimitsFor(key);
  if (duration_s < bounds.min_s || duration_s > bounds.max_s) {
    throw std::runtime_error(Fixed(duration_s, 2) + " s of sound (silence trimmed); a " + key +
                             " cue must be " + Fixed(bounds.min_s, 2) + "-" +
                             Fixed(bounds.max_s, 1) + " s: " + bounds.why);
  }
  StaffCue cue;
  cue.path = path.string();
  cue.samples = std::move(shaped.samples);
  std::ifstream text(fs::path(path).replace_extension(".txt"));
  std::getline(text, cue.text);
  return cue;
}

}  // namespace

CueDurationLimits DurationLimitsFor(const std::string& key) {
  // Shortest: a single short word ("one", "drei"), not a click. A cue is cut off by the next one
  // the kiosk speaks (one plays at a time), which sets the longest.
  constexpr double kWord = 0.15;
  if (key.rfind("count_", 0) == 0) {
    return {kWord, 1.0, "the countdown's numbers are spoken a second apart"};
  }
  if (key == "record_countdown") {
    return {kWord, 2.0, "the countdown's first number follows it 2.1 s after the button press"};
  }
  if (key == "language" || (key.size() > 5 && key.compare(key.size() - 5, 5, "_name") == 0)) {
    return {kWord, 4.0, "a name is said at each token switch, and visitors switch quickly"};
  }
  return {kWord, 20.0,
          "a message or description is heard out while the visitor waits; longer ones are "
          "walked away from"};
}

StaffCueMap LoadStaffCues(const std::string& cues_dir, const std::vector<std::string>& languages,
                          const std::vector<std::string>& keys, double sample_rate_hz,
                          platform::Logger& log) {
  StaffCueMap found;
  std::error_code error;
  if (cues_dir.empty()) return found;
  if (!fs::exists(cues_dir, error)) {
    // Said once, so that a staff_dir the kiosk cannot see (a typo, or under /home, which the unit
    // hides) does not look like cues that were all taken.
    log.Info("cues", "no staff cues: " + cues_dir + " does not exist");
    return found;
  }
  const auto refuse = [&](const fs::path& path, const std::string& why,
                          const std::string& instead = "the synthetic cue is kept") {
    log.Warn("cues", "staff cue " + path.string() + " refused: " + why + "; " + instead);
  };
  if (!fs::is_directory(cues_dir, error)) {
    refuse(cues_dir, "not a folder (expected " + cues_dir + "/<language>/<cue key>.wav)");
    return found;
  }
  const auto& shipped = KioskLanguages();
  for (const auto& entry : SortedEntries(cues_dir)) {
    const std::string name = entry.filename().string();
    const bool language_dir = fs::is_directory(entry, error);
    if (language_dir && std::find(languages.begin(), languages.end(), name) != languages.end()) {
      continue;  // read below, in the kiosk's language order
    }
    if (language_dir && std::find(shipped.begin(), shipped.end(), name) != shipped.end()) {
      log.Info("cues", "staff cues in " + entry.string() + " not used: " + name +
                           " is not one of the kiosk's languages ([language] default, "
                           "visitor_choices)");
    } else if (language_dir) {
      refuse(entry, "no language the kiosk knows (" + Joined(shipped) + ")",
             "nothing in it is used");
    } else {
      refuse(entry, "not in a language folder (" + cues_dir + "/<language>/" + name + ")");
    }
  }
  for (const auto& language : languages) {
    const fs::path dir = fs::path(cues_dir) / language;
    std::vector<std::string> used;
    if (fs::is_directory(dir, error)) {
      auto& cues = found[language];
      for (const auto& path : SortedEntries(dir)) {
        const std::string key = path.stem().string();
        const std::string extension = path.extension().string();
        const bool known = std::find(keys.begin(), keys.end(), key) != keys.end();
        if (!known) {
          refuse(path, "\"" + key + "\" is no cue key (" + Joined(keys) + ")");
          continue;
        }
        if (Lower(extension) == ".txt") continue;  // a recording's sentence
        if (const auto other = cues.find(key); other != cues.end()) {
          refuse(path, "a second recording of " + key, other->second.path + " is used");
          continue;
        }
        try {
          cues[key] = ReadRecording(path, key, sample_rate_hz);
          used.push_back(key);
        } catch (const std::exception& bad) {
          refuse(path, bad.what());
        }
      }
    }
    log.Info("cues", language + ": " + std::to_string(used.size()) + " staff cue" +
                         (used.size() == 1 ? "" : "s") + " from " + dir.string() +
                         (used.empty() ? "" : " (" + Joined(used) + ")"));
  }
  return found;
}

}  // namespace sas::kiosk
