// The spoken cues' engines, shaping and committed renders (see cue_voice.h).
#include "cue_voice.h"

#include <dlfcn.h>
#include <fcntl.h>
#include <glob.h>
#include <sndfile.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include <toml++/toml.h>

#include "surface/audio_file.h"
#include "surface/loudness.h"
#include "surface/texture_file.h"

extern char** environ;

namespace sas::cues {
namespace {

namespace fs = std::filesystem;

// The first path matching a shell pattern, or "".
std::string FirstMatch(const std::string& pattern) {
  glob_t found{};
  std::string path;
  if (glob(pattern.c_str(), 0, nullptr, &found) == 0 && found.gl_pathc > 0) {
    path = found.gl_pathv[0];
  }
  globfree(&found);
  return path;
}

}  // namespace

std::vector<std::string> TextureFolders(const std::string& textures_dir) {
  std::vector<std::string> folders;
  for (const auto& entry : fs::directory_iterator(textures_dir)) {
    if (entry.is_directory() && fs::is_regular_file(entry.path() / "texture.toml")) {
      folders.push_back(entry.path().filename().string());
    }
  }
  std::sort(folders.begin(), folders.end());
  return folders;
}

std::vector<CueSentence> CueSentences(const kiosk::LanguageTable& table,
                                      const std::string& textures_dir) {
  std::vector<CueSentence> list;
  for (const auto& folder : TextureFolders(textures_dir)) {
    const auto texture =
        surface::LoadTextureFile((fs::path(textures_dir) / folder / "texture.toml").string());
    list.push_back({folder + "_name", table.CueText(folder + "_name", texture.name)});
    list.push_back(
        {folder + "_description", table.CueText(folder + "_description", texture.description)});
  }
  for (const auto& key : kiosk::CueKeys()) list.push_back({key, table.CueText(key)});
  return list;
}

void RunProgram(const std::vector<std::string>& args, const std::vector<std::string>& extra_env,
                const std::string& stdout_path) {
  std::vector<std::string> strings = args;
  std::vector<char*> argv;
  for (auto& arg : strings) argv.push_back(arg.data());
  argv.push_back(nullptr);
  // Later entries win in getenv's first-match search only if they come first: put ours ahead.
  std::vector<std::string> env_strings = extra_env;
  std::vector<char*> envp;
  for (auto& e : env_strings) envp.push_back(e.data());
  for (char** e = environ; *e != nullptr; ++e) envp.push_back(*e);
  envp.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (!stdout_path.empty()) {
    posix_spawn_file_actions_addopen(&actions, 1, stdout_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  }
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, args.at(0).c_str(), &actions, nullptr, argv.data(),
                                  envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) throw std::runtime_error("cannot run " + args[0]);
  int status = 0;
  if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error(args[0] + " failed for \"" + args.back() + "\"");
  }
}

Speech SpeakEspeak(const std::string& espeak, const std::string& voice, int wpm,
                   const std::string& text, const std::string& scratch_wav,
                   const std::string& data_path, const std::string& bin_path) {
  std::vector<std::string> args = {espeak};
  if (!data_path.empty()) args.push_back("--path=" + data_path);
  args.insert(args.end(), {"-v", voice, "-s", std::to_string(wpm), "-w", scratch_wav, text});
  std::vector<std::string> env;
  if (!bin_path.empty()) {
    const char* path = std::getenv("PATH");
    env.push_back("PATH=" + bin_path + ":" + (path != nullptr ? path : "/usr/bin:/bin"));
  }
  RunProgram(args, env);
  const Speech speech = ReadRender(scratch_wav);
  fs::remove(scratch_wav);
  return speech;
}

