// Usage counters file (see counters_file.h).
#include "files/counters_file.h"

#include <sys/stat.h>

#include <toml++/toml.h>
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>

#include "files/atomic_file.h"

namespace sas::kiosk {
namespace {

constexpr const char* kStrokePrefix = "strokes.";
constexpr std::size_t kFixedFields = 4;

std::string Trim(const std::string& text) {
  const auto begin = text.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  const auto end = text.find_last_not_of(" \t\r");
  return text.substr(begin, end - begin + 1);
}

std::uint64_t* Field(UsageCounters& counters, std::size_t index) {
  switch (index) {
    case 0:
      return &counters.sessions;
    case 1:
      return &counters.recordings;
    case 2:
      return &counters.failed_recordings;
    case 3:
      return &counters.voice_strokes;
    default:
      return &counters.strokes_per_texture[index - kFixedFields];
  }
}

// Index of `key` in CounterFieldNames order; -1 for a texture we do not know, -2 for anything else.
int FieldIndex(const std::string& key, const std::vector<std::string>& names) {
  static const char* const kFixed[kFixedFields] = {"sessions", "recordings", "failed_recordings",
                                                   "voice_strokes"};
  for (std::size_t i = 0; i < kFixedFields; ++i) {
    if (key == kFixed[i]) return static_cast<int>(i);
  }
  if (key.rfind(kStrokePrefix, 0) != 0) return -2;
  const std::string name = key.substr(std::strlen(kStrokePrefix));
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return static_cast<int>(kFixedFields + i);
  }
  return name.empty() ? -2 : -1;
}

CountersSalvage Empty(const std::vector<std::string>& names) {
  CountersSalvage salvage;
  salvage.counters.strokes_per_texture.assign(names.size(), 0);
  salvage.found.assign(kFixedFields + names.size(), false);
  return salvage;
}

// A key given twice keeps the larger count: which one is stale cannot be told, and a count only
// ever grows.
void Take(CountersSalvage& salvage, int index, std::uint64_t value) {
  std::uint64_t& count = *Field(salvage.counters, static_cast<std::size_t>(index));
  const auto i = static_cast<std::size_t>(index);
  count = salvage.found[i] ? std::max(count, std::min(value, kMaxUsageCount))
                           : std::min(value, kMaxUsageCount);
  salvage.found[i] = true;
}

// The usual path: a well-formed TOML file (comments, hand edits, [strokes] tables all fine).
void FromToml(const toml::table& root, const std::vector<std::string>& names,
              const std::string& source, CountersSalvage& salvage) {
  const auto where = [&](const toml::node& node) {
    return source + ":" + std::to_string(node.source().begin.line) + ": ";
  };
  const auto take = [&](const std::string& key, const toml::node& node) {
    const int index = FieldIndex(key, names);
    if (index == -1) return;  // a texture swapped out: not ours to judge
    if (index == -2) {
      salvage.problems.push_back(where(node) + key + ": unknown key");
      return;
    }
    const auto value = node.value<std::int64_t>();
    if (!node.is_integer() || !value || *value < 0) {
      salvage.problems.push_back(where(node) + key + ": not a whole number");
      return;
    }
    Take(salvage, index, static_cast<std::uint64_t>(*value));
  };
  for (const auto& [key, node] : root) {
    const std::string name(key.str());
    if (name == "strokes" && node.is_table()) {
      for (const auto& [texture, count] : *node.as_table()) {
        take(kStrokePrefix + std::string(texture.str()), count);
      }
    } else {
      take(name, node);
    }
  }
}

// When toml++ cannot read the file: keep every `key = count` line that is intact. A last line with
// no newline may have been cut inside its number (5000 -> 50), so it is not trusted.
void FromLines(const std::string& text, const std::vector<std::string>& names,
               const std::string& source, CountersSalvage& salvage) {
  std::size_t start = 0;
  int line_number = 0;
  while (start < text.size()) {
    ++line_number;
    const auto newline = text.find('\n', start);
    const bool complete = newline != std::string::npos;
    std::string line = text.substr(start, complete ? newline - start : std::string::npos);
    start = complete ? newline + 1 : text.size();
    const auto where = source + ":" + std::to_string(line_number) + ": ";
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    line = Trim(line);
    if (line.empty()) continue;
    const auto equals = line.find('=');
    if (equals == std::string::npos) {
      salvage.problems.push_back(where + "expected key = value");
      continue;
    }
    const std::string key = Trim(line.substr(0, equals));
    const std::string value_text = Trim(line.substr(equals + 1));
    std::uint64_t value = 0;
    const auto [end, ec] =
        std::from_chars(value_text.data(), value_text.data() + value_text.size(), value);
    const int index = FieldIndex(key, names);
    if (index == -2) {
      salvage.problems.push_back(where + "unknown key");
    } else if (ec == std::errc::result_out_of_range) {
      salvage.problems.push_back(where + key + ": larger than any count; kept as the largest");
      if (index >= 0) Take(salvage, index, kMaxUsageCount);
    } else if (ec != std::errc() || end != value_text.data() + value_text.size()) {
      salvage.problems.push_back(where + key + ": not a whole number");
    } else if (!complete) {
      salvage.problems.push_back(where + key + ": cut off (no end of line); not trusted");
    } else if (index >= 0) {
      Take(salvage, index, value);
    }
  }
}

enum class ReadResult { kMissing, kRead, kUnreadable };

ReadResult ReadFile(const std::string& path, std::string* text, std::string* why) {
  struct stat info {};
  if (stat(path.c_str(), &info) != 0) {
    if (errno == ENOENT) return ReadResult::kMissing;
    *why = std::strerror(errno);
    return ReadResult::kUnreadable;
  }
  if (!S_ISREG(info.st_mode)) {
    *why = "not a regular file";
    return ReadResult::kUnreadable;
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    *why = std::strerror(errno);
    return ReadResult::kUnreadable;
  }
  std::ostringstream contents;
  contents << file.rdbuf();
  *text = contents.str();
  return ReadResult::kRead;
}

std::string BackupPath(const std::string& path) {
  return path + ".backup";
}

}  // namespace

