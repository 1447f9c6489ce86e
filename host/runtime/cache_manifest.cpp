#include "host/runtime/cache_manifest.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <ctime>
#include <fstream>
#include <sstream>

#include "host/base/errors.h"
#include "host/runtime/pocl_cache_files.h"

namespace depthprec {

namespace fs = std::filesystem;

namespace {

// Version 2: the header names the boot that wrote it ("depthprec-pocl-manifest 2 boot ID"), then
// lines of size checksum inode mtime_ns ctime_ns path. Version 1 (size checksum path), or a
// manifest of another boot, is read with no stamps, so its files are read once more and stamped.
constexpr const char* kManifestMagic = "depthprec-pocl-manifest 2";
constexpr const char* kManifestMagicV1 = "depthprec-pocl-manifest 1";

// This boot's id from the kernel ("" where there is none: then no stamp is kept). Stamps vouch
// for the boot that recorded them only: a power loss can leave a file's size and times on a file
// system that journals metadata alone while its data never reached the disk, so the first run
// after a boot reads every file again.
const std::string& boot_id() {
  static const std::string id = [] {
    std::ifstream in("/proc/sys/kernel/random/boot_id");
    std::string line;
    std::getline(in, line);
    return line;
  }();
  return id;
}

std::string header() {
  const std::string& boot = boot_id();
  return boot.empty() ? kManifestMagic : fmt::format("{} boot {}", kManifestMagic, boot);
}

// A stamp is kept only for a file whose last change is this much older than the check: a change
// within the same clock tick as the one before it could leave both times as they were.
constexpr std::int64_t kRacyNs = 2'000'000'000;

std::uint64_t ns_of(const struct timespec& t) {
  return static_cast<std::uint64_t>(t.tv_sec) * 1'000'000'000u +
         static_cast<std::uint64_t>(t.tv_nsec);
}

struct Stat {
  std::uint64_t size = 0;
  FileStamp stamp;
};

Stat stat_of(const struct stat& st) {
  return {static_cast<std::uint64_t>(st.st_size),
          {static_cast<std::uint64_t>(st.st_ino), ns_of(st.st_mtim), ns_of(st.st_ctim)}};
}

std::uint64_t now_ns() {
  struct timespec t {};
  ::clock_gettime(CLOCK_REALTIME, &t);
  return ns_of(t);
}

// The whole file in one read, and the stamp of the bytes read: stat's before and after the read
// on the same descriptor, none when they differ (changed while read) or when the last change is
// too recent to vouch for (kRacyNs).
bool read_bytes(const fs::path& p, std::string& out, FileStamp& stamp) {
  stamp = {};
  const int fd = ::open(p.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  struct stat before {
  }, after{};
  bool ok = ::fstat(fd, &before) == 0 && before.st_size >= 0;
  if (ok) {
    out.resize(static_cast<size_t>(before.st_size));
    size_t done = 0;
    while (ok && done < out.size()) {
      const ssize_t n = ::read(fd, out.data() + done, out.size() - done);
      if (n <= 0) ok = false;
      done += n > 0 ? static_cast<size_t>(n) : 0;
    }
    char extra;
    ok = ok && ::read(fd, &extra, 1) == 0 && ::fstat(fd, &after) == 0;  // not grown meanwhile
  }
  ::close(fd);
  if (!ok) return false;
  const Stat b = stat_of(before), a = stat_of(after);
  if (!boot_id().empty() && b.stamp == a.stamp && b.size == a.size &&
      static_cast<std::int64_t>(now_ns() - a.stamp.ctime_ns) > kRacyNs)
    stamp = a.stamp;
  return true;
}

// Whether stat finds the file as its entry's stamp recorded it.
bool unchanged(const fs::path& p, const ManifestEntry& e) {
  if (!e.stamp.known()) return false;
  struct stat st {};
  if (::stat(p.c_str(), &st) != 0) return false;
  const Stat s = stat_of(st);
  return s.size == e.size && s.stamp == e.stamp;
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
  const bool has_header = static_cast<bool>(std::getline(in, line));
  const std::string v2_magic = kManifestMagic;
  const bool v2 = has_header && line.compare(0, v2_magic.size(), v2_magic) == 0 &&
                  (line.size() == v2_magic.size() || line[v2_magic.size()] == ' ');
  if (!v2 && !(has_header && line == kManifestMagicV1)) {
    if (problem)
      *problem = fmt::format("{} does not start with '{}' or '{}'", kManifestName, kManifestMagic,
                             kManifestMagicV1);
    return {};
  }
  const bool this_boot = v2 && !boot_id().empty() && line == header();
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    std::istringstream fields(line);
    ManifestEntry e;
    std::string path;
    bool parsed = static_cast<bool>(fields >> e.size >> std::hex >> e.checksum >> std::dec);
    if (v2) parsed = parsed && (fields >> e.stamp.inode >> e.stamp.mtime_ns >> e.stamp.ctime_ns);
    parsed = parsed && std::getline(fields >> std::ws, path) && !path.empty() &&
             path.find("..") == std::string::npos;
    if (!parsed) {
      if (problem) *problem = fmt::format("{} line {} is malformed", kManifestName, number);
      return {};
    }
    if (!this_boot) e.stamp = {};
    m[path] = e;
  }
  return m;
}

void write_manifest(const fs::path& dir, const Manifest& manifest) {
  const fs::path path = dir / kManifestName;
  const fs::path tmp = dir / fmt::format("{}.{}.tmp", kManifestName, ::getpid());
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << header() << '\n';
    for (const auto& [file, e] : manifest)
      out << fmt::format("{} {:016x} {} {} {} {}\n", e.size, e.checksum, e.stamp.inode,
                         e.stamp.mtime_ns, e.stamp.ctime_ns, file);
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

std::vector<DamagedFile> remove_damaged_files(const fs::path& dir, Manifest& manifest,
                                              bool* restamped) {
  std::vector<DamagedFile> damaged;
  for (const std::string& file : pocl_code_files(dir)) {
    const auto listed = manifest.find(file);
    if (listed != manifest.end() && unchanged(dir / file, listed->second)) continue;
    std::string bytes;
    FileStamp stamp;
    // gone meanwhile, or unreadable: PoCL's concern
    if (!read_bytes(dir / file, bytes, stamp)) continue;
    std::string why;
    if (listed != manifest.end()) {
      if (bytes.size() != listed->second.size)
        why = fmt::format("{} bytes where {} were written", bytes.size(), listed->second.size);
      else if (file_checksum(bytes) != listed->second.checksum)
        why = "its bytes changed after it was written";
      else if (stamp.known()) {
        listed->second.stamp = stamp;
        if (restamped) *restamped = true;
      }
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
    FileStamp stamp;
    if (!read_bytes(dir / file, bytes, stamp)) continue;
    const std::string why = pocl_file_structure_problem(file, bytes);
    if (!why.empty()) {
      remove_file(dir / file);
      damaged.push_back({file, why});
      continue;
    }
    kept[file] = {bytes.size(), file_checksum(bytes), stamp};
  }
  manifest = std::move(kept);
  return damaged;
}

}  // namespace depthprec
