// The program binary cache: what it stores it loads back, and nothing damaged, foreign or
// truncated is ever loaded; a run over damaged entries compiles again and gives the same rows.
#include "host/runtime/program_cache.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "tests/support/files.h"
#include "tests/support/run_cli.h"

using namespace depthprec;
namespace fs = std::filesystem;
using depthprec::test::bytes_of;
using depthprec::test::empty_dir;
using depthprec::test::run_cli;
using depthprec::test::write_bytes;

namespace {

fs::path only_entry(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir)) files.push_back(e.path());
  REQUIRE(files.size() == 1);
  return files.front();
}

}  // namespace

TEST_CASE("the program binary cache loads what it stored and refuses anything else",
          "[program_cache]") {
  const fs::path dir = empty_dir("binaries");
  const ProgramBinaryCache cache(dir.string(), {});
  const std::vector<unsigned char> binary = {1, 2, 3, 250, 0, 7, 9};
  CHECK_FALSE(cache.load("key a"));
  cache.store("key a", binary);
  REQUIRE(cache.load("key a"));
  CHECK(*cache.load("key a") == binary);
  CHECK_FALSE(cache.load("key b"));

  const fs::path file = only_entry(dir);
  const std::string good = bytes_of(file);
  // another key's entry under this key's name (a name-hash collision) is not this program
  const ProgramBinaryCache other(dir.string(), {});
  other.store("key b", binary);
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path() != file) fs::rename(e.path(), file, ec);
  CHECK_FALSE(cache.load("key a"));

  // one byte of the binary changed, the file cut short, or bytes after it: all refused
  std::string flipped = good;
  flipped[flipped.size() - 2] ^= 0x40;
  write_bytes(file, flipped);
  CHECK_FALSE(cache.load("key a"));
  write_bytes(file, good.substr(0, good.size() - 3));
  CHECK_FALSE(cache.load("key a"));
  write_bytes(file, good + "x");
  CHECK_FALSE(cache.load("key a"));
  write_bytes(file, good);
  CHECK(cache.load("key a"));

  // read-only places are looked up after the writable one, and forget() leaves them alone
  const fs::path prebuilt = empty_dir("binaries_prebuilt");
  ProgramBinaryCache(prebuilt.string(), {}).store("key c", binary);
  const ProgramBinaryCache layered((dir / "elsewhere").string(), {prebuilt.string()});
  REQUIRE(layered.load("key c"));
  layered.forget("key c");
  CHECK(layered.load("key c"));
  CHECK(ProgramBinaryCache("", {}).enabled() == false);
}

TEST_CASE("a run with PoCL's cache empty loads the kept programs, and damaged ones are rebuilt",
          "[program_cache][cli]") {
  const fs::path kept = empty_dir("kernel_cache");
  const std::string mts =
      "mts -t reversed -f unorm16 --kernel 16x16 --frames 2 --distances 2,1024 --no-timing -q";
  const auto env = [&kept](const std::string& pocl) {
    return "DEPTHPREC_KERNEL_CACHE=" + kept.string() + " POCL_CACHE_DIR=" + pocl;
  };
  const auto first = run_cli(mts, env(empty_dir("pocl_1").string()));
  REQUIRE(first.exit_code == 0);
  // one program: reversed/unorm16's variant, which the build (default scene) did not compile
  const fs::path entry = only_entry(kept);
  const std::string stored = bytes_of(entry);
  CHECK(stored.size() > 10000);  // the program with its compiled kernels

  const auto loaded = run_cli(mts, env(empty_dir("pocl_2").string()));
  REQUIRE(loaded.exit_code == 0);
  CHECK(loaded.output == first.output);
  CHECK(bytes_of(entry) == stored);  // nothing compiled, nothing rewritten

  // Damaged in the middle of the binary: not loaded, compiled from source, replaced.
  std::string damaged = stored;
  for (size_t i = damaged.size() / 2; i < damaged.size() / 2 + 64; ++i) damaged[i] = '\x5a';
  write_bytes(entry, damaged);
  const auto rebuilt = run_cli(mts, env(empty_dir("pocl_3").string()));
  REQUIRE(rebuilt.exit_code == 0);
  CHECK(rebuilt.output == first.output);
  CHECK(bytes_of(entry) != damaged);
  CHECK(ProgramBinaryCache(kept.string(), {}).enabled());
}
