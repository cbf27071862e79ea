// The per-language string tables (see strings.h).
#include "files/strings.h"

#include "surface/cue_library.h"

#include <toml++/toml.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

namespace sas::kiosk {
namespace {

std::string Where(const std::string& file, const toml::node& node, const std::string& key) {
  return file + ":" + std::to_string(node.source().begin.line) + ": " + key + ": ";
}

// Reads a table of non-empty strings; with `required`, exactly those keys.
std::map<std::string, std::string> Strings(const toml::table& root, const std::string& file,
                                           const std::string& table,
                                           const std::vector<std::string>* required) {
  std::map<std::string, std::string> values;
  const toml::table* node = root[table].as_table();
  if (node == nullptr) {
    if (required == nullptr) return values;
    throw std::runtime_error(file + ": no [" + table + "] table");
  }
  for (const auto& [key, value] : *node) {
    const std::string name = table + "." + std::string(key.str());
    const auto text = value.value<std::string>();
    if (!value.is_string() || !text || text->empty()) {
      throw std::runtime_error(Where(file, value, name) + "expected a non-empty string");
    }
    if (required != nullptr &&
        std::find(required->begin(), required->end(), std::string(key.str())) == required->end()) {
      throw std::runtime_error(Where(file, value, name) + "unknown key");
    }
    values[std::string(key.str())] = *text;
  }
  if (required != nullptr) {
    for (const auto& key : *required) {
      if (!values.count(key))
        throw std::runtime_error(file + ": " + table + "." + key + ": missing");
    }
  }
  return values;
}

}  // namespace

const std::vector<std::string>& KioskLanguages() {
  static const std::vector<std::string> codes = {"en", "de", "fr", "it", "es"};
  return codes;
}

const std::vector<std::string>& CueKeys() {
  return surface::MessageCueNames();  // the cue files' one list
}

const std::vector<std::string>& ScreenKeys() {
  static const std::vector<std::string> keys = {
      "countdown",   "recording", "meter_louder", "meter_good",    "meter_too_loud",
      "voice_ready", "too_quiet", "too_loud",     "no_microphone", "voice_surface", "recording_sign"};
  return keys;
}

const std::vector<std::string>& InvitationParts() {
  static const std::vector<std::string> parts = {"scratch", "rest",   "roll",
                                                 "token",   "record", "language"};
  return parts;
}

std::string SpokenInvitation(const std::map<std::string, std::string>& parts) {
  std::string sentence;
  for (const auto& part : InvitationParts()) {
    const auto found = parts.find(part);
    if (found == parts.end()) continue;
    if (!sentence.empty()) sentence += ", ";
    sentence += found->second;
  }
  return sentence.empty() ? sentence : sentence + ".";
}

const std::string& LanguageTable::Screen(const std::string& key) const {
  static const std::string kNone;
  const auto found = screen.find(key);
  return found == screen.end() ? kNone : found->second;
}

const std::string& LanguageTable::Invitation(const std::string& part) const {
  static const std::string kNone;
  const auto found = invitation.find(part);
  return found == invitation.end() ? kNone : found->second;
}

std::string LanguageTable::CueText(const std::string& key,
                                   const std::string& texture_fallback) const {
  if (const auto found = cues.find(key); found != cues.end()) return found->second;
  if (const auto found = textures.find(key); found != textures.end()) return found->second;
  return texture_fallback;
}

LanguageTable LoadLanguageTable(const std::string& dir, const std::string& code) {
  const std::string file = (std::filesystem::path(dir) / (code + ".toml")).string();
  toml::table root;
  try {
    root = toml::parse_file(file);
  } catch (const toml::parse_error& error) {
    throw std::runtime_error(file + ":" + std::to_string(error.source().begin.line) + ": " +
                             std::string(error.description()));
  }
  for (const auto& [key, node] : root) {
    const std::string name(key.str());
    if (name != "voice" && name != "cues" && name != "screen" && name != "textures" &&
        name != "invitation") {
      throw std::runtime_error(Where(file, node, name) + "unknown table");
    }
  }
  LanguageTable table;
  table.code = code;
  const toml::table* voice = root["voice"].as_table();
  if (voice == nullptr) throw std::runtime_error(file + ": no [voice] table");
  table.language_name = (*voice)["language_name"].value_or(std::string());
  table.espeak_voice = (*voice)["espeak_voice"].value_or(std::string());
  table.words_per_minute =
      static_cast<int>((*voice)["words_per_minute"].value_or(std::int64_t{160}));
  if (table.language_name.empty() || table.espeak_voice.empty()) {
    throw std::runtime_error(file + ": voice.language_name and voice.espeak_voice are required");
  }
  if (table.words_per_minute < 80 || table.words_per_minute > 450) {
    throw std::runtime_error(file + ": voice.words_per_minute: out of range [80, 450]");
  }
  // The spoken invitation is made of the [invitation] parts, not written out in [cues].
  std::vector<std::string> written_cues = CueKeys();
  std::erase(written_cues, std::string("invitation"));
  table.cues = Strings(root, file, "cues", &written_cues);
  table.invitation = Strings(root, file, "invitation", &InvitationParts());
  table.cues["invitation"] = SpokenInvitation(table.invitation);
  table.screen = Strings(root, file, "screen", &ScreenKeys());
  table.textures = Strings(root, file, "textures", nullptr);
  return table;
}

}  // namespace sas::kiosk
