#include "host/cli/audit_png_paths.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "host/base/errors.h"

namespace depthprec::cli {

namespace fs = std::filesystem;

std::string png_prefix(const std::string& png, const std::string& gltf_file) {
  if (png.empty()) return "";
  std::error_code ec;
  const bool directory = png.back() == '/' || fs::is_directory(png, ec);
  // The files go inside a directory prefix, else beside the prefix's last component.
  // ("dir/" is "dir" with an empty last component)
  const fs::path dir = directory && png.back() != '/' ? fs::path(png) : fs::path(png).parent_path();
  const std::string shown = dir.empty() ? "." : dir.string();
  const std::string forms =
      "--png PREFIX writes PREFIX-<technique>-<format>-<range>.png; --png DIR/ writes "
      "DIR/<glTF name>-<technique>-<format>-<range>.png";
  if (!dir.empty() && !fs::exists(dir, ec))
    throw OutputError(fmt::format(
        "--png {}: the directory '{}' does not exist; create it first ({})", png, shown, forms));
  if (!dir.empty() && !fs::is_directory(dir, ec))
    throw OutputError(fmt::format("--png {}: '{}' is not a directory ({})", png, shown, forms));
  if (::access(dir.empty() ? "." : dir.c_str(), W_OK) != 0)
    throw OutputError(
        fmt::format("--png {}: cannot write in '{}': {}", png, shown, std::strerror(errno)));
  return directory ? (dir / fs::path(gltf_file).stem()).string() : png;
}

std::string png_name(const std::string& prefix, const EvalPair& pair, const char* kind) {
  return fmt::format("{}-{}-{}-{}{}.png", prefix, info(pair.technique).name, pair.format,
                     to_string(pair.depth_range), kind);
}

void check_png_names(const std::string& prefix, const std::vector<EvalPair>& pairs,
                     const std::vector<NamedInput>& inputs) {
  if (prefix.empty()) return;
  for (const EvalPair& pair : pairs)
    for (const char* kind : {"", "-margin"}) {
      const std::string name = png_name(prefix, pair, kind);
      std::error_code ec;
      if (fs::is_directory(name, ec))
        throw OutputError(fmt::format("--png: cannot write '{}': it is a directory", name));
      check_output_spares_inputs("--png", name, inputs);
    }
}

}  // namespace depthprec::cli
