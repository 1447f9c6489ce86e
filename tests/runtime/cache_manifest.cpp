// The manifest's stamps (host/runtime/cache_manifest.h): a start reads a listed kernel file only
// when stat says it may have changed since its bytes were last found whole, so the check costs a
// stat per file rather than a read of the whole cache; every change a write makes is still read.
#include "host/runtime/cache_manifest.h"

#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

#include "host/runtime/pocl_cache_files.h"
#include "tests/support/files.h"

using namespace depthprec;
using depthprec::test::empty_dir;
using depthprec::test::write_bytes;
namespace fs = std::filesystem;

namespace {

const std::string kStampedFile = "AB/CDEF/program.bc";

}  // namespace

TEST_CASE("a listed kernel file is read until its stamp vouches for it, then only stat'ed",
          "[driver_cache]") {
  const fs::path dir = empty_dir("manifest_stamps");
  fs::create_directories(dir / "AB" / "CDEF");
  const std::string bytes(5000, 'k');
  write_bytes(dir / kStampedFile, bytes);
  Manifest m = {{kStampedFile, {bytes.size(), file_checksum(bytes), {}}}};

  // Just written: read and found whole, but too recent a change to stamp.
  bool stamped = false;
  CHECK(remove_damaged_files(dir, m, &stamped).empty());
  CHECK_FALSE(stamped);
  CHECK_FALSE(m.at(kStampedFile).stamp.known());

  // Older than the racy interval: stamped, and the stamp round-trips through the manifest.
  std::this_thread::sleep_for(std::chrono::milliseconds(2100));
  CHECK(remove_damaged_files(dir, m, &stamped).empty());
  CHECK(stamped);
  const FileStamp stamp = m.at(kStampedFile).stamp;
  REQUIRE(stamp.known());
  write_manifest(dir, m);
  std::string problem;
  CHECK(read_manifest(dir, &problem) == m);
  CHECK(problem.empty());

  // While stat matches the stamp the bytes are not read: an entry with the right stamp and a
  // wrong checksum passes (a read would have removed the file).
  Manifest trusting = m;
  trusting.at(kStampedFile).checksum ^= 1;
  stamped = false;
  CHECK(remove_damaged_files(dir, trusting, &stamped).empty());
  CHECK_FALSE(stamped);
  CHECK(fs::exists(dir / kStampedFile));

  // Overwritten in place with as many bytes: stat no longer matches, the bytes are read, and the
  // checksum finds the change.
  std::string garbled = bytes;
  garbled[100] = 'x';
  write_bytes(dir / kStampedFile, garbled);
  const auto damaged = remove_damaged_files(dir, m, &stamped);
  REQUIRE(damaged.size() == 1);
  CHECK(damaged[0].why == "its bytes changed after it was written");
  CHECK_FALSE(fs::exists(dir / kStampedFile));
  CHECK(m.empty());

  // A manifest of the first version (no stamps) is read, its entries unstamped.
  write_bytes(dir / kManifestName,
              "depthprec-pocl-manifest 1\n5000 00000000000000ff " + kStampedFile + "\n");
  const Manifest v1 = read_manifest(dir, &problem);
  CHECK(problem.empty());
  REQUIRE(v1.size() == 1);
  CHECK(v1.at(kStampedFile).size == 5000);
  CHECK(v1.at(kStampedFile).checksum == 0xff);
  CHECK_FALSE(v1.at(kStampedFile).stamp.known());

  // Stamps vouch for the boot that wrote them only: another boot's are dropped on reading.
  write_bytes(dir / kManifestName,
              "depthprec-pocl-manifest 2 boot not-this-boot\n5000 "
              "00000000000000ff 7 8 9 " +
                  kStampedFile + "\n");
  const Manifest other_boot = read_manifest(dir, &problem);
  CHECK(problem.empty());
  REQUIRE(other_boot.size() == 1);
  CHECK(other_boot.at(kStampedFile).checksum == 0xff);
  CHECK_FALSE(other_boot.at(kStampedFile).stamp.known());
  fs::remove_all(dir);
}