// --- SVOX Pico -------------------------------------------------------------------------------
// The few calls of libttspico's public C API (picoapi.h) that a text-to-PCM client needs, looked
// up at run time. pico_Status is a signed int; strings are unsigned char.
struct PicoSpeaker::Api {
  using Status = int;
  void* library = nullptr;
  void* system = nullptr;
  void* engine = nullptr;
  void* ta = nullptr;  // the voice's resources
  void* sg = nullptr;
  std::vector<unsigned char> memory;
  Status (*initialize)(void*, unsigned int, void**) = nullptr;
  Status (*terminate)(void**) = nullptr;
  Status (*load_resource)(void*, const unsigned char*, void**) = nullptr;
  Status (*unload_resource)(void*, void**) = nullptr;
  Status (*resource_name)(void*, void*, char*) = nullptr;
  Status (*create_voice)(void*, const unsigned char*) = nullptr;
  Status (*add_resource)(void*, const unsigned char*, const unsigned char*) = nullptr;
  Status (*release_voice)(void*, const unsigned char*) = nullptr;
  Status (*new_engine)(void*, const unsigned char*, void**) = nullptr;
  Status (*dispose_engine)(void*, void**) = nullptr;
  Status (*put_text)(void*, const unsigned char*, short, short*) = nullptr;
  Status (*get_data)(void*, void*, short, short*, short*) = nullptr;

  template <typename F>
  void Bind(F& f, const char* name) {
    void* symbol = dlsym(library, name);
    if (symbol == nullptr) throw std::runtime_error(std::string("libttspico: no ") + name);
    f = reinterpret_cast<F>(symbol);
  }
};

namespace {
constexpr int kPicoOk = 0;
constexpr int kPicoStepBusy = 201;
constexpr unsigned int kPicoMemoryBytes = 2500000;  // what Pico's own pico2wave gives it
constexpr double kPicoRateHz = 16000.0;
const auto* const kPicoVoiceName = reinterpret_cast<const unsigned char*>("cue_voice");
}  // namespace

PicoSpeaker::PicoSpeaker(const std::string& root) : api_(std::make_unique<Api>()) {
  const std::string library = FirstMatch(root + "/usr/lib/*/libttspico.so.0");
  lang_dir_ = root + "/usr/share/pico/lang";
  if (library.empty() || !fs::is_directory(lang_dir_)) {
    throw std::runtime_error("no SVOX Pico under " + root +
                             " (textures/voices/fetch_engines.sh unpacks it)");
  }
  api_->library = dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (api_->library == nullptr) throw std::runtime_error("cannot open " + library);
  api_->Bind(api_->initialize, "pico_initialize");
  api_->Bind(api_->terminate, "pico_terminate");
  api_->Bind(api_->load_resource, "pico_loadResource");
  api_->Bind(api_->unload_resource, "pico_unloadResource");
  api_->Bind(api_->resource_name, "pico_getResourceName");
  api_->Bind(api_->create_voice, "pico_createVoiceDefinition");
  api_->Bind(api_->add_resource, "pico_addResourceToVoiceDefinition");
  api_->Bind(api_->release_voice, "pico_releaseVoiceDefinition");
  api_->Bind(api_->new_engine, "pico_newEngine");
  api_->Bind(api_->dispose_engine, "pico_disposeEngine");
  api_->Bind(api_->put_text, "pico_putTextUtf8");
  api_->Bind(api_->get_data, "pico_getData");
  api_->memory.resize(kPicoMemoryBytes);
}

PicoSpeaker::~PicoSpeaker() {
  Unload();
  if (api_->library != nullptr) dlclose(api_->library);
}

void PicoSpeaker::Unload() {
  Api& api = *api_;
  if (api.system == nullptr) return;
  if (api.engine != nullptr) api.dispose_engine(api.system, &api.engine);
  api.release_voice(api.system, kPicoVoiceName);
  if (api.sg != nullptr) api.unload_resource(api.system, &api.sg);
  if (api.ta != nullptr) api.unload_resource(api.system, &api.ta);
  api.terminate(&api.system);
  api.system = nullptr;
  api.engine = api.sg = api.ta = nullptr;
  voice_.clear();
}

