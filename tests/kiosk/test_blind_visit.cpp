// A blind visitor's session with no screen, through the real engine on the virtual clock (the
// headless visit's VirtualVisit), with the spoken cues made at build time: place a token -> the
// texture's name; rest the pen -> its description; press record -> "speak after the tone", the
// count, the tone, then (a voice into the fake microphone) "now scratch your voice"; walk away ->
// the idle reset and the spoken invitation. Every heard cue is checked on the captured output:
// it sounds where it was handed over (the cue file's own samples found there by correlation, at
// its level), and the sentence in its file is the one the language's string table holds (read
// here from the table itself). The same session in English and in German.
#include <toml++/toml.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "kiosk/kiosk_engine.h"
#include "kiosk/synthetic_voice.h"
#include "kiosk/virtual_visit.h"
#include "platform/audio/audio_input.h"
#include "sas/version.h"
#include "surface/audio_file.h"

#if defined(SAS_CUES_DIR)

using sas::kiosk::CueEvent;
using sas::kiosk::KioskEngine;
using sas::kiosk::VirtualVisit;
using sas::platform::PenReading;

namespace {

constexpr double kFs = 48000.0;

struct Heard {
  CueEvent cue;
  std::size_t frame = 0;  // output frames rendered when it was handed over
};

// What the table file says for `key` in `language` (the texture's own file for English names
// and descriptions).
std::string Expected(const std::string& language, const std::string& key) {
  const std::string root = std::string(sas::kSourceDir) + "/textures/";
  const toml::table table = toml::parse_file(root + "strings/" + language + ".toml");
  if (auto text = table["cues"][key].value<std::string>()) return *text;
  if (key == "invitation") {  // spoken as its parts in order, one sentence
    std::string sentence;
    for (const char* part : {"scratch", "rest", "roll", "token", "record", "language"}) {
      sentence +=
          (sentence.empty() ? "" : ", ") + table["invitation"][part].value_or(std::string());
    }
    return sentence + ".";
  }
  if (auto text = table["textures"][key].value<std::string>()) return *text;
  const auto split = key.rfind('_');
  const toml::table texture = toml::parse_file(root + key.substr(0, split) + "/texture.toml");
  return texture[key.substr(split + 1)].value_or(std::string("?"));
}

std::vector<float> CueSamples(const std::string& language, const std::string& key) {
  sas::surface::AudioReadLimits limits;
  limits.target_rate_hz = kFs;
  return sas::surface::ReadAudioFile(
             std::string(SAS_CUES_DIR) + "/" + language + "/" + key + ".wav", limits)
      .samples;
}

double Rms(const float* x, std::size_t n, std::size_t stride) {
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) sum += static_cast<double>(x[i * stride]) * x[i * stride];
  return std::sqrt(sum / static_cast<double>(std::max<std::size_t>(n, 1)));
}

// Where `clip` sounds in the speaker channel of `stereo` within `search` frames after `from`:
// the lag of the best normalised correlation, and that correlation.
std::pair<std::size_t, double> Locate(const std::vector<float>& stereo, std::size_t from,
                                      const std::vector<float>& clip, std::size_t search) {
  std::size_t best_lag = 0;
  double best = -1.0;
  const double clip_energy = Rms(clip.data(), clip.size(), 1);
  for (std::size_t lag = 0; lag < search; ++lag) {
    const std::size_t start = from + lag;
    if ((start + clip.size()) * 2 > stereo.size()) break;
    double dot = 0.0, energy = 0.0;
    for (std::size_t i = 0; i < clip.size(); ++i) {
      const double y = stereo[2 * (start + i)];
      dot += y * clip[i];
      energy += y * y;
    }
    const double n = static_cast<double>(clip.size());
    const double c = dot / n / (clip_energy * std::sqrt(energy / n) + 1e-30);
    if (c > best) {
      best = c;
      best_lag = lag;
    }
  }
  return {from + best_lag, best};
}

// The fraction of the speaker signal's power at `hz` (Goertzel) over `n` frames from `from`.
double ToneShare(const std::vector<float>& stereo, std::size_t from, std::size_t n, double hz) {
  const double w = 2.0 * std::numbers::pi * hz / kFs;
  double s1 = 0.0, s2 = 0.0, total = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = stereo[2 * (from + i)];
    const double s0 = x + 2.0 * std::cos(w) * s1 - s2;
    s2 = s1;
    s1 = s0;
    total += x * x;
  }
  const double power = s1 * s1 + s2 * s2 - 2.0 * std::cos(w) * s1 * s2;
  return 2.0 * power / static_cast<double>(n) / (total + 1e-30);
}

