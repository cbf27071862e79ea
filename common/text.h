// Small text helpers shared by the staff-facing reports (staff panel, staff cues, texture command).
#pragma once

#include <cstdio>
#include <string>
#include <vector>

namespace sas::text {

// `value` with `digits` decimals, as printf's %.*f.
inline std::string Fixed(double value, int digits) {
  char out[48];
  std::snprintf(out, sizeof out, "%.*f", digits, value);
  return out;
}

// "a, b, c".
inline std::string Joined(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

}  // namespace sas::text
