// Spoken cue files -> RAM (see cue_library.h).
#include "surface/cue_library.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <filesystem>
#include <numbers>
#include <stdexcept>

#include "surface/audio_file.h"
#include "surface/loudness.h"

namespace sas::surface {
std::string CueLevelProblem(const AudioClip& clip) {
  if (clip.clipped_fraction <= kMaxCueClippedFraction) return {};
  return std::to_string(clip.clipped_fraction * 100.0) +
         " % of the samples at or beyond full scale (a damaged file)";
}

ShapedCue ShapeCue(std::vector<float> x, double rate_hz) {
  float peak = 0.0f;
  for (float v : x) peak = std::max(peak, std::fabs(v));
  if (peak <= 0.0f) throw std::runtime_error("silence: no sample above zero");
  const float floor = peak * static_cast<float>(std::pow(10.0, kCueTrimBelowPeakDb / 20.0));
  // A sample is sound when it passes the floor and so does the 10 ms around it, within 12 dB: a
  // lone click in a silent stretch (a codec's or a recorder's) does not hold the trim open, which
  // could leave a count twice as long as its word.
  std::vector<double> energy(x.size() + 1, 0.0);
  for (std::size_t i = 0; i < x.size(); ++i) {
    energy[i + 1] = energy[i] + static_cast<double>(x[i]) * static_cast<double>(x[i]);
  }
  const auto half = std::max<std::size_t>(1, static_cast<std::size_t>(0.005 * rate_hz));
  const double floor_rms = 0.25 * static_cast<double>(floor);
  // The window keeps its length at the ends (moved inside), so a codec's loud last samples are
  // judged against 10 ms too.
  const std::size_t window = std::min(x.size(), 2 * half + 1);
  const auto sound = [&](std::size_t i) {
    if (std::fabs(x[i]) < floor) return false;
    const std::size_t a = std::min(i > half ? i - half : 0, x.size() - window);
    return (energy[a + window] - energy[a]) / static_cast<double>(window) >=
           floor_rms * floor_rms;
  };
  std::size_t first = 0, last = x.size();
  while (first < x.size() && !sound(first)) ++first;
  while (last > first && !sound(last - 1)) --last;
  if (first == last) throw std::runtime_error("silence: nothing sustained above the trim floor");
  const auto margin = static_cast<std::size_t>(kCueMarginS * rate_hz);
  first = first > margin ? first - margin : 0;
  last = std::min(x.size(), last + margin);
  x = std::vector<float>(x.begin() + static_cast<std::ptrdiff_t>(first),
                         x.begin() + static_cast<std::ptrdiff_t>(last));

  ShapedCue shaped;
  shaped.source_loudness_lufs = KWeightedLoudnessDb(x, rate_hz, 0, x.size());
  double gain_db = kCueLoudnessLufs - shaped.source_loudness_lufs;
  // The trimmed signal keeps the peak found above.
  gain_db = std::min(gain_db, kCuePeakDbfs - 20.0 * std::log10(static_cast<double>(peak)));
  shaped.gain_db = gain_db;
  const double gain = std::pow(10.0, gain_db / 20.0);
  const auto fade = static_cast<std::size_t>(kCueFadeS * rate_hz);
  for (std::size_t i = 0; i < x.size(); ++i) {
    double w = 1.0;
    const std::size_t edge = std::min(i, x.size() - 1 - i);
    if (edge < fade) {
      w = 0.5 -
          0.5 * std::cos(std::numbers::pi * static_cast<double>(edge) / static_cast<double>(fade));
    }
    x[i] = static_cast<float>(x[i] * gain * w);
  }
  shaped.samples = std::move(x);
  return shaped;
}

const std::vector<std::string>& MessageCueNames() {
  static const std::vector<std::string> names = {
      "record_countdown", "count_3",       "count_2",     "count_1",    "too_quiet",
      "too_loud",         "no_microphone", "voice_ready", "invitation", "language"};
  return names;
}

std::vector<std::string> ExpectedCueFiles(const std::vector<std::string>& texture_folders) {
  std::vector<std::string> files;
  for (const auto& folder : texture_folders) {
    files.push_back(folder + "_name.wav");
    files.push_back(folder + "_description.wav");
  }
  for (const auto& name : MessageCueNames()) files.push_back(name + ".wav");
  return files;
}

CueLibrary CueLibrary::Load(const std::string& dir, const std::vector<std::string>& texture_folders,
                            double sample_rate_hz) {
  CueLibrary library;
  library.sample_rate_hz_ = sample_rate_hz;
  AudioReadLimits limits;
  limits.target_rate_hz = sample_rate_hz;
  limits.max_duration_s = 30.0;  // a cue is a sentence; anything longer is not one of ours
  for (const auto& file : ExpectedCueFiles(texture_folders)) {
    const std::filesystem::path path = std::filesystem::path(dir) / file;
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) {
      library.problems_.push_back(path.string() + ": missing (spoken cue not generated? " +
                                  "the build needs espeak-ng)");
      continue;
    }
    try {
      AudioClip clip = ReadAudioFile(path.string(), limits);
      if (clip.silent) {
        library.problems_.push_back(path.string() + ": silent");
        continue;
      }
      if (const std::string problem = CueLevelProblem(clip); !problem.empty()) {
        library.problems_.push_back(path.string() + ": " + problem);
        continue;
      }
      library.cues_[file.substr(0, file.size() - 4)] = std::move(clip.samples);
    } catch (const std::exception& e) {
      library.problems_.push_back(path.string() + ": " + e.what());
    }
  }
  return library;
}

const std::vector<float>* CueLibrary::Find(const std::string& name) const {
  const auto it = cues_.find(name);
  return it == cues_.end() ? nullptr : &it->second;
}

const std::vector<float>* CueLibrary::TextureName(const std::string& folder) const {
  return Find(folder + "_name");
}

const std::vector<float>* CueLibrary::TextureDescription(const std::string& folder) const {
  return Find(folder + "_description");
}

}  // namespace sas::surface