// A pen held still on the middle of the picture for `seconds`, then lifted.
sas::kiosk::PenScript RestingPen(double t0_s, double seconds) {
  return [=](double t_s) -> std::optional<sas::kiosk::ScriptedPen> {
    PenReading pen;
    pen.time_ns = static_cast<std::int64_t>(std::llround(t_s * 1e9));
    pen.x_px = 960.0 + 0.5 * std::sin(t_s);  // a hand's tremor: well under the rest radius
    pen.y_px = 540.0;
    pen.tip_down = t_s < t0_s + seconds;
    pen.pressure = pen.tip_down ? 0.5 : 0.0;
    pen.origin = sas::platform::PenOrigin::kTablet;
    return sas::kiosk::ScriptedPen{pen, {}};
  };
}

void BlindVisit(const std::string& language) {
  sas::kiosk::KioskEngineOptions options;
  options.virtual_clock = true;
  options.cues_dir = SAS_CUES_DIR;
  options.config.language = language;
  options.config.visitor_languages = {};
  options.config.idle_timeout_s = 20.0;
  options.config.invitation_interval_s = 15.0;
  options.config.describe_after_rest_s = 2.0;
  options.config.record_max_duration_s = 3.0;
  KioskEngine engine(options);
  sas::platform::FakeAudioInput mic(sas::kiosk::RecorderConfigFor(options.config));
  engine.SetRecorder(&mic.recorder());
  mic.Start();
  VirtualVisit visit(engine);
  visit.SetMicrophone(&mic);
  std::vector<Heard> heard;
  engine.SetCueObserver([&](const CueEvent& cue) { heard.push_back({cue, visit.frames_kept()}); });

  visit.Advance(1.0);
  REQUIRE(heard.size() == 1);  // the attract screen invites at once
  REQUIRE(heard[0].cue.key == "invitation");
  visit.Advance(12.0);  // the whole invitation (about 10 s), then a token
  const double token_s = visit.now_s();
  engine.OnToken(visit.now_ns(), 1);  // broken glass
  visit.Advance(3.5);
  const double rest_start_s = visit.now_s();
  visit.Advance(9.0, RestingPen(rest_start_s, 3.0));  // rests 3 s; the description plays on
  const double press_s = visit.now_s();
  engine.OnRecordButton(visit.now_ns(), true);
  visit.Advance(0.1);
  engine.OnRecordButton(visit.now_ns(), false);
  visit.SetVoice(sas::kiosk::SynthesiseVoice(kFs, 2.5));
  visit.Advance(5.5 + 3.0 + 4.0);
  CHECK(engine.has_voice());
  visit.Advance(20.0 + 15.0 + 6.0);  // the idle reset and its invitation at once
  const auto& out = visit.output();

  std::vector<std::string> keys;
  for (const auto& h : heard) keys.push_back(h.cue.key);
  REQUIRE(keys == std::vector<std::string>{"invitation", "broken_glass_name",
                                           "broken_glass_description", "record_countdown",
                                           "count_3", "count_2", "count_1", "tone", "voice_ready",
                                           "invitation"});
  const auto at_s = [&](const Heard& h) { return static_cast<double>(h.frame) / kFs; };
  // When each was heard.
  CHECK(at_s(heard[0]) == Approx(0.0).margin(0.02));
  CHECK(at_s(heard[1]) - token_s == Approx(0.0).margin(0.02));
  CHECK(at_s(heard[2]) - rest_start_s == Approx(2.0).margin(0.05));
  CHECK(at_s(heard[3]) - press_s == Approx(0.0).margin(0.02));
  CHECK(at_s(heard[5]) - at_s(heard[4]) == Approx(1.0).margin(0.02));
  CHECK(at_s(heard[6]) - at_s(heard[5]) == Approx(1.0).margin(0.02));
  CHECK(at_s(heard[7]) - press_s == Approx(5.5 - 0.4).margin(0.02));
  CHECK(at_s(heard[8]) - press_s == Approx(5.5 + 3.0).margin(0.05));
  // The take ended the last activity: the idle reset 20 s later, with its invitation (one
  // language: the next one a 45 s cycle later, after this run).
  CHECK(at_s(heard[9]) - press_s == Approx(5.5 + 3.0 + 20.0).margin(0.05));

  for (const auto& h : heard) {
    INFO(language << " " << h.cue.key);
    CHECK(h.cue.language == language);
    const std::size_t search = 2 * 256;  // the one-buffer hand-over plus the safety stage
    if (h.cue.key == "tone") {
      // The tone is no sentence: 880 Hz carries nearly all of the output while it sounds.
      CHECK(h.cue.text.empty());
      CHECK(ToneShare(out, h.frame + search, static_cast<std::size_t>(0.15 * kFs), 880.0) > 0.9);
      continue;
    }
    CHECK(h.cue.text == Expected(language, h.cue.key));
    // Heard where it was handed over: its own samples are there, at their level.
    const auto clip = CueSamples(language, h.cue.key);
    const auto [start, correlation] = Locate(out, h.frame, clip, search);
    CHECK(correlation > 0.9);
    const double heard_db =
        20.0 * std::log10(Rms(&out[2 * start], clip.size(), 2) / Rms(clip.data(), clip.size(), 1));
    CHECK(std::fabs(heard_db) < 1.5);
  }
}

}  // namespace

