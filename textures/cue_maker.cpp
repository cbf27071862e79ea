// cue_maker: speaks the kiosk's spoken cues with espeak-ng at build time (for visitors who cannot
// see the screen), in every language of textures/strings/ (files/strings.h). For each language
// <code> it writes <out>/<code>/<key>.wav and, next to it, <key>.txt with the sentence it spoke
// (the kiosk reports it with each cue it plays, so a test can check what was heard against the
// string table). Keys: each message of the table's [cues], and for each texture folder in
// <textures_dir> (a texture.toml inside) <folder>_name and <folder>_description: from the table's
// [textures], else the texture.toml's own (English) name and description. Chain per cue:
//   espeak-ng -v <voice> -s <wpm> -w tmp.wav "<text>"  (22.05 kHz)
//   -> surface::ReadAudioFile: mono, windowed-sinc resampled to 48 kHz
//   -> trim leading/trailing silence (below -40 dB re the peak), keep 20 ms either side
//   -> loudness-normalise to kCueLoudnessLufs (BS.1770 K-weighted, surface/loudness.h), then
//      lower further if needed so the peak stays at or below kCuePeakDbfs (never clipped)
//   -> 5 ms raised-cosine fades -> 24-bit PCM WAV, 48 kHz mono.
// Normalising here, in our own code, keeps the build free of sox.
//
// Usage: cue_maker --espeak <path> --strings <dir> --textures-dir <dir> --out <dir>

#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "files/strings.h"
#include "surface/audio_file.h"
#include "surface/cue_library.h"
#include "surface/loudness.h"
#include "surface/texture_file.h"
#include "surface/wav_writer.h"

extern char** environ;

namespace {

namespace fs = std::filesystem;

constexpr double kRateHz = 48000.0;
// EBU R 128's programme target: a cue sits at the level of broadcast speech; the exhibit's strokes
// at the kiosk's default gains are about -24 LUFS (calibration/texture_levels.h), so cues and
// textures are heard at a similar level.
constexpr double kCueLoudnessLufs = -23.0;
constexpr double kCuePeakDbfs = -1.0;
constexpr double kTrimBelowPeakDb = -40.0;
constexpr double kMarginS = 0.02;
constexpr double kFadeS = 0.005;

struct Cue {
  std::string key;  // file name without .wav
  std::string text;
};

void Speak(const std::string& espeak, const std::string& voice, int wpm, const std::string& text,
           const std::string& wav_path) {
  const std::string speed = std::to_string(wpm);
  std::vector<std::string> args = {espeak, "-v", voice, "-s", speed, "-w", wav_path, text};
  std::vector<char*> argv;
  for (auto& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, espeak.c_str(), nullptr, nullptr, argv.data(), environ) != 0) {
    throw std::runtime_error("cannot run " + espeak);
  }
  int status = 0;
  if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error(espeak + " failed for \"" + text + "\"");
  }
}

std::vector<float> Shape(std::vector<float> x) {
  float peak = 0.0f;
  for (float v : x) peak = std::max(peak, std::fabs(v));
  if (peak <= 0.0f) throw std::runtime_error("espeak-ng produced silence");
  const float floor = peak * static_cast<float>(std::pow(10.0, kTrimBelowPeakDb / 20.0));
  std::size_t first = 0, last = x.size();
  while (first < x.size() && std::fabs(x[first]) < floor) ++first;
  while (last > first && std::fabs(x[last - 1]) < floor) --last;
  const auto margin = static_cast<std::size_t>(kMarginS * kRateHz);
  first = first > margin ? first - margin : 0;
  last = std::min(x.size(), last + margin);
  x = std::vector<float>(x.begin() + static_cast<std::ptrdiff_t>(first),
                         x.begin() + static_cast<std::ptrdiff_t>(last));

  const double loudness = sas::surface::KWeightedLoudnessDb(x, kRateHz, 0, x.size());
  double gain_db = kCueLoudnessLufs - loudness;
  double new_peak = 0.0;
  for (float v : x) new_peak = std::max(new_peak, static_cast<double>(std::fabs(v)));
  gain_db = std::min(gain_db, kCuePeakDbfs - 20.0 * std::log10(new_peak));
  const double gain = std::pow(10.0, gain_db / 20.0);
  const auto fade = static_cast<std::size_t>(kFadeS * kRateHz);
  for (std::size_t i = 0; i < x.size(); ++i) {
    double w = 1.0;
    const std::size_t edge = std::min(i, x.size() - 1 - i);
    if (edge < fade) {
      w = 0.5 -
          0.5 * std::cos(std::numbers::pi * static_cast<double>(edge) / static_cast<double>(fade));
    }
    x[i] = static_cast<float>(x[i] * gain * w);
  }
  return x;
}

}  // namespace

