#pragma once
// Persistence of the anonymous usage counters (strokes per texture, recordings, visits) shown on
// the staff panel. Written with AtomicWriteFile, so a crash or a full disk never loses them; a
// missing file means "start from zero"; a damaged one is reported and left in place for staff.

#include <string>
#include <vector>

#include "kiosk/session.h"

namespace sas::kiosk {

// Plain text, one `key = value` per line (valid TOML), texture names as keys.
std::string FormatCounters(const UsageCounters& counters,
                           const std::vector<std::string>& texture_names);

// Parses what FormatCounters wrote. Unknown texture names are ignored (a texture was swapped);
// anything malformed throws std::runtime_error naming the line.
UsageCounters ParseCounters(const std::string& text, const std::vector<std::string>& texture_names,
                            const std::string& source_name);

bool SaveCounters(const std::string& path, const UsageCounters& counters,
                  const std::vector<std::string>& texture_names, std::string* error);

// Missing file: zeros and true. Damaged file: zeros, false and the reason in `error`.
bool LoadCounters(const std::string& path, const std::vector<std::string>& texture_names,
                  UsageCounters* counters, std::string* error);

}  // namespace sas::kiosk
