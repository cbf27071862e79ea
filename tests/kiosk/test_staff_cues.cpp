// Staff-recorded cues (kiosk/staff_cues.h): a recording in <staff_dir>/cues/<language>/<key>.*
// replaces the synthetic cue of that language and key, levelled like the synthetic ones, and the
// kiosk plays it; every malformed file is refused with one warning at the journal's warning
// priority naming it and why, and the synthetic cue stays. The "recordings" are speech as a
// museum would bring it: espeak-ng at another speed than the kiosk's, 44.1 kHz stereo FLAC, at its
// own level, with room noise before and after.
#include <sndfile.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "files/strings.h"
#include "kiosk/kiosk_control.h"
#include "kiosk/kiosk_engine.h"
#include "kiosk/spoken_cues.h"
#include "kiosk/staff_cues.h"
#include "kiosk/staff_panel.h"
#include "platform/log/log.h"
#include "sas/version.h"
#include "support/fft.h"
#include "support/sound_file.h"
#include "support/temp_dir.h"
#include "surface/audio_file.h"
#include "surface/loudness.h"

extern char** environ;

#if defined(SAS_CUES_DIR) && defined(SAS_ESPEAK_NG)
namespace {

namespace fs = std::filesystem;
using sas::kiosk::Cue;
using sas::kiosk::KioskConfig;
using sas::kiosk::SpokenCues;
using sas::test::WriteSound;

const std::string kStringsDir = std::string(sas::kSourceDir) + "/textures/strings";
const std::vector<std::string> kTextures = {"bubble_wrap", "broken_glass", "wooden_board",
                                            "cracked_ground"};

std::string FromTable(const std::string& code, const std::string& table, const std::string& key) {
  const toml::table root = toml::parse_file(kStringsDir + "/" + code + ".toml");
  return root[table][key].value_or(std::string());
}

// espeak-ng's speech (22.05 kHz mono) for `text`.
std::vector<float> Speak(const std::string& voice, int wpm, const std::string& text,
                         const fs::path& scratch) {
  const std::string out = (scratch / "espeak.wav").string();
  std::vector<std::string> args = {SAS_ESPEAK_NG,       "-v", voice, "-s",
                                   std::to_string(wpm), "-w", out,   text};
  std::vector<char*> argv;
  for (auto& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  REQUIRE(posix_spawn(&pid, SAS_ESPEAK_NG, nullptr, nullptr, argv.data(), environ) == 0);
  int status = 0;
  REQUIRE(waitpid(pid, &status, 0) == pid);
  REQUIRE((WIFEXITED(status) && WEXITSTATUS(status) == 0));
  SF_INFO info{};
  SNDFILE* file = sf_open(out.c_str(), SFM_READ, &info);
  REQUIRE(file != nullptr);
  REQUIRE(info.channels == 1);
  REQUIRE(info.samplerate == 22050);
  std::vector<float> x(static_cast<std::size_t>(info.frames));
  sf_readf_float(file, x.data(), info.frames);
  sf_close(file);
  fs::remove(out);
  return x;
}

// A staff recording of `speech` (22.05 kHz): 44.1 kHz stereo, the right channel 3 dB lower and
// 0.3 ms later (a spaced microphone pair), at `gain_db`, with 0.4 s of room noise at -66 dBFS
// before and after, saved at `path` (FLAC unless `format` says otherwise). Returns what the
// kiosk should hear from it: its mono mix at 48 kHz.
std::vector<float> Record(const std::string& path, const std::vector<float>& speech, double gain_db,
                          int format = SF_FORMAT_FLAC | SF_FORMAT_PCM_16) {
  const std::vector<float> at44 = sas::surface::Resample(speech, 22050.0, 44100.0);
  const double gain = std::pow(10.0, gain_db / 20.0);
  const std::size_t pad = 17640, delay = 13;  // 0.4 s, 0.3 ms at 44.1 kHz
  const std::size_t n = at44.size() + 2 * pad + delay;
  std::mt19937 random(7);
  std::normal_distribution<float> noise(0.0f, 5e-4f);  // -66 dBFS RMS
  std::vector<float> stereo(2 * n), mono(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double l = i >= pad && i - pad < at44.size() ? gain * at44[i - pad] : 0.0;
    const double r = i >= pad + delay && i - pad - delay < at44.size()
                         ? 0.708 * gain * at44[i - pad - delay]
                         : 0.0;
    stereo[2 * i] = static_cast<float>(l) + noise(random);
    stereo[2 * i + 1] = static_cast<float>(r) + noise(random);
    mono[i] = 0.5f * (stereo[2 * i] + stereo[2 * i + 1]);
  }
  WriteSound(path, format, 44100, 2, stereo);
  return sas::surface::Resample(mono, 44100.0, 48000.0);
}

// The largest normalised cross-correlation of `a` and `b` over every lag (FFT, zero-padded).
double BestCorrelation(const std::vector<float>& a, const std::vector<float>& b) {
  std::size_t n = 1;
  while (n < a.size() + b.size()) n <<= 1;
  std::vector<double> ar(n, 0.0), ai(n, 0.0), br(n, 0.0), bi(n, 0.0);
  double ea = 0.0, eb = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) ar[i] = a[i], ea += double(a[i]) * a[i];
  for (std::size_t i = 0; i < b.size(); ++i) br[i] = b[i], eb += double(b[i]) * b[i];
  sas::test::FftInPlace(ar, ai);
  sas::test::FftInPlace(br, bi);
  // A * conj(B), then the inverse through the conjugate trick.
  std::vector<double> cr(n), ci(n);
  for (std::size_t k = 0; k < n; ++k) {
    cr[k] = ar[k] * br[k] + ai[k] * bi[k];
    ci[k] = -(ai[k] * br[k] - ar[k] * bi[k]);
  }
  sas::test::FftInPlace(cr, ci);
  double best = 0.0;
  for (std::size_t k = 0; k < n; ++k) best = std::max(best, cr[k] / static_cast<double>(n));
  return best / std::sqrt(ea * eb);
}

double PeakDb(const std::vector<float>& x) {
  float peak = 0.0f;
  for (const float v : x) peak = std::max(peak, std::fabs(v));
  return 20.0 * std::log10(static_cast<double>(peak));
}

std::size_t SyntheticFrames(const std::string& code, const std::string& key) {
  SF_INFO info{};
  SNDFILE* file = sf_open((std::string(SAS_CUES_DIR) + "/" + code + "/" + key + ".wav").c_str(),
                          SFM_READ, &info);
  REQUIRE(file != nullptr);
  sf_close(file);
  REQUIRE(info.samplerate == 48000);
  return static_cast<std::size_t>(info.frames);
}

// Every journal entry the kiosk's logger sends while it lives: fields as sd_journal_sendv gets
// them ("MESSAGE=...", "PRIORITY=4", ...).
class JournalCapture {
 public:
  JournalCapture() {
    sas::platform::DefaultLogger().SetJournalSender([this](const std::vector<std::string>& f) {
      entries_.push_back(f);
      return 0;
    });
  }
  ~JournalCapture() { sas::platform::DefaultLogger().SetJournalSender(nullptr); }
  JournalCapture(const JournalCapture&) = delete;
  JournalCapture& operator=(const JournalCapture&) = delete;

