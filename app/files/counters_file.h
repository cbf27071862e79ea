#pragma once
// Persistence of the anonymous usage counters (strokes per texture, recordings, visits) shown on
// the staff panel. No single fault may lower them:
//  - every save writes the file and then an identical `<file>.backup`, each with AtomicWriteFile,
//    so a crash, a full disk or damage to one copy leaves the other whole;
//  - the file is read with toml++ and, where that fails (truncation, binary junk, a bad value),
//  line
//    by line, salvaging every `key = count` that is intact; each count is the larger of what the
//    file and the backup hold;
//  - a damaged file is renamed aside with a timestamp (`<file>.damaged-YYYYMMDD-HHMMSS`) before the
//    first save, never overwritten, and one journal line says what was wrong and what was kept.

#include <cstdint>
#include <string>
#include <vector>

namespace sas::kiosk {

// Anonymous usage counters shown on the staff panel (and persisted by the wiring).
// Counts stop at the largest TOML integer (2^63 - 1) instead of wrapping to zero, so the file
// stays valid TOML and a count never goes down.
inline constexpr std::uint64_t kMaxUsageCount = 0x7fffffffffffffffULL;
inline void CountOne(std::uint64_t& count) {
  if (count < kMaxUsageCount) ++count;
}

struct UsageCounters {
  std::vector<std::uint64_t> strokes_per_texture;  // pen-down strokes on each texture
  std::uint64_t voice_strokes = 0;
  std::uint64_t recordings = 0;  // good recordings that became a surface
  std::uint64_t failed_recordings = 0;
  std::uint64_t sessions = 0;  // visits: first pen contact after the attract screen

  bool operator==(const UsageCounters&) const = default;
};

// Plain text, one `key = value` per line (valid TOML), texture names as keys.
std::string FormatCounters(const UsageCounters& counters,
                           const std::vector<std::string>& texture_names);

// What could be read from one counters text.
struct CountersSalvage {
  UsageCounters counters;             // zero where nothing was read
  std::vector<bool> found;            // per field, in CounterFieldNames() order
  std::vector<std::string> problems;  // "<source>:<line>: <what>", empty when the text is whole
};

// The field names in file order: sessions, recordings, failed_recordings, voice_strokes, then
// strokes.<texture> for each texture name.
std::vector<std::string> CounterFieldNames(const std::vector<std::string>& texture_names);

// Reads everything that is intact; never throws. Unknown texture names are not problems (a texture
// was swapped); an empty text is (the kiosk never writes one).
CountersSalvage SalvageCounters(const std::string& text,
                                const std::vector<std::string>& texture_names,
                                const std::string& source_name);

// Writes `path`, then `path.backup`; false (and the reason) when `path` could not be written.
bool SaveCounters(const std::string& path, const UsageCounters& counters,
                  const std::vector<std::string>& texture_names, std::string* error);

// Read-only load of `path` alone (tests and tools). Missing file: zeros and true. Damaged file:
// what could be salvaged, false and the first problem in `error`.
bool LoadCounters(const std::string& path, const std::vector<std::string>& texture_names,
                  UsageCounters* counters, std::string* error);

// The kiosk's start-up load (see the top of this file); it first removes the temporaries a kill in
// the middle of a save left next to the file or its backup.
struct CountersRecovery {
  UsageCounters counters;
  std::string report;    // empty when the file was whole or absent; else one journal line
  bool may_save = true;  // false: a damaged file could not be moved aside, so must not be replaced
};
CountersRecovery RecoverCounters(const std::string& path,
                                 const std::vector<std::string>& texture_names);

}  // namespace sas::kiosk
