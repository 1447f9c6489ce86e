// cache show | clear: the compiled kernels kept between runs (docs/caches.md): PoCL's cache,
// which depthprec points at a directory of its own and checks, and depthprec's program-binary
// cache. Neither subcommand touches OpenCL, so a cache that crashes the driver can still be seen
// and cleared.
#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "host/cli/commands.h"
#include "host/runtime/cache_manifest.h"
#include "host/runtime/driver_cache.h"
#include "host/runtime/pocl_cache_files.h"
#include "host/runtime/program_cache.h"

namespace depthprec::cli {

namespace {

namespace fs = std::filesystem;

struct Usage {
  bool exists = false;
  std::uintmax_t files = 0, bytes = 0;
};

Usage usage_of(const fs::path& dir) {
  Usage u;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return u;
  u.exists = true;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::end(it);
       it.increment(ec))
    if (it->is_regular_file(ec)) {
      ++u.files;
      u.bytes += it->file_size(ec);
    }
  return u;
}

std::string size_text(std::uintmax_t bytes) {
  if (bytes >= (1u << 20)) return fmt::format("{:.1f} MiB", static_cast<double>(bytes) / (1 << 20));
  if (bytes >= (1u << 10)) return fmt::format("{:.1f} KiB", static_cast<double>(bytes) / (1 << 10));
  return fmt::format("{} B", bytes);
}

void run_show() {
  const DriverCacheDir pocl = driver_cache_dir();
  const ProgramBinaryCache binaries = ProgramBinaryCache::from_environment();
  const auto line = [](const std::string& what, const std::string& dir, const std::string& how) {
    const Usage u = usage_of(dir);
    std::printf(
        "%s: %s\n  %s; %s\n", what.c_str(), dir.c_str(),
        u.exists ? fmt::format("{} files, {}", u.files, size_text(u.bytes)).c_str() : "absent",
        how.c_str());
  };
  std::string how = pocl.chosen_by;
  if (!pocl.persistent) how += "; $POCL_KERNEL_CACHE is off, so PoCL keeps nothing there";
  std::string problem;
  const Manifest m = read_manifest(pocl.path, &problem);
  const std::vector<std::string> code = pocl_code_files(pocl.path);
  size_t listed = 0;
  for (const std::string& f : code) listed += m.count(f);
  how += fmt::format("; {} of its {} kernel files recorded in its manifest", listed, code.size());
  if (!problem.empty()) how += " (" + problem + ")";
  line("PoCL's kernel cache", pocl.path.string(), how);
  if (binaries.writable())
    line("depthprec's kernel cache", binaries.writable_dir(), "$DEPTHPREC_KERNEL_CACHE");
  else
    std::printf("depthprec's kernel cache: %s\n",
                std::getenv("DEPTHPREC_KERNEL_CACHE")
                    ? "off ($DEPTHPREC_KERNEL_CACHE=off: no compiled program is loaded)"
                    : "not kept ($DEPTHPREC_KERNEL_CACHE unset)");
  for (const std::string& dir : binaries.prebuilt_dirs())
    line("prebuilt kernels", dir,
         "read-only, from the build or installation; checked, not cleared");
  std::printf("`depthprec cache clear` empties the first two (docs/caches.md).\n");
}

void run_clear() {
  const DriverCacheDir pocl = driver_cache_dir();
  const ProgramBinaryCache binaries = ProgramBinaryCache::from_environment();
  const std::uintmax_t pocl_bytes = clear_driver_cache(pocl);
  std::printf("cleared PoCL's kernel cache %s (%s removed)\n", pocl.path.string().c_str(),
              size_text(pocl_bytes).c_str());
  if (binaries.writable())
    std::printf("cleared depthprec's kernel cache %s (%s removed)\n",
                binaries.writable_dir().c_str(), size_text(binaries.clear()).c_str());
  std::printf("the next run compiles the kernels it needs again%s\n",
              binaries.prebuilt_dirs().empty()
                  ? ""
                  : " (the build's prebuilt kernels, read-only and checked, are kept)");
}

}  // namespace

void add_cache_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "cache",
      "The compiled kernels kept between runs: PoCL's kernel cache, in a directory of depthprec's\n"
      "own (or $POCL_CACHE_DIR) that every run checks for damaged files, and depthprec's\n"
      "program-binary cache ($DEPTHPREC_KERNEL_CACHE). docs/caches.md says more.\n"
      "Examples:\n"
      "  depthprec cache show\n"
      "  depthprec cache clear      (after a crash that names a damaged kernel cache)");
  cmd->require_subcommand(1);
  cmd->add_subcommand("show", "Directories, files and sizes of the caches")->callback(run_show);
  cmd->add_subcommand("clear",
                      "Remove what the caches hold (refused while another depthprec run uses "
                      "PoCL's cache); the next run compiles its kernels again")
      ->callback(run_clear);
}

}  // namespace depthprec::cli
