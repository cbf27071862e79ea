// cue_maker: makes the kiosk's spoken cues at build time (for visitors who cannot see the screen),
// in every language of textures/strings/ (files/strings.h). For each language <code> it writes
// <out>/<code>/<key>.wav and, next to it, <key>.txt with the sentence it speaks (the kiosk reports
// it with each cue it plays, so a test can check what was heard against the string table). Keys:
// each message of the table's [cues], and <folder>_name / <folder>_description for each texture
// folder of --textures-dir (cue_voice.h).
//
// Each cue's voice: the committed render in --renders (<code>/<key>.opus, spoken by the engine
// docs/voices.md chose for that language) while its <key>.txt equals the table's sentence; else
// espeak-ng with the table's [voice] (a changed sentence or a new key is never spoken with stale
// words; the build says once which cues fell back). Then, for every cue alike: 48 kHz mono,
// silence trimmed, loudness-normalised under a peak ceiling, faded (cues::ShapeCue), 24-bit WAV.
//
// --render-out DIR re-speaks the committed renders instead: for each language of --choice
// (textures/voices/choice.toml) with SVOX Pico from --pico-root (textures/voices/fetch_engines.sh
// unpacks Debian's non-free packages there), into DIR/<code>/<key>.opus + .txt: the cues whose
// render is missing or whose sentence changed, at choice.toml's [rate_percent] for their key. The
// build target regenerate_voices runs both steps.
//
// Exit status: 0 ok, 1 runtime error, 2 usage error.

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "cue_voice.h"
#include "files/strings.h"
#include "surface/wav_writer.h"
#include "tools/command_line.h"

