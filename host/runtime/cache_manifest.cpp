#include "host/runtime/cache_manifest.h"

#include <fmt/format.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

#include "host/base/errors.h"
#include "host/runtime/pocl_cache_files.h"

namespace depthprec {

namespace fs = std::filesystem;

namespace {

constexpr const char* kManifestMagic = "depthprec-pocl-manifest 1";

// The whole file in one read (the check reads every kernel file at each start: no per-byte
// stream iteration).
bool read_bytes(const fs::path& p, std::string& out) {
  std::ifstream in(p, std::ios::binary | std::ios::ate);
  if (!in) return false;
  const std::streamoff size = in.tellg();
  if (size < 0) return false;
  out.resize(static_cast<size_t>(size));
  in.seekg(0);
  in.read(out.data(), size);
  return in.gcount() == size;
}

// Removes a damaged file; one that is already gone (another run removed it first) is fine.
void remove_file(const fs::path& p) {
  std::error_code ec;
  fs::remove(p, ec);
}

}  // namespace

Manifest read_manifest(const fs::path& dir, std::string* problem) {
  Manifest m;
  std::ifstream in(dir / kManifestName);
  if (!in) return m;
  std::string line;
  if (!std::getline(in, line) || line != kManifestMagic) {
    if (problem)
      *problem = fmt::format("{} does not start with '{}'", kManifestName, kManifestMagic);
    return {};
  }
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    std::istringstream fields(line);
    ManifestEntry e;
    std::string path;
    const bool parsed = (fields >> e.size >> std::hex >> e.checksum) &&
                        std::getline(fields >> std::ws, path) && !path.empty() &&
                        path.find("..") == std::string::npos;
    if (!parsed) {
      if (problem) *problem = fmt::format("{} line {} is malformed", kManifestName, number);
      return {};
    }
    m[path] = e;
  }
  return m;
}

void write_manifest(const fs::path& dir, const Manifest& manifest) {
  const fs::path path = dir / kManifestName;
  const fs::path tmp = dir / fmt::format("{}.{}.tmp", kManifestName, ::getpid());
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << kManifestMagic << '\n';
    for (const auto& [file, e] : manifest)
      out << e.size << ' ' << fmt::format("{:016x}", e.checksum) << ' ' << file << '\n';
    out.flush();
    if (!out) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw RuntimeError(fmt::format("cannot write {}", tmp.string()));
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw RuntimeError(fmt::format("cannot rename {} to {}", tmp.string(), path.string()));
  }
}

std::vector<DamagedFile> remove_damaged_files(const fs::path& dir, Manifest& manifest) {
  std::vector<DamagedFile> damaged;
  for (const std::string& file : pocl_code_files(dir)) {
    std::string bytes;
    if (!read_bytes(dir / file, bytes)) continue;  // gone meanwhile, or unreadable: PoCL's concern
    std::string why;
    const auto listed = manifest.find(file);
    if (listed != manifest.end()) {
      if (bytes.size() != listed->second.size)
        why = fmt::format("{} bytes where {} were written", bytes.size(), listed->second.size);
      else if (file_checksum(bytes) != listed->second.checksum)
        why = "its bytes changed after it was written";
    } else {
      why = pocl_file_structure_problem(file, bytes);
    }
    if (why.empty()) continue;
    remove_file(dir / file);
    manifest.erase(file);
    damaged.push_back({file, why});
  }
  return damaged;
}

std::vector<DamagedFile> add_new_files(const fs::path& dir, Manifest& manifest) {
  std::vector<DamagedFile> damaged;
  const std::vector<std::string> files = pocl_code_files(dir);
  Manifest kept;
  for (const std::string& file : files) {
    const auto listed = manifest.find(file);
    if (listed != manifest.end()) {
      kept.insert(*listed);
      continue;
    }
    std::string bytes;
    if (!read_bytes(dir / file, bytes)) continue;
    const std::string why = pocl_file_structure_problem(file, bytes);
    if (!why.empty()) {
      remove_file(dir / file);
      damaged.push_back({file, why});
      continue;
    }
    kept[file] = {bytes.size(), file_checksum(bytes)};
  }
  manifest = std::move(kept);
  return damaged;
}

}  // namespace depthprec
