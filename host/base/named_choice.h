// One of a setting's named values (a scene's enum keys), or an InputError that names what was
// given and what is allowed: "unknown clip 'x': expected none or llvmpipe".
#pragma once

#include <fmt/format.h>

#include <initializer_list>
#include <string>
#include <utility>

#include "host/base/errors.h"

namespace depthprec {

template <typename E>
E named_choice(const char* what, const std::string& given,
               std::initializer_list<std::pair<const char*, E>> names) {
  std::string allowed;
  for (const auto& [name, value] : names) {
    if (given == name) return value;
    allowed += (allowed.empty() ? "" : " or ") + std::string(name);
  }
  throw InputError(fmt::format("unknown {} '{}': expected {}", what, given, allowed));
}

}  // namespace depthprec
