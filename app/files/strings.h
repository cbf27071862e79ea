#pragma once
// What the kiosk says and shows, one table per language (textures/strings/<code>.toml, installed
// to share/sketch-a-scratch/strings): the espeak-ng voice, the spoken cues' sentences (made into
// WAVs at build time by textures/cue_maker), the on-screen texts and the textures' names and
// descriptions. English texture names and descriptions are each texture's own texture.toml, so a
// table's [textures] may leave them out. Every table has every cue and screen key: a visitor
// never meets a missing sentence, in any language. Set-up only.

#include <map>
#include <string>
#include <vector>

namespace sas::kiosk {

// The languages the kiosk ships, in the order a visitor's language key steps through them.
const std::vector<std::string>& KioskLanguages();
// Cue keys (file name without .wav) every table has, in a fixed order.
const std::vector<std::string>& CueKeys();
// On-screen text keys every table has.
const std::vector<std::string>& ScreenKeys();
// The invitation's parts every table has ([invitation]), in the order they are spoken: the attract
// screen shows them one a line, and the spoken invitation (cue "invitation") is made of them, so
// what a visitor reads and what a blind visitor hears name the same things.
const std::vector<std::string>& InvitationParts();
// The spoken invitation from its parts: one sentence, the parts joined by commas. A full stop
// between them makes espeak-ng pause about 0.3 s longer each time, and every language's
// invitation must fit in the one-minute attract cycle.
std::string SpokenInvitation(const std::map<std::string, std::string>& parts);

struct LanguageTable {
  std::string code;           // "en"
  std::string language_name;  // how it names itself: "Deutsch"
  std::string espeak_voice;
  int words_per_minute = 160;
  std::map<std::string, std::string> cues;        // CueKeys()
  std::map<std::string, std::string> screen;      // ScreenKeys()
  std::map<std::string, std::string> invitation;  // InvitationParts()
  std::map<std::string, std::string> textures;    // "<folder>_name", "<folder>_description"

  // The on-screen text for `key` ("" for a key no table has).
  const std::string& Screen(const std::string& key) const;
  // One part of the invitation ("" for a part no table has).
  const std::string& Invitation(const std::string& part) const;
  // The sentence a cue file holds: a message (CueKeys()) or "<folder>_name/_description"
  // (from [textures], else `texture_fallback`).
  std::string CueText(const std::string& key, const std::string& texture_fallback = {}) const;
};

// Reads <dir>/<code>.toml. Throws std::runtime_error ("<file>:<line>: <key>: <what>") on a syntax
// error, a missing, empty or unknown key.
LanguageTable LoadLanguageTable(const std::string& dir, const std::string& code);

}  // namespace sas::kiosk