  // The messages logged at `priority` (4 warning, 6 info) that contain `text`.
  std::vector<std::string> At(int priority, const std::string& text) const {
    std::vector<std::string> found;
    for (const auto& fields : entries_) {
      if (fields.size() < 2 || fields[1] != "PRIORITY=" + std::to_string(priority)) continue;
      if (fields[0].find(text) != std::string::npos) found.push_back(fields[0]);
    }
    return found;
  }
  std::size_t Count(int priority) const { return At(priority, "").size(); }

 private:
  std::vector<std::vector<std::string>> entries_;
};

KioskConfig Config(const sas::test::TempDir& staff) {
  KioskConfig config;
  config.language = "en";
  config.visitor_languages = {"en", "de"};
  config.staff_dir = staff.path().string();
  return config;
}

}  // namespace

TEST_CASE(
    "a staff recording (44.1 kHz stereo FLAC) replaces its language's cue, levelled like "
    "the synthetic cues, and other cues and languages keep theirs",
    "[kiosk]") {
  sas::test::TempDir staff;
  fs::create_directories(staff.path() / "cues" / "de");
  fs::create_directories(staff.path() / "cues" / "en");
  // Recorded well under and over the cues' level, at other speeds than the kiosk's voices.
  const auto name_speech = Speak("de", 110, "Zerbrochenes Glas, von uns gesprochen.", staff.path());
  const auto name_heard =
      Record((staff.path() / "cues/de/broken_glass_name.flac").string(), name_speech, -14.0);
  staff.Write("cues/de/broken_glass_name.txt", "Zerbrochenes Glas, von uns gesprochen.\n");
  // A hot recording through a recorder's limiter: peaks at -0.5 dBFS, the speech pressed up
  // towards them.
  auto count_speech = Speak("en-gb", 220, "Three!", staff.path());
  const double drive = 4.0 * std::pow(10.0, -PeakDb(count_speech) / 20.0);
  for (auto& v : count_speech)
    v = static_cast<float>(0.944 * std::tanh(drive * v) / std::tanh(4.0));
  const auto count_heard =
      Record((staff.path() / "cues/en/count_3.flac").string(), count_speech, 0.0);
  // Far from the cues' -23 LUFS either way: the levelling has work to do.
  const double name_lufs =
      sas::surface::KWeightedLoudnessDb(name_heard, 48000.0, 0, name_heard.size());
  const double count_lufs =
      sas::surface::KWeightedLoudnessDb(count_heard, 48000.0, 0, count_heard.size());
  INFO("recorded at " << name_lufs << " and " << count_lufs << " LUFS");
  REQUIRE(name_lufs < -29.0);
  REQUIRE(count_lufs > -17.0);

  JournalCapture journal;
  SpokenCues cues(Config(staff), kStringsDir, SAS_CUES_DIR, true, kTextures);
  const auto samples = cues.TakeClipSamples();
  const auto clip = [&](const sas::kiosk::CuePick& pick) -> const std::vector<float>& {
    REQUIRE(pick.clip >= 0);
    return samples[static_cast<std::size_t>(pick.clip)].samples;
  };
  CHECK(cues.staff_cues_loaded() == 2);
  CHECK(journal.Count(4) == 0);
  CHECK(journal.At(6, "en: 1 staff cue from").size() == 1);
  CHECK(journal.At(6, "de: 1 staff cue from").size() == 1);

  // English: the count is the recording (no .txt: the table's sentence is reported), the other
  // cues are the synthetic files, sample for sample in length.
  const auto three = cues.ForMessage("count_3");
  const auto& count = clip(three);
  CHECK(cues.clip_text(three.clip) == FromTable("en", "cues", "count_3"));
  CHECK(BestCorrelation(count, count_heard) > 0.97);
  CHECK(clip(cues.ForMessage("count_2")).size() == SyntheticFrames("en", "count_2"));
  CHECK(clip(cues.ForCue(Cue::kTextureName, 1)).size() ==
        SyntheticFrames("en", "broken_glass_name"));

  // German: the texture name is the recording, trimmed of its room noise, at the cues' loudness.
  REQUIRE(cues.NextLanguage());
  REQUIRE(cues.strings().code == "de");
  const auto pick = cues.ForCue(Cue::kTextureName, 1);
  const auto& name = clip(pick);
  CHECK(pick.key == "broken_glass_name");
  CHECK(cues.clip_text(pick.clip) == "Zerbrochenes Glas, von uns gesprochen.");
  CHECK(BestCorrelation(name, name_heard) > 0.97);
  const double speech_s = static_cast<double>(name_speech.size()) / 22050.0;
  const double name_s = static_cast<double>(name.size()) / 48000.0;
  INFO("espeak-ng's speech " << speech_s << " s, the cue " << name_s << " s");
  CHECK(name_s < speech_s + 0.1);  // the 0.8 s of room noise are gone...
  CHECK(name_s > 0.7 * speech_s);  // ...the speech is not
  const auto& synthetic = clip(cues.ForCue(Cue::kTextureName, 0));
  CHECK(synthetic.size() == SyntheticFrames("de", "bubble_wrap_name"));
  for (const auto* x : {&name, &count}) {
    const double lufs = sas::surface::KWeightedLoudnessDb(*x, 48000.0, 0, x->size());
    const double synthetic_lufs =
        sas::surface::KWeightedLoudnessDb(synthetic, 48000.0, 0, synthetic.size());
    INFO("staff cue " << lufs << " LUFS, a synthetic one " << synthetic_lufs);
    CHECK(std::fabs(lufs - synthetic_lufs) < 0.5);
    CHECK(std::fabs(lufs - (-23.0)) < 0.5);
    CHECK(PeakDb(*x) <= -1.0 + 1e-4);
  }
  CHECK(clip(cues.ForMessage("count_3")).size() == SyntheticFrames("de", "count_3"));
}

