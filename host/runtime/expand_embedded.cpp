#include <fmt/format.h>

#include <regex>
#include <set>
#include <sstream>

#include "host/runtime/embedded_sources.h"
#include "host/base/errors.h"

namespace depthprec {

namespace {

void expand_into(const std::string& path, std::set<std::string>& seen, std::string& out) {
  if (!seen.insert(path).second) return;
  const auto& sources = embedded_sources();
  const auto it = sources.find(path);
  if (it == sources.end())
    throw RuntimeError(fmt::format("kernel source '{}' is not embedded in this build", path));
  static const std::regex include_line(R"re(^\s*#\s*include\s+"([^"]+)"\s*$)re");
  std::istringstream in(it->second);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    std::smatch m;
    if (std::regex_match(line, m, include_line)) {
      expand_into(m[1], seen, out);
      out += fmt::format("#line {} \"{}\"\n", number + 1, path);
    } else {
      out += line;
      out += '\n';
    }
  }
}

}  // namespace

std::string expand_embedded(const std::string& path) {
  std::set<std::string> seen;
  std::string out;
  expand_into(path, seen, out);
  return out;
}

}  // namespace depthprec
