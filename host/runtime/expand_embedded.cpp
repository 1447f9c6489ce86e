#include <fmt/format.h>

#include <regex>
#include <set>
#include <sstream>

#include "host/base/embedded_sources.h"
#include "host/base/errors.h"

namespace depthprec {

namespace {

void expand_into(const std::string& path, std::set<std::string>& seen, std::string& out) {
  if (!seen.insert(path).second) return;
  const auto& sources = embedded_sources();
  const auto it = sources.find(path);
  if (it == sources.end())
    throw RuntimeError(fmt::format("kernel source '{}' is not embedded in this build", path));
  // An include may end in a comment; any other #include left would reach the OpenCL compiler,
  // which resolves it against the working directory, if at all: refused.
  static const std::regex include_line(R"re(^\s*#\s*include\s+"([^"]+)"\s*(/\*.*\*/|//.*)?\s*$)re");
  static const std::regex any_include(
      R"re(^\s*#\s*include\s*".*)re");  // <...> only in host-only branches
  std::istringstream in(it->second);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    std::smatch m;
    if (std::regex_match(line, m, include_line)) {
      expand_into(m[1], seen, out);
      out += fmt::format("#line {} \"{}\"\n", number + 1, path);
    } else if (std::regex_match(line, any_include)) {
      throw RuntimeError(fmt::format(
          "{}:{}: only #include \"embedded/path\" is allowed in kernel sources", path, number));
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