TEST_CASE(
    "the kiosk plays a staff recording for its language and key, reports its sentence and "
    "counts it on the staff panel",
    "[kiosk]") {
  sas::test::TempDir staff;
  fs::create_directories(staff.path() / "cues" / "de");
  // The language key speaks the new language's own name.
  const auto heard = Record((staff.path() / "cues/de/language.wav").string(),
                            Speak("de", 120, "Deutsch, bitte.", staff.path()), -10.0,
                            SF_FORMAT_WAV | SF_FORMAT_PCM_24);
  sas::kiosk::KioskEngineOptions options;
  options.virtual_clock = true;
  options.texture_paths = {sas::kiosk::FindTextureFile("broken_glass")};  // one loads faster
  options.cues_dir = SAS_CUES_DIR;
  options.config = Config(staff);
  sas::kiosk::KioskEngine engine(options);
  std::vector<sas::kiosk::CueEvent> events;
  engine.SetCueObserver([&](const sas::kiosk::CueEvent& cue) { events.push_back(cue); });
  engine.SetAudioRunning(true);
  CHECK(engine.staff_cues_loaded() == 1);
  // On the attract screen the first press keeps the language being shown (English here); the
  // second steps to German.
  REQUIRE(engine.NextLanguage(0));
  REQUIRE(events.size() == 1);
  CHECK(events[0].language == "en");
  events.clear();
  REQUIRE(engine.NextLanguage(0));
  REQUIRE(events.size() == 1);
  CHECK(events[0].language == "de");
  CHECK(events[0].key == "language");
  CHECK(events[0].text == FromTable("de", "cues", "language"));  // no .txt of its own
  std::vector<float> block(2 * 128), speaker;
  for (std::size_t frames = 0; frames < heard.size(); frames += 128) {
    engine.audio().Render(block.data(), 128, 2);
    for (std::size_t i = 0; i < 128; ++i) speaker.push_back(block[2 * i]);
  }
  CHECK(BestCorrelation(speaker, heard) > 0.95);

  // Staff see it on the panel's textures line, beside the count of cues.
  sas::platform::Logger log;
  log.SetEchoToStderr(false);
  sas::platform::DeviceStatusBoard board{log};
  sas::kiosk::ReportTextures(board, engine);  // as the live kiosk does at start
  sas::platform::OfflineAudioOutput output(engine.audio(), sas::platform::AudioOutputConfig{});
  sas::platform::SwitchInputs switches;
  sas::platform::TokenSelector selector;
  int counted = 0;
  for (const auto& line : sas::kiosk::StaffPanelLines(
           {&engine, &output, &board, &switches, &selector, false, {}, "", 128, 48000})) {
    if (line.text.find(" spoken cues") != std::string::npos) {
      ++counted;
      CHECK_THAT(line.text, Catch::Contains(" spoken cues (1 staff-recorded)"));
    }
  }
  CHECK(counted == 1);
}