void PicoSpeaker::Load(const std::string& voice) {
  // A voice is two resources: the language's text analysis (<lang>_ta.bin) and its speaker's
  // signal generation (<lang>_<speaker>_sg.bin). A new system per voice: Pico's fixed memory pool
  // does not take a third language after two were unloaded from it.
  const std::string ta = lang_dir_ + "/" + voice + "_ta.bin";
  const std::string sg = FirstMatch(lang_dir_ + "/" + voice + "_*_sg.bin");
  if (!fs::is_regular_file(ta) || sg.empty()) {
    throw std::runtime_error("SVOX Pico has no voice " + voice + " in " + lang_dir_);
  }
  Unload();
  Api& api = *api_;
  auto check = [](int status, const char* what) {
    if (status != kPicoOk) throw std::runtime_error(std::string("SVOX Pico: ") + what + " failed");
  };
  check(api.initialize(api.memory.data(), kPicoMemoryBytes, &api.system), "starting");
  char ta_name[200] = {};
  char sg_name[200] = {};
  check(api.load_resource(api.system, reinterpret_cast<const unsigned char*>(ta.c_str()), &api.ta),
        "loading the text analysis");
  check(api.load_resource(api.system, reinterpret_cast<const unsigned char*>(sg.c_str()), &api.sg),
        "loading the signal generation");
  check(api.resource_name(api.system, api.ta, ta_name), "naming a resource");
  check(api.resource_name(api.system, api.sg, sg_name), "naming a resource");
  check(api.create_voice(api.system, kPicoVoiceName), "creating the voice");
  check(api.add_resource(api.system, kPicoVoiceName, reinterpret_cast<unsigned char*>(ta_name)),
        "adding a resource");
  check(api.add_resource(api.system, kPicoVoiceName, reinterpret_cast<unsigned char*>(sg_name)),
        "adding a resource");
  check(api.new_engine(api.system, kPicoVoiceName, &api.engine), "starting the engine");
  voice_ = voice;
}

Speech PicoSpeaker::Speak(const std::string& voice, const std::string& text, int rate_percent) {
  if (voice != voice_) Load(voice);
  Api& api = *api_;
  Speech speech;
  speech.rate_hz = kPicoRateHz;
  // Pico's markup sets the speed; the sentence itself stays as the table has it.
  const std::string marked =
      rate_percent == 100
          ? text
          : "<speed level=\"" + std::to_string(rate_percent) + "\">" + text + "</speed>";
  // The text goes in with its terminating zero, which tells Pico the input is complete.
  const auto* next = reinterpret_cast<const unsigned char*>(marked.c_str());
  auto left = static_cast<short>(marked.size() + 1);
  short pcm[512];
  while (left > 0) {
    short put = 0;
    if (api.put_text(api.engine, next, left, &put) != kPicoOk) {
      throw std::runtime_error("SVOX Pico: taking the text failed");
    }
    left = static_cast<short>(left - put);
    next += put;
    int status = 0;
    do {
      short bytes = 0, type = 0;
      status = api.get_data(api.engine, pcm, static_cast<short>(sizeof pcm), &bytes, &type);
      for (int i = 0; i < bytes / 2; ++i) {
        speech.samples.push_back(static_cast<float>(pcm[i]) / 32768.0f);
      }
    } while (status == kPicoStepBusy);
  }
  if (speech.samples.empty()) throw std::runtime_error("SVOX Pico said nothing for \"" + text + "\"");
  return speech;
}

std::vector<float> ShapeCue(const Speech& speech) {
  std::vector<float> x = speech.rate_hz == kCueRateHz
                             ? speech.samples
                             : surface::Resample(speech.samples, speech.rate_hz, kCueRateHz);
  try {
    return surface::ShapeCue(std::move(x), kCueRateHz).samples;
  } catch (const std::runtime_error&) {
    throw std::runtime_error("the engine produced silence");
  }
}