int main(int argc, char** argv) {
  std::string espeak, strings_dir, textures_dir, out_dir;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--espeak") {
      espeak = argv[i + 1];
    } else if (flag == "--strings") {
      strings_dir = argv[i + 1];
    } else if (flag == "--textures-dir") {
      textures_dir = argv[i + 1];
    } else if (flag == "--out") {
      out_dir = argv[i + 1];
    }
  }
  if (espeak.empty() || strings_dir.empty() || textures_dir.empty() || out_dir.empty()) {
    std::fprintf(stderr,
                 "usage: cue_maker --espeak <path> --strings <dir> --textures-dir <dir> "
                 "--out <dir>\n");
    return 2;
  }
  try {
    std::vector<std::string> folders;
    for (const auto& entry : fs::directory_iterator(textures_dir)) {
      if (entry.is_directory() && fs::is_regular_file(entry.path() / "texture.toml")) {
        folders.push_back(entry.path().filename().string());
      }
    }
    std::sort(folders.begin(), folders.end());
    std::vector<sas::surface::TextureFile> textures;
    for (const auto& folder : folders) {
      textures.push_back(sas::surface::LoadTextureFile(
          (fs::path(textures_dir) / folder / "texture.toml").string()));
    }
    std::size_t made = 0;
    for (const auto& code : sas::kiosk::KioskLanguages()) {
      const auto table = sas::kiosk::LoadLanguageTable(strings_dir, code);
      std::vector<Cue> list;
      for (std::size_t t = 0; t < folders.size(); ++t) {
        list.push_back(
            {folders[t] + "_name", table.CueText(folders[t] + "_name", textures[t].name)});
        list.push_back({folders[t] + "_description",
                        table.CueText(folders[t] + "_description", textures[t].description)});
      }
      for (const auto& key : sas::kiosk::CueKeys()) list.push_back({key, table.CueText(key)});
      const fs::path dir = fs::path(out_dir) / code;
      fs::create_directories(dir);
      for (const auto& cue : list) {
        const std::string raw = (dir / (cue.key + ".espeak.wav")).string();
        Speak(espeak, table.espeak_voice, table.words_per_minute, cue.text, raw);
        sas::surface::AudioReadLimits limits;
        limits.target_rate_hz = kRateHz;
        const auto clip = sas::surface::ReadAudioFile(raw, limits);
        fs::remove(raw);
        const std::vector<float> shaped = Shape(clip.samples);
        sas::surface::WriteWav((dir / (cue.key + ".wav")).string(), shaped.data(), shaped.size(), 1,
                               static_cast<int>(kRateHz), sas::surface::WavFormat::kPcm24);
        std::FILE* text = std::fopen((dir / (cue.key + ".txt")).c_str(), "w");
        if (text == nullptr) throw std::runtime_error("cannot write " + (dir / cue.key).string());
        std::fprintf(text, "%s\n", cue.text.c_str());
        std::fclose(text);
        ++made;
      }
    }
    std::printf("cue_maker: %zu spoken cues in %zu languages in %s\n", made,
                sas::kiosk::KioskLanguages().size(), out_dir.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cue_maker: %s\n", e.what());
    return 1;
  }
  return 0;
}