std::vector<std::string> CounterFieldNames(const std::vector<std::string>& texture_names) {
  std::vector<std::string> fields = {"sessions", "recordings", "failed_recordings",
                                     "voice_strokes"};
  for (const auto& name : texture_names) fields.push_back(kStrokePrefix + name);
  return fields;
}

std::string FormatCounters(const UsageCounters& counters,
                           const std::vector<std::string>& texture_names) {
  std::ostringstream out;
  out << "# Sketch-a-Scratch anonymous usage counters (no visitor data).\n";
  out << "sessions = " << counters.sessions << "\n";
  out << "recordings = " << counters.recordings << "\n";
  out << "failed_recordings = " << counters.failed_recordings << "\n";
  out << "voice_strokes = " << counters.voice_strokes << "\n";
  for (std::size_t i = 0; i < texture_names.size() && i < counters.strokes_per_texture.size();
       ++i) {
    out << kStrokePrefix << texture_names[i] << " = " << counters.strokes_per_texture[i] << "\n";
  }
  return out.str();
}

CountersSalvage SalvageCounters(const std::string& text,
                                const std::vector<std::string>& texture_names,
                                const std::string& source_name) {
  CountersSalvage salvage = Empty(texture_names);
  if (Trim(text).empty()) {
    salvage.problems.push_back(source_name + ": empty");
    return salvage;
  }
  // The kiosk always ends the file with a newline; without one it was cut off, perhaps inside the
  // last number (12000 -> 12), which toml++ would read as valid.
  if (text.back() != '\n') {
    salvage.problems.push_back(source_name + ": cut off (no newline at the end)");
    FromLines(text, texture_names, source_name, salvage);
    return salvage;
  }
  try {
    const toml::table root = toml::parse(text, source_name);
    FromToml(root, texture_names, source_name, salvage);
  } catch (const toml::parse_error& e) {
    salvage.problems.push_back(source_name + ":" + std::to_string(e.source().begin.line) + ": " +
                               std::string(e.description()));
    FromLines(text, texture_names, source_name, salvage);
  }
  return salvage;
}

