#pragma once
// What /proc/self/smaps says about a range of this process's memory: whether a core dump would
// leave it out (the kernel's "dd" VmFlag, set by madvise(MADV_DONTDUMP)).

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace sas::test {

// The VmFlags of every mapping in /proc/self/smaps that overlaps [data, data + bytes); empty when
// none does. A core dump leaves out the pages whose flags include "dd".
inline std::vector<std::string> VmFlagsOf(const void* data, std::size_t bytes) {
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t end = begin + bytes;
  std::ifstream smaps("/proc/self/smaps");
  std::vector<std::string> flags;
  std::string line;
  bool overlaps = false;
  while (std::getline(smaps, line)) {
    const auto dash = line.find('-');
    const auto space = line.find(' ');
    if (dash != std::string::npos && space != std::string::npos && dash < space &&
        line.find(':') > space) {  // a mapping's header: "start-end perms offset dev inode path"
      const std::uintptr_t lo = std::stoull(line.substr(0, dash), nullptr, 16);
      const std::uintptr_t hi = std::stoull(line.substr(dash + 1, space - dash - 1), nullptr, 16);
      overlaps = lo < end && begin < hi;
    } else if (overlaps && line.rfind("VmFlags:", 0) == 0) {
      flags.push_back(line.substr(8));
    }
  }
  return flags;
}

// True when some mapping overlaps the range and every one that does is marked "dd".
inline bool AllDontDump(const std::vector<std::string>& flags) {
  return !flags.empty() && std::all_of(flags.begin(), flags.end(), [](const std::string& f) {
    return (" " + f + " ").find(" dd ") != std::string::npos;
  });
}

}  // namespace sas::test
