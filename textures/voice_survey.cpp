// voice_survey: every speech engine Debian 12 packages for the kiosk's five languages, measured on
// the kiosk's own sentences (all cues of the language, cues::CueSentences), written to
// docs/voices.md with the choice it supports.
//
//   voice_survey --engines ROOT [--espeak espeak-ng] [--strings textures/strings]
//                [--textures-dir textures] [--choice textures/voices/choice.toml] [--docs docs]
//
// ROOT is what `textures/voices/fetch_engines.sh DIR survey` unpacked (DIR/root): SVOX Pico,
// MBROLA and its voices, flite and pocketsphinx with its US English model, none of them installed.
// Candidates per language: espeak-ng with the table's voice (what the build uses without renders),
// espeak-ng with each MBROLA voice of the language, SVOX Pico, and for English flite's voices.
// Figures (voice_figures.h) per candidate, pooled over the cues; for English also the word error
// rate of pocketsphinx (general US English language model, not told the sentences) on each cue.
// Exit status: 0 ok, 1 runtime error, 2 usage error.
#include <CLI/CLI.hpp>
#include <sndfile.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cue_voice.h"
#include "files/strings.h"
#include "tools/command_line.h"
#include "voice_figures.h"

namespace {

namespace fs = std::filesystem;
using sas::cues::Speech;

enum class Engine { kEspeak, kMbrola, kPico, kFlite };

struct Candidate {
  std::string label;    // as the doc names it
  std::string package;  // the Debian package that brings the voice
  Engine engine;
  std::string voice;
};

std::vector<Candidate> Candidates(const std::string& code, const std::string& espeak_voice) {
  std::vector<Candidate> list = {
      {"espeak-ng " + espeak_voice, "espeak-ng (main)", Engine::kEspeak, espeak_voice}};
  const std::map<std::string, std::vector<std::string>> mbrola = {
      {"en", {"en1", "us1", "us2"}},
      {"de", {"de1", "de2", "de3", "de4", "de5", "de6", "de7"}},
      {"fr", {"fr1", "fr2", "fr3", "fr4", "fr6"}},
      {"it", {"it1", "it2", "it3", "it4"}},
      {"es", {"es1", "es2", "es3", "es4"}}};
  for (const auto& v : mbrola.at(code)) {
    list.push_back({"espeak-ng + MBROLA " + v, "mbrola-" + v + " (contrib/non-free)",
                    Engine::kMbrola, "mb-" + v});
  }
  const std::map<std::string, std::vector<std::string>> pico = {
      {"en", {"en-GB", "en-US"}}, {"de", {"de-DE"}}, {"fr", {"fr-FR"}}, {"it", {"it-IT"}},
      {"es", {"es-ES"}}};
  for (const auto& v : pico.at(code)) {
    list.push_back({"SVOX Pico " + v, "libttspico0 (non-free)", Engine::kPico, v});
  }
  if (code == "en") {
    for (const char* v : {"slt"}) {
      list.push_back({std::string("flite ") + v, "flite (main)", Engine::kFlite, v});
    }
  }
  return list;
}

void WritePcm16(const std::string& path, const std::vector<float>& x, double rate_hz) {
  SF_INFO info{};
  info.samplerate = static_cast<int>(rate_hz);
  info.channels = 1;
  info.format = SF_FORMAT_WAV | SF_FORMAT_PCM_16;
  SNDFILE* file = sf_open(path.c_str(), SFM_WRITE, &info);
  if (file == nullptr) throw std::runtime_error("cannot write " + path);
  sf_writef_float(file, x.data(), static_cast<sf_count_t>(x.size()));
  sf_close(file);
}

struct Row {
  Candidate candidate;
  sas::cues::VoiceSummary summary;
  std::size_t edits = 0, words = 0;  // recognition (English)
  std::vector<std::string> misheard;
};

class Survey {
 public:
  Survey(std::string root, std::string espeak, fs::path work)
      : root_(std::move(root)), espeak_(std::move(espeak)), work_(std::move(work)), pico_(root_) {
    lib_env_ = "LD_LIBRARY_PATH=" + root_ + "/usr/lib/x86_64-linux-gnu";
    // espeak-ng finds an MBROLA voice as <data>/espeak-ng-data/mbrola/<voice>: a private data
    // folder of links to the system's data plus the unpacked voices.
    const fs::path data = work_ / "espeak" / "espeak-ng-data";
    fs::create_directories(data / "mbrola");
    for (const auto& e : fs::directory_iterator("/usr/lib/x86_64-linux-gnu/espeak-ng-data")) {
      if (!fs::exists(data / e.path().filename())) fs::create_directory_symlink(e.path(), data / e.path().filename());
    }
    for (const auto& v : fs::directory_iterator(root_ + "/usr/share/mbrola")) {
      const fs::path file = v.path() / v.path().filename();
      if (fs::is_regular_file(file) && !fs::exists(data / "mbrola" / v.path().filename())) {
        fs::create_symlink(file, data / "mbrola" / v.path().filename());
      }
    }
    espeak_data_ = (work_ / "espeak").string();
  }