TEST_CASE(
    "a malformed staff cue is refused with one journal warning naming it and why, and the "
    "synthetic cue is kept",
    "[kiosk]") {
  sas::test::TempDir staff;
  const fs::path en = staff.path() / "cues" / "en";
  fs::create_directories(en);
  const auto speech = Speak("en", 140, "Bubble wrap.", staff.path());
  const std::string good = (staff.path() / "good.wav").string();
  Record(good, speech, 0.0, SF_FORMAT_WAV | SF_FORMAT_PCM_16);
  std::string wav;
  {
    std::ifstream in(good, std::ios::binary);
    wav.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  fs::remove(good);
  // What each file is, its name, and what its warning must say.
  struct Bad {
    std::string file, why, instead = "the synthetic cue is kept";
  };
  std::vector<Bad> bad;
  staff.Write("cues/en/bubble_wrap_name.wav", wav.substr(0, 20));
  bad.push_back({"en/bubble_wrap_name.wav", "not a readable sound file"});  // a cut-off header
  {
    std::mt19937 random(3);
    std::string noise(4000, '\0');
    for (auto& c : noise) c = static_cast<char>(random());
    staff.Write("cues/en/broken_glass_name.wav", noise);
    bad.push_back({"en/broken_glass_name.wav", "not a readable sound file"});
  }
  fs::create_directories(en / "wooden_board_name.wav");
  bad.push_back({"en/wooden_board_name.wav", "a folder, not a sound file"});
  WriteSound((en / "cracked_ground_name.wav").string(), SF_FORMAT_WAV | SF_FORMAT_PCM_16, 48000, 1,
             std::vector<float>(48000, 0.0f));
  bad.push_back({"en/cracked_ground_name.wav", "silent"});
  // The invitation's length where a count belongs (numbers are a second apart).
  Record((en / "count_3.flac").string(),
         Speak("en", 140, "Scratch the picture with the pen and listen.", staff.path()), 0.0);
  bad.push_back({"en/count_3.flac", "a count_3 cue must be 0.15-1.0 s"});
  staff.Write("cues/en/wooden_bord_name.wav", wav);  // a typo
  bad.push_back({"en/wooden_bord_name.wav", "\"wooden_bord_name\" is no cue key"});
  {  // the same speech 30 dB hotter, hard clipped
    std::vector<float> hot = sas::surface::Resample(speech, 22050.0, 48000.0);
    for (auto& v : hot) v = std::clamp(v * 31.6f, -1.0f, 1.0f);
    WriteSound((en / "too_loud.wav").string(), SF_FORMAT_WAV | SF_FORMAT_FLOAT, 48000, 1, hot);
    bad.push_back({"en/too_loud.wav", "clipped"});
  }
  Record((en / "voice_ready.wav").string(), speech, -45.0, SF_FORMAT_WAV | SF_FORMAT_FLOAT);
  bad.push_back({"en/voice_ready.wav", "too quiet to be speech"});
  {  // quiet speech and a knock on the microphone at nearly full scale
    std::vector<float> knocked = speech;
    for (std::size_t i = 0; i < knocked.size(); ++i) knocked[i] *= 0.1f;
    for (std::size_t i = 0; i < 22; ++i) knocked[knocked.size() / 2 + i] = (i % 2 ? -0.95f : 0.95f);
    Record((en / "no_microphone.flac").string(), knocked, 0.0);
    bad.push_back({"en/no_microphone.flac", "a knock or click?"});
  }
  Record((en / "invitation.flac").string(), speech, 0.0);
  staff.Write("cues/en/invitation.wav", wav);
  bad.push_back(
      {"en/invitation.wav", "a second recording of invitation", "invitation.flac is used"});
  fs::create_directories(staff.path() / "cues" / "english");
  staff.Write("cues/english/count_1.wav", wav);
  bad.push_back({"english", "no language the kiosk knows", "nothing in it is used"});
  staff.Write("cues/count_2.wav", wav);
  bad.push_back({"cues/count_2.wav", "not in a language folder"});

  JournalCapture journal;
  SpokenCues cues(Config(staff), kStringsDir, SAS_CUES_DIR, true, kTextures);
  const auto samples = cues.TakeClipSamples();
  for (const auto& refused : bad) {
    INFO(refused.file);
    const auto lines = journal.At(4, refused.file);
    REQUIRE(lines.size() == 1);
    CHECK_THAT(lines[0], Catch::StartsWith("MESSAGE=warn cues: staff cue ") &&
                             Catch::Contains(refused.why) && Catch::EndsWith(refused.instead));
  }
  CHECK(journal.Count(4) == bad.size());
  // Only the first invitation (invitation.flac) was taken; every other cue is the synthetic file.
  CHECK(cues.staff_cues_loaded() == 1);
  CHECK(journal.At(6, "en: 1 staff cue from").size() == 1);
  const auto synthetic = [&](const sas::kiosk::CuePick& pick) {
    INFO(pick.key);
    REQUIRE(pick.clip >= 0);
    CHECK(samples[static_cast<std::size_t>(pick.clip)].samples.size() ==
          SyntheticFrames("en", pick.key));
  };
  for (int t = 0; t < 4; ++t) synthetic(cues.ForCue(Cue::kTextureName, t));
  for (const char* key :
       {"count_3", "count_2", "count_1", "too_loud", "voice_ready", "no_microphone"}) {
    synthetic(cues.ForMessage(key));
  }
  CHECK(samples[static_cast<std::size_t>(cues.ForMessage("invitation").clip)].samples.size() !=
        SyntheticFrames("en", "invitation"));
}

TEST_CASE(
    "a staff cue the kiosk's user may not read is refused saying so, and a missing staff "
    "folder is said once",
    "[kiosk]") {
  sas::test::TempDir staff;
  const fs::path de = staff.path() / "cues" / "de";
  fs::create_directories(de);
  Record((de / "voice_ready.flac").string(), Speak("de", 140, "Jetzt!", staff.path()), 0.0);
  Record((de / "invitation.flac").string(), Speak("de", 140, "Komm her!", staff.path()), 0.0);
  chmod((de / "voice_ready.flac").c_str(), 0600);  // copied by root with a strict umask
  // As root the file would be readable anyway: read as nobody, like the kiosk's own user.
  const bool root = geteuid() == 0;
  if (root) {
    for (const auto& dir : {staff.path(), staff.path() / "cues", de}) chmod(dir.c_str(), 0755);
    chmod((de / "invitation.flac").c_str(), 0644);
    REQUIRE(seteuid(65534) == 0);
  }
  JournalCapture journal;
  const auto cues =
      sas::kiosk::LoadStaffCues((staff.path() / "cues").string(), {"de"}, sas::kiosk::CueKeys(),
                                48000.0, sas::platform::DefaultLogger());
  if (root) REQUIRE(seteuid(0) == 0);
  const auto lines = journal.At(4, "de/voice_ready.flac");
  REQUIRE(lines.size() == 1);
  CHECK_THAT(lines[0], Catch::Contains("cannot be opened (Permission denied)") &&
                           Catch::Contains("chmod 644"));
  CHECK(journal.Count(4) == 1);
  REQUIRE(cues.count("de") == 1);
  CHECK(cues.at("de").count("voice_ready") == 0);
  CHECK(cues.at("de").count("invitation") == 1);  // its readable neighbour is taken

  // A staff folder the kiosk cannot see says so once, at info: nothing is wrong with a box whose
  // staff recorded nothing.
  const auto none =
      sas::kiosk::LoadStaffCues((staff.path() / "no" / "cues").string(), {"de"},
                                sas::kiosk::CueKeys(), 48000.0, sas::platform::DefaultLogger());
  CHECK(none.empty());
  CHECK(
      journal.At(6, "no staff cues: " + (staff.path() / "no" / "cues").string() + " does not exist")
          .size() == 1);
  CHECK(journal.Count(4) == 1);
}

TEST_CASE("a cue's duration bounds hold every synthetic cue and keep it from being cut off",
          "[kiosk]") {
  // Every shipped synthetic cue lies inside its kind's bounds (a staff recording as long as the
  // kiosk's own voice is never refused).
  for (const auto& code : sas::kiosk::KioskLanguages()) {
    for (const auto& entry : fs::directory_iterator(fs::path(SAS_CUES_DIR) / code)) {
      if (entry.path().extension() != ".wav") continue;
      const std::string key = entry.path().stem().string();
      INFO(code << "/" << key);
      const auto bounds = sas::kiosk::DurationLimitsFor(key);
      const double s = static_cast<double>(SyntheticFrames(code, key)) / 48000.0;
      CHECK(s >= bounds.min_s);
      CHECK(s <= 0.8 * bounds.max_s);
    }
  }
  // A cue that fits its bound is not cut off by the next one the session speaks: a number by the
  // next number, the countdown's sentence by "three".
  const sas::kiosk::SessionConfig session;
  const double countdown_s = sas::kiosk::KioskEngineOptions{}.countdown_s;
  CHECK(sas::kiosk::DurationLimitsFor("count_2").max_s <= session.count_step_s);
  CHECK(sas::kiosk::DurationLimitsFor("record_countdown").max_s <=
        countdown_s - session.tone_s - 3.0 * session.count_step_s);
}
#endif
