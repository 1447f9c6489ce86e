#include "host/runtime/driver_cache.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <optional>
#include <vector>

#include "host/base/errors.h"
#include "host/base/fatal_signal.h"
#include "host/runtime/cache_manifest.h"
#include "host/runtime/pocl_cache_files.h"
#include "host/runtime/program_cache.h"

namespace depthprec {

namespace fs = std::filesystem;

namespace {

constexpr const char* kLockName = "depthprec.lock";    // checks and manifest updates
constexpr const char* kUsersName = "depthprec.users";  // held shared by every run

// An flock() on a file of the directory, released when it goes out of scope.
class DirLock {
 public:
  DirLock(const fs::path& file, int operation) {
    fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
    if (fd_ < 0) return;
    int r;
    do r = ::flock(fd_, operation);
    while (r != 0 && errno == EINTR);
    locked_ = r == 0;
  }
  ~DirLock() {
    if (fd_ >= 0) ::close(fd_);  // closing releases the lock
  }
  DirLock(const DirLock&) = delete;
  DirLock& operator=(const DirLock&) = delete;
  bool locked() const { return locked_; }
  // Keeps the lock (and its descriptor) for the rest of the process.
  void keep() { fd_ = -1; }

 private:
  int fd_ = -1;
  bool locked_ = false;
};

std::optional<DriverCacheDir> g_opened;  // set by open_driver_cache

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v ? v : "";
}

void note(const std::string& text) {
  std::fprintf(stderr, "depthprec: note: %s\n", text.c_str());
}

void note_damage(const fs::path& dir, const std::vector<DamagedFile>& damaged) {
  for (const DamagedFile& d : damaged)
    note(fmt::format(
        "PoCL's kernel cache {} held a damaged file, removed so that it is compiled again: {} "
        "({})",
        dir.string(), d.path, d.why));
}

}  // namespace

DriverCacheDir driver_cache_dir() {
  DriverCacheDir d;
  const std::string kernel_cache = env("POCL_KERNEL_CACHE");
  d.persistent = kernel_cache.empty() || kernel_cache[0] == '1';  // PoCL reads it so
  if (const std::string given = env("POCL_CACHE_DIR"); !given.empty()) {
    d.path = given;
    d.from_environment = true;
    d.chosen_by = "$POCL_CACHE_DIR";
  } else if (const std::string xdg = env("XDG_CACHE_HOME"); !xdg.empty()) {
    d.path = fs::path(xdg) / "depthprec" / "pocl";
    d.chosen_by = "depthprec's own, $XDG_CACHE_HOME/depthprec/pocl";
  } else if (const std::string home = env("HOME"); !home.empty()) {
    d.path = fs::path(home) / ".cache" / "depthprec" / "pocl";
    d.chosen_by = "depthprec's own, ~/.cache/depthprec/pocl";
  } else {
    d.path = fs::path("/tmp") / fmt::format("depthprec-{}", ::getuid()) / "pocl";
    d.chosen_by = "depthprec's own (no $HOME)";
  }
  return d;
}

std::string crash_advice(const DriverCacheDir& dir, const std::string& kernel_cache) {
  return fmt::format(
      "depthprec: the OpenCL driver (PoCL) was in use, and the likely cause is a damaged kernel "
      "cache: a compiled kernel cut short or overwritten after it was written (a full disk, a "
      "crash, a copy, a tool that touched it), which PoCL runs without checking. The caches: "
      "PoCL's {} ({}){}.\n"
      "depthprec: fix: run `depthprec cache clear` (it removes what they hold) and run again: "
      "the kernels are compiled anew. If it crashes again after that, please report it.\n",
      dir.path.string(), dir.chosen_by,
      kernel_cache.empty() ? "" : fmt::format(", depthprec's {}", kernel_cache));
}

void open_driver_cache() {
  static std::once_flag once;
  std::call_once(once, [] {
    const DriverCacheDir dir = driver_cache_dir();
    std::error_code ec;
    fs::create_directories(dir.path, ec);
    if (ec || !fs::is_directory(dir.path))
      throw RuntimeError(fmt::format(
          "cannot create PoCL's kernel cache directory {} ({}): {}; set POCL_CACHE_DIR (or "
          "XDG_CACHE_HOME) to a writable directory",
          dir.path.string(), dir.chosen_by, ec ? ec.message() : "not a directory"));
    if (!dir.from_environment) ::setenv("POCL_CACHE_DIR", dir.path.c_str(), 1);
    DirLock(dir.path / kUsersName, LOCK_SH).keep();
    if (dir.persistent) {
      const DirLock lock(dir.path / kLockName, LOCK_EX);
      std::string problem;
      Manifest manifest = read_manifest(dir.path, &problem);
      if (!problem.empty())
        note(fmt::format("PoCL's kernel cache {}: {}; its files' structure is checked instead",
                         dir.path.string(), problem));
      bool stamped = false;
      const auto damaged = remove_damaged_files(dir.path, manifest, &stamped);
      note_damage(dir.path, damaged);
      if (!damaged.empty() || !problem.empty() || stamped) {
        try {
          write_manifest(dir.path, manifest);
        } catch (const Error& e) {
          note(e.what());
        }
      }
    }
    const ProgramBinaryCache binaries = ProgramBinaryCache::from_environment();
    set_fatal_signal_advice(
        crash_advice(
            dir, binaries.writable_dir().empty() ? "" : "kernel cache " + binaries.writable_dir()),
        static_cast<int>(ExitCode::runtime));
    g_opened = dir;
  });
}

void record_driver_cache() {
  if (!g_opened || !g_opened->persistent) return;
  const fs::path& dir = g_opened->path;
  try {
    const DirLock lock(dir / kLockName, LOCK_EX);
    Manifest manifest = read_manifest(dir, nullptr);
    note_damage(dir, add_new_files(dir, manifest));
    write_manifest(dir, manifest);
  } catch (const std::exception& e) {
    note(
        fmt::format("PoCL's kernel cache {}: the files this run added are not recorded ({}); the "
                    "next run checks their structure only",
                    dir.string(), e.what()));
  }
}

std::uintmax_t clear_driver_cache(const DriverCacheDir& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir.path, ec)) return 0;
  const DirLock users(dir.path / kUsersName, LOCK_EX | LOCK_NB);
  if (!users.locked())
    throw RuntimeError(fmt::format(
        "PoCL's kernel cache {} is in use by another depthprec run: clear it once that run has "
        "ended",
        dir.path.string()));
  const DirLock lock(dir.path / kLockName, LOCK_EX);
  std::vector<fs::path> doomed;
  for (const auto& entry : fs::directory_iterator(dir.path, ec)) {
    const std::string name = entry.path().filename().string();
    if (is_pocl_cache_entry(name) && name != kLockName && name != kUsersName)
      doomed.push_back(entry.path());
  }
  std::uintmax_t bytes = 0;
  for (const fs::path& p : doomed) {
    if (fs::is_directory(p, ec)) {
      for (auto it = fs::recursive_directory_iterator(p, ec); !ec && it != fs::end(it);
           it.increment(ec))
        if (it->is_regular_file(ec)) bytes += it->file_size(ec);
    } else {
      bytes += fs::file_size(p, ec);
    }
    fs::remove_all(p, ec);
    if (ec) throw RuntimeError(fmt::format("cannot remove {}: {}", p.string(), ec.message()));
  }
  return bytes;
}

}  // namespace depthprec