TEST_CASE(
    "a blind visitor hears the name, the description, the count, the tone, now scratch "
    "and the invitation in English",
    "[kiosk][e2e]") {
  BlindVisit("en");
}

TEST_CASE("the same blind visit in German uses the German cues and strings", "[kiosk][e2e]") {
  BlindVisit("de");
}

TEST_CASE(
    "at the default settings the attract screen shows and speaks every visitor language's "
    "invitation within one cycle of at most 60 s, each naming tokens, resting, recording, "
    "rolling and the language key",
    "[kiosk][e2e]") {
  // Nobody presses a key: the cycle alone reaches every language. Each invitation is heard where
  // it was handed over (its cue file's samples in the output), in full before the next, while
  // the screen's texts (engine.strings(), what the attract screen draws) are in its language.
  sas::kiosk::KioskEngineOptions options;
  options.virtual_clock = true;
  options.cues_dir = SAS_CUES_DIR;
  KioskEngine engine(options);
  const double cycle_s = sas::kiosk::AttractCycleS(engine.session().config());
  INFO("attract cycle " << cycle_s << " s");
  CHECK(cycle_s <= 60.0);
  VirtualVisit visit(engine);
  std::vector<Heard> heard;
  std::vector<std::string> shown;  // the screen's language when each cue was handed over
  engine.SetCueObserver([&](const CueEvent& cue) {
    heard.push_back({cue, visit.frames_kept()});
    shown.push_back(engine.strings().code);
  });
  visit.Advance(std::min(cycle_s, 60.0) + 0.5);
  const auto& out = visit.output();
  const std::vector<std::string> languages = {"en", "de", "fr", "it", "es"};
  REQUIRE(heard.size() >= languages.size());
  // Each language's key word for the parts a visitor must learn: tokens, resting, recording,
  // rolling (its side button) and the language key, L.
  const std::map<std::string, std::vector<std::string>> words = {
      {"en", {"Token", "Rest", "records", "roll", "L "}},
      {"de", {"Spielsteine", "still", "Stimme", "rollt", "L "}},
      {"fr", {"jetons", "immobile", "enregistre", "rouler", "L "}},
      {"it", {"gettoni", "Fermala", "registra", "rotola", "L "}},
      {"es", {"fichas", "quieto", "graba", "rueda", "L "}}};
  for (std::size_t i = 0; i < languages.size(); ++i) {
    const auto& h = heard[i];
    INFO(languages[i]);
    CHECK(h.cue.key == "invitation");
    CHECK(h.cue.language == languages[i]);
    CHECK(shown[i] == languages[i]);
    const double at_s = static_cast<double>(h.frame) / kFs;
    const auto clip = CueSamples(languages[i], "invitation");
    const double clip_s = static_cast<double>(clip.size()) / kFs;
    INFO("at " << at_s << " s, " << clip_s << " s long");
    CHECK(at_s + clip_s <= 60.0);
    if (i + 1 < heard.size()) {  // heard in full: the next starts after it
      CHECK(static_cast<double>(heard[i + 1].frame) / kFs >= at_s + clip_s);
    }
    // Its first and last second where they belong (cheaper than the whole clip at every lag).
    const std::size_t second = static_cast<std::size_t>(kFs);
    REQUIRE(clip.size() > 2 * second);
    const std::vector<float> head(clip.begin(), clip.begin() + static_cast<long>(second));
    const std::vector<float> tail(clip.end() - static_cast<long>(second), clip.end());
    const auto [start, correlation] = Locate(out, h.frame, head, 2 * 256);
    CHECK(correlation > 0.9);
    CHECK(Locate(out, start + clip.size() - second, tail, 1).second > 0.9);
    for (const auto& word : words.at(languages[i])) {
      INFO(word);
      CHECK(h.cue.text.find(word) != std::string::npos);
      std::string screen;
      for (const auto& part : sas::kiosk::InvitationParts()) {
        screen += sas::kiosk::LoadLanguageTable(std::string(sas::kSourceDir) + "/textures/strings",
                                                languages[i])
                      .Invitation(part) +
                  " ";
      }
      CHECK(screen.find(word) != std::string::npos);
    }
  }
}

#endif
