// Text helpers for matching joint names. Internal to engine/motion: defined here once, not per file, so that
// the module's .cpp files can share a translation unit (unity build) without two overloads of one helper.
#pragma once

#include <cctype>
#include <string>
#include <string_view>

namespace prep::joint_names {

inline std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace prep::joint_names