  Speech Speak(const Candidate& c, const sas::kiosk::LanguageTable& table, const std::string& text) {
    const std::string scratch = (work_ / "speech.wav").string();
    switch (c.engine) {
      case Engine::kEspeak:
        return sas::cues::SpeakEspeak(espeak_, c.voice, table.words_per_minute, text, scratch);
      case Engine::kMbrola:
        return sas::cues::SpeakEspeak(espeak_, c.voice, table.words_per_minute, text, scratch,
                                      espeak_data_, root_ + "/usr/bin");
      case Engine::kPico:
        return pico_.Speak(c.voice, text);
      case Engine::kFlite:
        sas::cues::RunProgram({root_ + "/usr/bin/flite", "-voice", c.voice, "-o", scratch, "-t", text},
                              {lib_env_});
        {
          Speech s = sas::cues::ReadRender(scratch);
          fs::remove(scratch);
          return s;
        }
    }
    throw std::logic_error("unknown engine");
  }

  // pocketsphinx's words for each 16 kHz cue: one batch run, so the model loads once.
  std::vector<std::vector<std::string>> Recognise(const std::vector<std::vector<float>>& cues) {
    const fs::path dir = work_ / "heard";
    fs::create_directories(dir);
    std::ofstream control(dir / "cues.ctl");
    for (std::size_t i = 0; i < cues.size(); ++i) {
      WritePcm16((dir / (std::to_string(i) + ".wav")).string(), cues[i], sas::cues::kAnalysisRateHz);
      control << i << "\n";
    }
    control.close();
    const std::string model = root_ + "/usr/share/pocketsphinx/model/en-us";
    const std::string hyp = (dir / "heard.hyp").string();
    sas::cues::RunProgram({root_ + "/usr/bin/pocketsphinx_batch", "-hmm", model + "/en-us",
                           "-lm", model + "/en-us.lm.bin", "-dict", model + "/cmudict-en-us.dict",
                           "-adcin", "yes", "-adchdr", "44", "-cepdir", dir.string(), "-cepext",
                           ".wav", "-ctl", (dir / "cues.ctl").string(), "-hyp", hyp,
                           // First pass only: the same for every candidate, and twice as fast.
                           "-fwdflat", "no", "-bestpath", "no"},
                          {lib_env_}, (dir / "log.txt").string());
    // One line per cue: "<words> (<id> <score>)".
    std::vector<std::vector<std::string>> heard(cues.size());
    std::ifstream in(hyp);
    std::string line;
    while (std::getline(in, line)) {
      const auto open = line.rfind('(');
      if (open == std::string::npos) continue;
      const std::size_t id = std::stoul(line.substr(open + 1));
      if (id < heard.size()) heard[id] = sas::cues::Words(line.substr(0, open));
    }
    return heard;
  }