bool SaveCounters(const std::string& path, const UsageCounters& counters,
                  const std::vector<std::string>& texture_names, std::string* error) {
  const std::string text = FormatCounters(counters, texture_names);
  if (!AtomicWriteFile(path, text, error)) return false;
  // The second copy is what a later damage to the first is repaired from. Failing to write it
  // leaves the main file good, so it is not a failed save.
  std::string ignored;
  AtomicWriteFile(BackupPath(path), text, &ignored);
  return true;
}

bool LoadCounters(const std::string& path, const std::vector<std::string>& texture_names,
                  UsageCounters* counters, std::string* error) {
  std::string text, why;
  switch (ReadFile(path, &text, &why)) {
    case ReadResult::kMissing:
      *counters = Empty(texture_names).counters;
      return true;
    case ReadResult::kUnreadable:
      *counters = Empty(texture_names).counters;
      if (error) *error = path + ": " + why;
      return false;
    case ReadResult::kRead:
      break;
  }
  CountersSalvage salvage = SalvageCounters(text, texture_names, path);
  *counters = salvage.counters;
  if (salvage.problems.empty()) return true;
  if (error) *error = salvage.problems.front();
  return false;
}

CountersRecovery RecoverCounters(const std::string& path,
                                 const std::vector<std::string>& texture_names) {
  CountersRecovery recovery;
  // A kill in the middle of a save leaves a temporary next to the file or its backup.
  RemoveStaleTemporaries(path);
  RemoveStaleTemporaries(BackupPath(path));
  std::string text, why;
  const ReadResult main = ReadFile(path, &text, &why);
  CountersSalvage salvage = Empty(texture_names);
  if (main == ReadResult::kRead) {
    salvage = SalvageCounters(text, texture_names, path);
    if (salvage.problems.empty()) {
      recovery.counters = salvage.counters;
      return recovery;
    }
  } else if (main == ReadResult::kUnreadable) {
    salvage.problems.push_back(path + ": " + why);
  }

  // Damaged or missing: each count is the larger of the file's salvage and the backup.
  std::string backup_text, backup_why;
  CountersSalvage backup = Empty(texture_names);
  const bool have_backup =
      ReadFile(BackupPath(path), &backup_text, &backup_why) == ReadResult::kRead;
  if (have_backup) backup = SalvageCounters(backup_text, texture_names, BackupPath(path));
  int from_file = 0, from_backup = 0;
  recovery.counters = salvage.counters;
  for (std::size_t i = 0; i < salvage.found.size(); ++i) {
    std::uint64_t& count = *Field(recovery.counters, i);
    const std::uint64_t kept = *Field(backup.counters, i);
    if (backup.found[i] && (!salvage.found[i] || kept > count)) {
      count = kept;
      ++from_backup;
    } else if (salvage.found[i]) {
      ++from_file;
    }
  }
  if (main == ReadResult::kMissing) {
    if (from_backup > 0) {
      recovery.report = path + " is missing; " + std::to_string(from_backup) +
                        " counts restored from " + BackupPath(path);
    }
    return recovery;
  }

  // Moved aside before anything is written, so the damaged original is never overwritten.
  const std::string aside = AsidePath(path);
  std::string report = salvage.problems.front();
  if (salvage.problems.size() > 1) {
    report += " (and " + std::to_string(salvage.problems.size() - 1) + " more problems)";
  }
  if (std::rename(path.c_str(), aside.c_str()) == 0) {
    report += "; file kept as " + aside;
  } else {
    report += "; could not be moved aside (" + std::string(std::strerror(errno)) +
              "), so it is left in place and counts are not saved this run";
    recovery.may_save = false;
  }
  report += "; " + std::to_string(from_file) + " of " + std::to_string(salvage.found.size()) +
            " counts salvaged from it, " + std::to_string(from_backup) + " from " +
            (have_backup ? BackupPath(path) : std::string("a backup (none found)"));
  recovery.report = report;
  return recovery;
}

}  // namespace sas::kiosk
