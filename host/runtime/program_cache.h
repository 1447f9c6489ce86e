// Compiled OpenCL programs kept between runs. PoCL compiles a program and then, at each kernel's
// first launch, its work-group function; both together are most of a first run's time (the
// default table: about 19 of 31 s). A program's binary (CL_PROGRAM_BINARIES) taken after its
// kernels have run holds all of it, so a later run that loads it compiles nothing.
//
// Entries are keyed by everything that makes a binary valid -- platform and driver version,
// device, the expanded source and the build options -- so a driver upgrade or a changed kernel
// misses instead of loading something stale. Each file carries its key and a checksum of the
// binary: a damaged or foreign entry is never loaded, and one that fails to load or build is
// removed and rebuilt from source.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace depthprec {

class ProgramBinaryCache {
 public:
  // writable: where binaries are stored and looked up first ("" to store nothing);
  // prebuilt: read-only places looked up after it (binaries compiled at build or install time).
  ProgramBinaryCache(std::string writable, std::vector<std::string> prebuilt);
  // From the environment: writable is $DEPTHPREC_KERNEL_CACHE when it names a directory ("off":
  // no cache at all, not even the prebuilt one); prebuilt: the kernel-cache directory next to the
  // executable (a build tree) and ../share/depthprec/kernels (an installation).
  //
  // Storing is opt-in because it is not free: PoCL compiles a generic work-group function of
  // every kernel to export a program's binary (about as long again as the compilation at first
  // launch), and PoCL's own cache already spares a later run on the same machine. The build sets
  // it to fill kernel-cache/; a user sets it for a cache PoCL's does not give, e.g. one shared by
  // the machines of a cluster.
  static ProgramBinaryCache from_environment();

  std::optional<std::vector<unsigned char>> load(const std::string& key) const;
  // Written to a temporary file and renamed, so concurrent runs never see half a file; a
  // failure to write is not an error (the next run compiles again).
  void store(const std::string& key, const std::vector<unsigned char>& binary) const;
  // Removes the writable entry of key (one that failed to load or build).
  void forget(const std::string& key) const;
  bool enabled() const { return !writable_.empty() || !prebuilt_.empty(); }
  bool writable() const { return !writable_.empty(); }
  const std::string& writable_dir() const { return writable_; }
  const std::vector<std::string>& prebuilt_dirs() const { return prebuilt_; }
  // The entries of the writable directory (each program's file, and any a crashed store left
  // half-written); nothing else there. Returns the bytes removed.
  std::uintmax_t clear() const;

 private:
  std::string file_name(const std::string& key) const;
  std::string writable_;
  std::vector<std::string> prebuilt_;
};

}  // namespace depthprec
