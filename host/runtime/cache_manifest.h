// The manifest depthprec keeps in PoCL's cache directory (docs/caches.md): the size and checksum
// of every file PoCL executes (pocl_code_files) as it was when a run that used it ended, so a
// later run finds a file cut short or overwritten since and removes it before PoCL trusts it.
//
// Callers hold the directory's lock (driver_cache.cpp): these functions read and write files
// without locking themselves.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace depthprec {

// What stat(2) said of a file when its bytes were found to match the entry. A later start that
// finds the same inode, size, modification and status-change times does not read the file
// again: any write, truncation, copy or rename over it moves the status-change time (ctime),
// which no call a program makes can set back. A file changed within the same clock tick as its
// last change could keep both times, so a stamp is only kept for a file whose last change is
// some seconds older than the check (as git's index treats "racy" entries); until then every
// start reads it. A stamp holds for the boot that recorded it only (cache_manifest.cpp, boot_id).
// Zero: not stamped, read and checksum the file.
struct FileStamp {
  std::uint64_t inode = 0, mtime_ns = 0, ctime_ns = 0;
  bool known() const { return inode != 0; }
  bool operator==(const FileStamp& o) const {
    return inode == o.inode && mtime_ns == o.mtime_ns && ctime_ns == o.ctime_ns;
  }
};

struct ManifestEntry {
  std::uint64_t size = 0;
  std::uint64_t checksum = 0;  // file_checksum of the bytes
  FileStamp stamp;
  bool operator==(const ManifestEntry& o) const {
    return size == o.size && checksum == o.checksum && stamp == o.stamp;
  }
};
using Manifest = std::map<std::string, ManifestEntry>;  // path relative to the directory

constexpr const char* kManifestName = "depthprec-manifest";

// The manifest of dir: empty when there is none. A malformed one (damaged itself) is empty too,
// and *problem says why.
Manifest read_manifest(const std::filesystem::path& dir, std::string* problem);
// Written to a temporary name and renamed over the old one, so a reader sees the old or the new
// manifest, never part of one. Throws RuntimeError naming the directory when it cannot.
void write_manifest(const std::filesystem::path& dir, const Manifest& manifest);

struct DamagedFile {
  std::string path;  // relative to the directory
  std::string why;
};

// Checks every file PoCL executes in dir: one in the manifest must have its size and checksum
// (read only when its stamp differs from stat's), one not (written by a run that did not end, or
// by another program) a sound structure. Removes each damaged file, and its entry, so PoCL
// compiles it again; returns them. *restamped is set when a listed file's bytes were read, found
// whole and stamped: the manifest changed and is worth writing.
std::vector<DamagedFile> remove_damaged_files(const std::filesystem::path& dir, Manifest& manifest,
                                              bool* restamped = nullptr);

// Adds the files PoCL wrote since the manifest was read (those with a sound structure; any other
// is removed and returned) and drops the entries of files no longer there. A listed file is not
// read again: remove_damaged_files vouched for it when the run began.
std::vector<DamagedFile> add_new_files(const std::filesystem::path& dir, Manifest& manifest);

}  // namespace depthprec