namespace {

namespace fs = std::filesystem;
using sas::cues::CueSentence;

int Render(const std::string& strings_dir, const std::string& textures_dir,
           const std::string& choice_path, const std::string& pico_root,
           const std::string& render_out) {
  sas::cues::PicoSpeaker pico(pico_root);
  const auto rates = sas::cues::LoadPicoRates(choice_path);
  std::size_t made = 0, kept = 0;
  for (const auto& [code, voice] : sas::cues::LoadPicoChoice(choice_path)) {
    const auto table = sas::kiosk::LoadLanguageTable(strings_dir, code);
    const fs::path dir = fs::path(render_out) / code;
    fs::create_directories(dir);
    std::set<std::string> current;
    for (const CueSentence& cue : sas::cues::CueSentences(table, textures_dir)) {
      current.insert(cue.key + ".opus");
      current.insert(cue.key + ".txt");
      const fs::path audio = dir / (cue.key + ".opus"), text = dir / (cue.key + ".txt");
      // A render whose sentence is unchanged is kept byte for byte (Opus encodes differently each
      // time: re-speaking all would rewrite every file in the repository). Delete one to redo it.
      if (fs::exists(audio) && fs::exists(text) && sas::cues::ReadText(text.string()) == cue.text) {
        ++kept;
        continue;
      }
      const auto rate = rates.find(cue.key);
      sas::cues::WriteRender(audio.string(),
                             pico.Speak(voice, cue.text, rate == rates.end() ? 100 : rate->second));
      sas::cues::WriteText(text.string(), cue.text);
      ++made;
    }
    // Old renders go: a key the table no longer has must not linger in the repository.
    for (const auto& entry : fs::directory_iterator(dir)) {
      if (!current.contains(entry.path().filename().string())) fs::remove(entry.path());
    }
  }
  std::printf("cue_maker: %zu renders with SVOX Pico in %s, %zu unchanged kept\n", made,
              render_out.c_str(), kept);
  return 0;
}

int Build(const std::string& espeak, const std::string& strings_dir,
          const std::string& textures_dir, const std::string& renders_dir,
          const std::string& out_dir) {
  std::size_t made = 0, rendered = 0;
  std::vector<std::string> fell_back;
  for (const auto& code : sas::kiosk::KioskLanguages()) {
    const auto table = sas::kiosk::LoadLanguageTable(strings_dir, code);
    const fs::path dir = fs::path(out_dir) / code;
    fs::create_directories(dir);
    // Only a language that has committed renders can fall back from them.
    const bool has_renders = !renders_dir.empty() && fs::is_directory(fs::path(renders_dir) / code);
    for (const CueSentence& cue : sas::cues::CueSentences(table, textures_dir)) {
      const auto choice = sas::cues::ChooseRender(renders_dir, code, cue.key, cue.text);
      sas::cues::Speech speech;
      if (choice.use_render) {
        speech = sas::cues::ReadRender(choice.audio_path);
        ++rendered;
      } else {
        speech = sas::cues::SpeakEspeak(espeak, table.espeak_voice, table.words_per_minute,
                                        cue.text, (dir / (cue.key + ".espeak.wav")).string());
        if (has_renders) fell_back.push_back(code + "/" + cue.key + " (" + choice.why + ")");
      }
      const std::vector<float> shaped = sas::cues::ShapeCue(speech);
      sas::surface::WriteWav((dir / (cue.key + ".wav")).string(), shaped.data(), shaped.size(), 1,
                             static_cast<int>(sas::cues::kCueRateHz),
                             sas::surface::WavFormat::kPcm24);
      sas::cues::WriteText((dir / (cue.key + ".txt")).string(), cue.text);
      ++made;
    }
  }
  std::printf("cue_maker: %zu spoken cues in %zu languages in %s (%zu from committed renders)\n",
              made, sas::kiosk::KioskLanguages().size(), out_dir.c_str(), rendered);
  if (!fell_back.empty()) {
    std::string list;
    for (const auto& item : fell_back) list += (list.empty() ? "" : ", ") + item;
    std::printf("cue_maker: %zu cues spoken with espeak-ng instead of their committed voice: %s. "
                "Re-speak them: cmake --build <build> --target regenerate_voices\n",
                fell_back.size(), list.c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Makes the kiosk's spoken cues: committed renders where their sentence is current, "
               "espeak-ng for the rest; or re-speaks the committed renders (--render-out).",
               "cue_maker"};
  std::string espeak, strings_dir, textures_dir, out_dir, renders_dir, render_out, pico_root,
      choice_path;
  app.add_option("--espeak", espeak, "espeak-ng program (build mode)");
  app.add_option("--strings", strings_dir, "the string tables' folder (textures/strings)")
      ->required();
  app.add_option("--textures-dir", textures_dir, "the texture folders' parent (textures)")
      ->required();
  app.add_option("--out", out_dir, "write <out>/<language>/<key>.wav and .txt (build mode)");
  app.add_option("--renders", renders_dir, "committed renders (textures/voices), build mode");
  app.add_option("--render-out", render_out,
                 "re-speak the committed renders into this folder instead of building cues");
  app.add_option("--pico-root", pico_root, "SVOX Pico unpacked by fetch_engines.sh (render mode)");
  app.add_option("--choice", choice_path, "which languages Pico speaks (textures/voices/choice.toml)");
  if (const int code = sas::kiosk::ParseProgramCommandLine(app, argc, argv); code >= 0) return code;
  // The two modes' own needs, which CLI11's option list cannot say: a usage error like the others.
  const bool render = !render_out.empty();
  const char* missing = render && (pico_root.empty() || choice_path.empty())
                            ? "--render-out needs --pico-root and --choice"
                        : !render && (espeak.empty() || out_dir.empty())
                            ? "building cues needs --espeak and --out"
                            : nullptr;
  if (missing != nullptr) {
    std::fprintf(stderr, "cue_maker: %s\n(cue_maker --help lists the options)\n", missing);
    return 2;
  }
  try {
    if (!render_out.empty()) return Render(strings_dir, textures_dir, choice_path, pico_root, render_out);
    return Build(espeak, strings_dir, textures_dir, renders_dir, out_dir);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cue_maker: %s\n", e.what());
    return 1;
  }
}
