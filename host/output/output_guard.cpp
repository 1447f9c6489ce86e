#include "host/output/output_guard.h"

#include <fmt/format.h>

#include <filesystem>
#include <system_error>

#include "host/base/errors.h"
#include "host/output/report.h"

namespace depthprec {

void check_output_spares_inputs(const std::string& option, const std::string& output,
                                const std::vector<NamedInput>& inputs) {
  if (output.empty() || is_stream_output(output)) return;
  // What a run writes: the final file, the temporary file it is written to before the rename,
  // and the journal of a batch.
  const std::vector<std::pair<std::string, std::string>> written = {
      {output, ""},
      {output + ".tmp", "its temporary file "},
      {output + ".rows.jsonl", "its row journal "}};
  for (const NamedInput& in : inputs) {
    if (in.path.empty()) continue;
    for (const auto& [path, through] : written) {
      std::error_code ec;
      // Only a file that exists can be replaced; equivalent() compares device and inode, so a
      // symbolic or hard link to the input is caught as the input itself.
      if (!std::filesystem::equivalent(in.path, path, ec) || ec) continue;
      const std::string same =
          in.path == path ? "" : fmt::format(" ('{}' and '{}' are one file)", path, in.path);
      throw InputError(fmt::format(
          "{} {}: {}{} is {} '{}'{}, which this command reads, and writing the output would "
          "replace it; choose another output file",
          option, output, through, through.empty() ? "the output" : "'" + path + "'", in.what,
          in.path, same));
    }
  }
}

void check_default_output_is_new(const std::string& who, const std::string& path, bool named) {
  std::error_code ec;
  if (named || !std::filesystem::exists(path, ec)) return;
  throw OutputError(fmt::format(
      "{}: '{}' exists, and without -o {} writes only where there is none; replace it with -o "
      "{}, or name another file with -o",
      who, path, who, path));
}

}  // namespace depthprec
