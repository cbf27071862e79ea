#pragma once
// Crash- and disk-full-safe file replacement: the new contents go to a temporary file in the same
// directory, are flushed to disk (fsync), and only then renamed over the old file (rename is
// atomic on POSIX file systems), after which the directory entry is synced too. A power cut,
// SIGKILL or a full disk at any point leaves either the complete old file or the complete new one,
// never a truncated mix: the kiosk's configuration and counters survive months of daily restarts.

#include <string>

namespace sas::kiosk {

// kSynced: the new contents and the rename reach the disk before the call returns (staff data,
// counters). kReadersOnly: readers still see the old or the new file whole (the rename), but
// nothing waits for the disk: for a file rewritten every few seconds whose loss at a power cut
// costs nothing (the health metrics), where an fsync on a slow SD card would stall the caller.
enum class Durability { kSynced, kReadersOnly };

// Returns true on success; on failure returns false, leaves `path` untouched, removes the
// temporary file and puts a readable reason in `error`.
bool AtomicWriteFile(const std::string& path, const std::string& contents, std::string* error,
                     Durability durability = Durability::kSynced);

// Removes the temporary files AtomicWriteFile leaves next to `path` when the process is killed
// between creating and renaming one (".<name>.XXXXXX"); `path` itself is never touched.
void RemoveStaleTemporaries(const std::string& path);

// Where a damaged state file is set aside so that nothing is lost: `<path>.damaged-YYYYMMDD-HHMMSS`
// (local time), with -2, -3... if that name is taken.
std::string AsidePath(const std::string& path);

}  // namespace sas::kiosk