 private:
  std::string root_, espeak_;
  fs::path work_;
  sas::cues::PicoSpeaker pico_;
  std::string lib_env_, espeak_data_;
};

std::string Fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

// How the figures decide, and what they cannot tell. Reviewed against the tables above each time
// they are rewritten.
constexpr const char* kWhy = R"(## How the choice is made, and what the figures cannot tell

- **Intelligibility decides where it can be measured.** Only English has a recogniser in Debian
  (pocketsphinx, US English acoustic model, general language model, first pass only: it is not
  told the sentences). The shipped English voice is the candidate it understands best (the tool
  checks this each time it runs and says so when it no longer holds). espeak-ng's formant voice,
  what the kiosk spoke before, is understood worst by far; the MBROLA voices, which speak
  espeak-ng's phonemes and melody with recorded diphones, sit between. Within each accent SVOX
  Pico beats the others (en-GB against MBROLA en1 and espeak-ng's British "en"; en-US against
  MBROLA us1/us2 and flite slt). The recogniser's US acoustic model favours US voices, so the gap
  between Pico's en-GB and en-US is partly accent; `en = "en-GB"` in textures/voices/choice.toml
  switches the kiosk to the British voice. A recogniser trained on natural speech is a stand-in
  for a listener, not a listening test.
- **The other languages have no recogniser here**, so no figure above measures their
  intelligibility. They get SVOX Pico because it is the same engine and design in all five
  languages (HMM-based synthesis with a prosody model per language) and it won English; MBROLA's
  voices differ from one another (and some break: "Saturation" warnings, F0 ranges of octave
  jumps) and all speak espeak-ng's prosody, which English shows to be the weak part.
- **What the other figures tell, and what not.** HF flatness separates espeak-ng's strictly
  periodic formant source (the lowest, the buzz the issue hears) from engines built from recorded
  speech; MBROLA's recorded diphones are mostly flatter than Pico's vocoded voice, which does not
  make them clearer (English says otherwise): flatness counts breath and artefacts alike. The F0
  range does not separate the working engines much. Pico's 16 kHz rate caps its band at 8 kHz; espeak-ng's
  22 kHz reaches higher, but with the formant source's buzz, not consonant detail. Loudness is
  equal for every engine by construction (the cue shaping: a candidate whose quietest cue is
  under -23 LUFS was held back by the -1 dBFS peak ceiling); the true peak shows each
  voice's crest, all under the ceiling. Naturalness as a
  visitor hears it, how a voice carries over a gallery's noise, and mispronounced words in the
  four other languages are not measured: a listening check by a speaker of each language is still
  worth doing once.
- **Cost:** Pico is non-free (its lingware has no source), so the build never runs it; its renders
  are committed (Ogg Opus, 24 kb/s) and any cue whose sentence changed falls back to espeak-ng.
)";

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Measures every packaged speech engine on the kiosk's sentences; writes "
               "docs/voices.md.",
               "voice_survey"};
  std::string root, espeak = "/usr/bin/espeak-ng", strings_dir = "textures/strings",
                    textures_dir = "textures", choice_path = "textures/voices/choice.toml", docs;
  app.add_option("--engines", root, "the engines fetch_engines.sh unpacked (<dir>/root)")->required();
  app.add_option("--espeak", espeak, "espeak-ng program");
  app.add_option("--strings", strings_dir, "string tables' folder");
  app.add_option("--textures-dir", textures_dir, "texture folders' parent");
  app.add_option("--choice", choice_path, "the committed choice (textures/voices/choice.toml)");
  app.add_option("--docs", docs, "write voices.md into this folder");
  if (const int code = sas::kiosk::ParseProgramCommandLine(app, argc, argv); code >= 0) return code;
  try {
    const fs::path work = fs::temp_directory_path() / ("voice_survey-" + std::to_string(getpid()));
    fs::create_directories(work);
    Survey survey(root, espeak, work);
    const auto choice = sas::cues::LoadPicoChoice(choice_path);
    std::ostringstream md;
    md << "# Voices: the packaged speech engines on the kiosk's sentences\n\n"
          "Written by `voice_survey --engines <root> --docs docs` (textures/voice_survey.cpp); "
          "do not edit by hand. The engines come from Debian 12 packages, unpacked but not "
          "installed by `textures/voices/fetch_engines.sh <dir> survey`. Every candidate speaks "
          "all of its language's cues (texture names and descriptions, messages) from "
          "textures/strings; each cue is then shaped as the kiosk plays it (trimmed, normalised "
          "to -23 LUFS under a -1 dBFS sample peak) and measured at 16 kHz "
          "(textures/voice_figures.h says how each figure is taken).\n\n"
          "Columns: *rate* the engine's own sample rate; *band* the highest frequency within "
          "50 dB of the long-term spectrum's peak; *wpm* words per minute of cue; *s* all cues' "
          "duration; *LUFS* the quietest..loudest cue after normalisation (under -23: held back by "
          "the peak ceiling); *dBTP* the highest true peak; *voiced* share of 10 ms frames; *F0* "
          "median and 5-95 % range in semitones (melody; a narrow range sounds flat); *HF flat* "
          "spectral flatness 2-5 kHz in voiced frames (near 0: a strict line spectrum, heard as "
          "buzz); *WER* (English) pocketsphinx's word error rate against the sentences.\n\n";
    for (const auto& code : sas::kiosk::KioskLanguages()) {
      const auto table = sas::kiosk::LoadLanguageTable(strings_dir, code);
      const auto cues = sas::cues::CueSentences(table, textures_dir);
      std::vector<Row> rows;
      for (const auto& candidate : Candidates(code, table.espeak_voice)) {
        Row row{candidate, {}, 0, 0, {}};
        std::vector<sas::cues::VoiceFigures> figures;
        std::vector<std::vector<float>> low(cues.size());
        for (std::size_t i = 0; i < cues.size(); ++i) {
          figures.push_back(sas::cues::MeasureCue(survey.Speak(candidate, table, cues[i].text),
                                                  cues[i].text, &low[i]));
        }
        if (code == "en") {
          const auto heard = survey.Recognise(low);
          for (std::size_t i = 0; i < cues.size(); ++i) {
            const auto reference = sas::cues::Words(cues[i].text);
            const std::size_t edits = sas::cues::WordEdits(reference, heard[i]);
            row.edits += edits;
            row.words += reference.size();
            if (edits > 0 && cues[i].key == "invitation") {
              std::string h;
              for (const auto& w : heard[i]) h += (h.empty() ? "" : " ") + w;
              row.misheard.push_back(h);
            }
          }
        }
        row.summary = sas::cues::Summarise(figures);
        std::printf("%s %-28s wpm %5.0f  F0 range %4.1f st  HF flat %.3f", code.c_str(),
                    candidate.label.c_str(), row.summary.words_per_minute, row.summary.f0_range_st,
                    row.summary.hf_flatness);
        if (row.words > 0) std::printf("  WER %.1f %%", 100.0 * double(row.edits) / double(row.words));
        std::printf("\n");
        std::fflush(stdout);
        rows.push_back(std::move(row));
      }
      md << "## " << table.language_name << " (" << code << ", " << cues.size() << " cues, "
         << table.words_per_minute << " wpm asked of espeak-ng)\n\n"
         << "| candidate | package | rate | band | wpm | s | LUFS | dBTP | voiced | F0 | HF flat |"
         << (code == "en" ? " WER |" : "") << "\n"
         << "|---|---|---|---|---|---|---|---|---|---|---|" << (code == "en" ? "---|" : "") << "\n";
      for (const auto& r : rows) {
        const auto& s = r.summary;
        md << "| " << r.candidate.label << " | " << r.candidate.package << " | "
           << Fixed(s.source_rate_hz / 1000.0, 2) << " kHz | " << Fixed(s.band_edge_hz / 1000.0, 1)
           << " kHz | " << Fixed(s.words_per_minute, 0) << " | " << Fixed(s.duration_s, 1) << " | "
           << Fixed(s.loudness_min_lufs, 1) << "..." << Fixed(s.loudness_max_lufs, 1) << " | "
           << Fixed(s.true_peak_max_dbtp, 1) << " | " << Fixed(100.0 * s.voiced_share, 0)
           << " % | " << Fixed(s.f0_median_hz, 0) << " Hz, " << Fixed(s.f0_range_st, 1)
           << " st | " << Fixed(s.hf_flatness, 3) << " |";
        if (code == "en") md << " " << Fixed(100.0 * double(r.edits) / double(r.words), 1) << " % |";
        md << "\n";
      }
      if (code == "en") {
        md << "\nWhat pocketsphinx heard of the invitation (\"" << table.CueText("invitation")
           << "\"), where it erred:\n\n";
        for (const auto& r : rows) {
          for (const auto& h : r.misheard) md << "- " << r.candidate.label << ": \"" << h << "\"\n";
        }
      }
      const auto chosen = choice.find(code);
      const std::string shipped_label = chosen != choice.end() ? "SVOX Pico " + chosen->second
                                                               : "espeak-ng " + table.espeak_voice;
      md << "\n**Shipped:** " << shipped_label
         << (chosen != choice.end() ? " (committed renders in textures/voices/" + code + "/)"
                                    : " (built from the table)")
         << ".";
      // The shipped voice against the fallback (espeak-ng, the first row) in the figures that
      // differ most between engines.
      const Row* shipped = nullptr;
      for (const auto& r : rows) {
        if (r.candidate.label == shipped_label) shipped = &r;
      }
      if (shipped != nullptr && shipped != &rows.front()) {
        const auto &a = shipped->summary, &b = rows.front().summary;
        md << " Against " << rows.front().candidate.label << ": F0 range "
           << Fixed(a.f0_range_st, 1) << " vs " << Fixed(b.f0_range_st, 1) << " st, HF flatness "
           << Fixed(a.hf_flatness, 3) << " vs " << Fixed(b.hf_flatness, 3) << ", band "
           << Fixed(a.band_edge_hz / 1000.0, 1) << " vs " << Fixed(b.band_edge_hz / 1000.0, 1)
           << " kHz, " << Fixed(a.words_per_minute, 0) << " vs " << Fixed(b.words_per_minute, 0)
           << " wpm";
        if (code == "en") {
          for (const auto& r : rows) {
            if (r.edits * shipped->words < shipped->edits * r.words) {
              std::printf("voice_survey: %s is understood better than the shipped %s: review "
                          "textures/voices/choice.toml and the reasoning in this tool\n",
                          r.candidate.label.c_str(), shipped_label.c_str());
            }
          }
          md << ", word errors " << Fixed(100.0 * double(shipped->edits) / double(shipped->words), 1)
             << " vs " << Fixed(100.0 * double(rows.front().edits) / double(rows.front().words), 1)
             << " %";
        }
        md << ".";
      }
      md << "\n\n";
    }
    md << kWhy;
    fs::remove_all(work);
    if (!docs.empty()) {
      fs::create_directories(docs);
      std::ofstream out(fs::path(docs) / "voices.md");
      out << md.str();
      if (!out) throw std::runtime_error("cannot write " + docs + "/voices.md");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "voice_survey: %s\n", e.what());
    return 1;
  }
  return 0;
}
