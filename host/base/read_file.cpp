#include "host/base/read_file.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "host/base/errors.h"

namespace depthprec {

std::string read_input_file(const std::string& path, const std::string& what) {
  // A directory opens as a stream on Linux and reads as nothing: named here, or it would be
  // reported as a file with no JSON in it.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(fmt::format("{} '{}' is a directory: name a file", what, path));
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(fmt::format("cannot read {} '{}': {}", what, path, std::strerror(errno)));
  std::stringstream buf;
  buf << in.rdbuf();
  if (in.bad())
    throw InputError(fmt::format("cannot read {} '{}': {}", what, path, std::strerror(errno)));
  return buf.str();
}

}  // namespace depthprec