RenderChoice ChooseRender(const std::string& renders_dir, const std::string& language,
                          const std::string& key, const std::string& text) {
  RenderChoice choice;
  const fs::path base = fs::path(renders_dir) / language / key;
  choice.audio_path = base.string() + ".opus";
  const std::string text_path = base.string() + ".txt";
  if (renders_dir.empty() || !fs::is_regular_file(choice.audio_path) ||
      !fs::is_regular_file(text_path)) {
    choice.why = "no render";
  } else if (ReadText(text_path) != text) {
    choice.why = "sentence changed";
  } else {
    choice.use_render = true;
  }
  return choice;
}

void WriteRender(const std::string& audio_path, const Speech& speech) {
  SF_INFO info{};
  info.samplerate = static_cast<int>(speech.rate_hz);
  info.channels = 1;
  info.format = SF_FORMAT_OGG | SF_FORMAT_OPUS;
  SNDFILE* file = sf_open(audio_path.c_str(), SFM_WRITE, &info);
  if (file == nullptr) throw std::runtime_error("cannot write " + audio_path + ": " + sf_strerror(nullptr));
  // libsndfile maps the compression level linearly onto Opus's bit rates, from its highest (0)
  // down to 6 kb/s per channel (1); constant bit rate keeps the committed size predictable.
  int mode = SF_BITRATE_MODE_CONSTANT;
  sf_command(file, SFC_SET_BITRATE_MODE, &mode, sizeof mode);
  double level = 1.0 - (kRenderBitrate - 6000.0) / (256000.0 - 6000.0);
  sf_command(file, SFC_SET_COMPRESSION_LEVEL, &level, sizeof level);
  const auto frames = static_cast<sf_count_t>(speech.samples.size());
  const sf_count_t written = sf_writef_float(file, speech.samples.data(), frames);
  sf_close(file);
  if (written != frames) throw std::runtime_error("cannot write " + audio_path);
}

Speech ReadRender(const std::string& audio_path) {
  surface::AudioReadLimits limits;
  const SF_INFO probe = [&] {
    SF_INFO info{};
    SNDFILE* file = sf_open(audio_path.c_str(), SFM_READ, &info);
    if (file == nullptr) throw std::runtime_error("cannot read " + audio_path);
    sf_close(file);
    return info;
  }();
  // Read at the file's own rate: the cue is resampled once, in ShapeCue.
  limits.target_rate_hz = static_cast<double>(probe.samplerate);
  const auto clip = surface::ReadAudioFile(audio_path, limits);
  return {clip.samples, clip.sample_rate_hz};
}

std::map<std::string, std::string> LoadPicoChoice(const std::string& path) {
  const toml::table root = toml::parse_file(path);
  std::map<std::string, std::string> choice;
  if (const toml::table* pico = root["pico"].as_table()) {
    for (const auto& [code, voice] : *pico) {
      const auto name = voice.value<std::string>();
      if (!name) throw std::runtime_error(path + ": pico." + std::string(code.str()) + ": not a string");
      choice[std::string(code.str())] = *name;
    }
  }
  return choice;
}

std::map<std::string, int> LoadPicoRates(const std::string& path) {
  const toml::table root = toml::parse_file(path);
  std::map<std::string, int> rates;
  if (const toml::table* table = root["rate_percent"].as_table()) {
    for (const auto& [key, value] : *table) {
      const auto percent = value.value<std::int64_t>();
      if (!percent || *percent < 50 || *percent > 200) {
        throw std::runtime_error(path + ": rate_percent." + std::string(key.str()) +
                                 ": a whole number from 50 to 200");
      }
      rates[std::string(key.str())] = static_cast<int>(*percent);
    }
  }
  return rates;
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream all;
  all << in.rdbuf();
  std::string text = all.str();
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  return text;
}

void WriteText(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text << "\n";
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace sas::cues
