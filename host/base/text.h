// Small text helpers shared by the host.
#pragma once

#include <algorithm>
#include <cctype>
#include <string>

namespace depthprec {

// s with ASCII letters lowered: names compared without regard to case.
inline std::string to_lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

}  // namespace depthprec
