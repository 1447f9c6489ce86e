// PoCL's kernel cache as depthprec runs it (docs/caches.md): a file cut short or overwritten
// there is found before PoCL runs it, removed and compiled again, with a note, and the rows come
// out as before; a crash that gets past that says what to do and exits 4, not by the signal;
// `cache show` and `cache clear` see and empty the caches; concurrent runs share them. Every run
// goes through a child process with its own cache directory, so damage never reaches the
// caches other runs use.
#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "host/base/fatal_signal.h"
#include "host/runtime/cache_manifest.h"
#include "host/runtime/pocl_cache_files.h"
#include "tests/support/files.h"
#include "tests/support/run_cli.h"

using namespace depthprec;
using Catch::Matchers::Contains;
using depthprec::test::run_cli;
using depthprec::test::slurp;
namespace fs = std::filesystem;
using depthprec::test::bytes_of;
using depthprec::test::empty_dir;
using depthprec::test::write_bytes;

namespace {

// The first file of the cache whose path ends with tail.
fs::path cache_file(const fs::path& dir, const std::string& tail) {
  for (const std::string& f : pocl_code_files(dir))
    if (f.size() >= tail.size() && f.compare(f.size() - tail.size(), tail.size(), tail) == 0)
      return dir / f;
  FAIL("no file ending with " << tail << " in " << dir);
  return {};
}

// The raster kernel's work-group function for the launches the runs make (16 work-items, a
// small grid), which every probe executes.
const std::string kRasterSo = "-smallgrid/mts_raster.so";

// The program.bc beside a kernel's .so: three directories up from it.
fs::path program_of(const fs::path& so) {
  return so.parent_path().parent_path().parent_path() / "program.bc";
}

// A small MTS run whose rows go to out, so that what run_cli returns is its stderr.
const std::string kRunWritingTo =
    "mts -t reversed -f unorm16 --kernel 16x16 --frames 2 --distances 2,1024 --no-timing -q -o ";

std::string env_for(const fs::path& pocl, const std::string& kernel_cache = "off") {
  return "POCL_CACHE_DIR=" + pocl.string() + " DEPTHPREC_KERNEL_CACHE=" + kernel_cache;
}

}  // namespace

TEST_CASE("a damaged kernel in PoCL's cache is removed, compiled again, and said",
          "[driver_cache][cli]") {
  // With depthprec's program-binary cache off (every program built through PoCL's cache), and on
  // (programs loaded from binaries, which PoCL unpacks around files it already has).
  for (const bool binaries : {false, true}) {
    INFO((binaries ? "depthprec's kernel cache on" : "depthprec's kernel cache off"));
    const fs::path pocl = empty_dir("damage_pocl");
    const fs::path kept = empty_dir("damage_kept");
    const std::string env = env_for(pocl, binaries ? kept.string() : "off");
    const std::string out = (fs::temp_directory_path() / "depthprec_test_damage.txt").string();
    const auto first = run_cli(kRunWritingTo + test::fresh(out), env);
    REQUIRE(first.exit_code == 0);
    CHECK(first.output.empty());
    const std::string rows = slurp(out);
    REQUIRE(!rows.empty());
    REQUIRE(fs::exists(pocl / kManifestName));
    const fs::path so = cache_file(pocl, kRasterSo);
    const fs::path bc = program_of(so);
    const std::string so_bytes = bytes_of(so), bc_bytes = bytes_of(bc);

    // cut short: a truncated .so killed the process with SIGBUS in dlopen()
    write_bytes(so, so_bytes.substr(0, 4096));
    const auto truncated = run_cli(kRunWritingTo + test::fresh(out), env);
    CHECK(truncated.exit_code == 0);
    CHECK(slurp(out) == rows);
    CHECK_THAT(truncated.output,
               Contains("damaged file") && Contains("mts_raster.so") &&
                   Contains(fmt::format("4096 bytes where {} were written", so_bytes.size())));
    CHECK(bytes_of(so).size() == so_bytes.size());  // compiled again

    // overwritten in place, same size: a damaged program.bc failed PoCL's assertion (SIGABRT),
    // or, as these bytes in a string table may be, was read without complaint: the checksum
    // finds it either way
    std::string garbled = bc_bytes;
    for (size_t i = 1000; i < 1064; ++i) garbled[i] = 'x';
    write_bytes(bc, garbled);
    const auto overwritten = run_cli(kRunWritingTo + test::fresh(out), env);
    CHECK(overwritten.exit_code == 0);
    CHECK(slurp(out) == rows);
    CHECK_THAT(overwritten.output,
               Contains("program.bc") && Contains("its bytes changed after it was written"));
    // compiled again (not byte for byte: PoCL's bitcode names the temporary file it compiled)
    CHECK(bytes_of(bc).size() == bc_bytes.size());
    CHECK(pocl_file_structure_problem("program.bc", bytes_of(bc)).empty());

    // and the cache is whole again: the next run says nothing
    const auto again = run_cli(kRunWritingTo + test::fresh(out), env);
    CHECK(again.exit_code == 0);
    CHECK(again.output.empty());
    CHECK(slurp(out) == rows);
    fs::remove_all(pocl);
    fs::remove_all(kept);
    std::remove(out.c_str());
  }
}

TEST_CASE("a crash in the driver names the cause and the fix and exits 4, not by the signal",
          "[driver_cache][cli]") {
  const fs::path pocl = empty_dir("crash_pocl");
  const std::string env = env_for(pocl);
  const std::string out = (fs::temp_directory_path() / "depthprec_test_crash.txt").string();
  REQUIRE(run_cli(kRunWritingTo + test::fresh(out), env).exit_code == 0);
  const std::string rows = slurp(out);
  const fs::path so = cache_file(pocl, kRasterSo);

  // Files no manifest lists (a run that crashed before recording them, or a cache filled by
  // another program) are checked for their structure: a truncated .so is still caught.
  fs::remove(pocl / kManifestName);
  write_bytes(so, bytes_of(so).substr(0, 8192));
  const auto truncated = run_cli(kRunWritingTo + test::fresh(out), env);
  CHECK(truncated.exit_code == 0);
  CHECK_THAT(truncated.output, Contains("mts_raster.so") && Contains("cut short"));
  CHECK(slurp(out) == rows);

  // Wrong bytes inside a well-formed frame, which no manifest vouches for, get past the checks:
  // LLVM cannot read the bitcode, PoCL's assertion fails, and the crash is reported in words.
  fs::remove(pocl / kManifestName);
  const fs::path bc = program_of(so);
  std::string garbled = bytes_of(bc);
  for (size_t i = garbled.size() / 4; i < garbled.size() / 2; ++i) garbled[i] = '\xff';
  write_bytes(bc, garbled);
  REQUIRE(pocl_file_structure_problem("program.bc", garbled).empty());
  const auto crashed = run_cli(kRunWritingTo + test::fresh(out), env);
  CHECK(crashed.exit_code == 4);  // run_cli gives -1 for a death by signal
  CHECK_THAT(crashed.output, Contains("crashed with SIGABRT") && Contains("damaged kernel cache") &&
                                 Contains(pocl.string()) && Contains("depthprec cache clear"));

  // The fix it names works.
  const auto cleared = run_cli("cache clear", env);
  CHECK(cleared.exit_code == 0);
  CHECK_THAT(cleared.output, Contains("cleared PoCL's kernel cache " + pocl.string()));
  CHECK(pocl_code_files(pocl).empty());
  const auto after = run_cli(kRunWritingTo + test::fresh(out), env);
  CHECK(after.exit_code == 0);
  CHECK(slurp(out) == rows);
  fs::remove_all(pocl);
  std::remove(out.c_str());
}

TEST_CASE("depthprec keeps PoCL's cache in a directory of its own, shown and cleared by cache",
          "[driver_cache][cli]") {
  const fs::path home = empty_dir("cache_home");
  const fs::path own = home / "depthprec" / "pocl";
  const fs::path kept = empty_dir("cache_kept");
  const std::string env = "env -u POCL_CACHE_DIR XDG_CACHE_HOME=" + home.string() +
                          " DEPTHPREC_KERNEL_CACHE=" + kept.string();
  const std::string out = (fs::temp_directory_path() / "depthprec_test_own.txt").string();
  REQUIRE(run_cli(kRunWritingTo + test::fresh(out), env).exit_code == 0);
  const size_t code = pocl_code_files(own).size();
  CHECK(code >= 5);  // the set-up and mts programs with their kernels
  std::string problem;
  CHECK(read_manifest(own, &problem).size() == code);
  CHECK(problem.empty());
  REQUIRE(!fs::is_empty(kept));

  const auto shown = run_cli("cache show", env);
  CHECK(shown.exit_code == 0);
  CHECK_THAT(shown.output, Contains("PoCL's kernel cache: " + own.string()) &&
                               Contains(fmt::format("{} of its {} kernel files", code, code)) &&
                               Contains("depthprec's kernel cache: " + kept.string()));

  // While another run uses the cache, clearing it is refused.
  write_bytes(own / "notes.txt", "not PoCL's");
  write_bytes(kept / "notes.txt", "not depthprec's");
  {
    const int users = ::open((own / "depthprec.users").c_str(), O_RDWR | O_CREAT, 0600);
    REQUIRE(users >= 0);
    REQUIRE(::flock(users, LOCK_SH) == 0);
    const auto busy = run_cli("cache clear", env);
    CHECK(busy.exit_code == 4);
    CHECK_THAT(busy.output, Contains("in use by another depthprec run"));
    ::close(users);
  }
  CHECK(pocl_code_files(own).size() == code);

  const auto cleared = run_cli("cache clear", env);
  CHECK(cleared.exit_code == 0);
  CHECK(pocl_code_files(own).empty());
  CHECK(!fs::exists(own / kManifestName));
  CHECK(fs::exists(own / "notes.txt"));  // only what PoCL and depthprec keep there is removed
  CHECK(fs::exists(kept / "notes.txt"));
  for (const auto& e : fs::directory_iterator(kept)) CHECK(e.path().extension() != ".bin");
  fs::remove_all(home);
  fs::remove_all(kept);
  std::remove(out.c_str());
}

TEST_CASE("two runs at once share a cold cache safely", "[driver_cache][cli]") {
  const fs::path pocl = empty_dir("concurrent_pocl");
  const fs::path dir = empty_dir("concurrent_out");
  const std::string env = env_for(pocl);
  // Both start with the cache empty and compile the same programs into it side by side.
  const std::string one =
      fmt::format("{} '{}' {}{} > {} 2>&1; echo $? > {}", env, DEPTHPREC_EXE, kRunWritingTo,
                  (dir / "a.txt").string(), (dir / "a.err").string(), (dir / "a.rc").string());
  const std::string two =
      fmt::format("{} '{}' {}{} > {} 2>&1; echo $? > {}", env, DEPTHPREC_EXE, kRunWritingTo,
                  (dir / "b.txt").string(), (dir / "b.err").string(), (dir / "b.rc").string());
  REQUIRE(std::system(("(" + one + ") & (" + two + ") & wait").c_str()) == 0);
  CHECK(slurp((dir / "a.rc").string()) == "0\n");
  CHECK(slurp((dir / "b.rc").string()) == "0\n");
  CHECK(slurp((dir / "a.err").string()).empty());
  CHECK(slurp((dir / "b.err").string()).empty());
  const std::string rows = slurp((dir / "a.txt").string());
  CHECK(!rows.empty());
  CHECK(slurp((dir / "b.txt").string()) == rows);
  // what they left is whole and recorded: a third run finds nothing to say
  std::string problem;
  CHECK(read_manifest(pocl, &problem).size() == pocl_code_files(pocl).size());
  const auto third = run_cli(kRunWritingTo + (dir / "c.txt").string(), env);
  CHECK(third.exit_code == 0);
  CHECK(third.output.empty());
  CHECK(slurp((dir / "c.txt").string()) == rows);
  fs::remove_all(pocl);
  fs::remove_all(dir);
}

TEST_CASE("the structure checks find cut-short kernels and bitcode, and pass whole ones",
          "[driver_cache]") {
  // Real files from a cache a run filled.
  const fs::path pocl = empty_dir("structure_pocl");
  const std::string out = (fs::temp_directory_path() / "depthprec_test_structure.txt").string();
  REQUIRE(run_cli(kRunWritingTo + test::fresh(out), env_for(pocl)).exit_code == 0);
  const fs::path so = cache_file(pocl, kRasterSo);
  const std::string elf = bytes_of(so), bc = bytes_of(program_of(so));
  CHECK(pocl_file_structure_problem("k.so", elf).empty());
  CHECK(pocl_file_structure_problem("program.bc", bc).empty());
  for (const size_t keep :
       {size_t{0}, size_t{40}, size_t{64}, size_t{4096}, elf.size() / 2, elf.size() - 1}) {
    INFO(".so cut to " << keep << " of " << elf.size() << " bytes");
    CHECK(!pocl_file_structure_problem("k.so", elf.substr(0, keep)).empty());
  }
  for (const size_t keep :
       {size_t{0}, size_t{4}, size_t{64}, bc.size() / 2, bc.size() - 4, bc.size() - 1}) {
    INFO(".bc cut to " << keep << " of " << bc.size() << " bytes");
    CHECK(!pocl_file_structure_problem("program.bc", bc.substr(0, keep)).empty());
  }
  CHECK_THAT(pocl_file_structure_problem("program.bc", "XC" + bc.substr(2)),
             Contains("not LLVM bitcode"));
  CHECK(pocl_file_structure_problem("build.log", "anything").empty());
  // what the checks look at: the files PoCL executes, not its bookkeeping or files in writing
  write_bytes(pocl / "tempfile_abc123.so", "half");
  write_bytes(so.parent_path() / "mts_raster.so_XyZ123.temp", "half");
  for (const std::string& f : pocl_code_files(pocl)) {
    INFO(f);
    CHECK((f.size() > 3 && (f.substr(f.size() - 3) == ".so" || f.substr(f.size() - 3) == ".bc")));
    CHECK(f.find("temp") == std::string::npos);
  }
  CHECK(is_pocl_cache_entry("HC"));
  CHECK(is_pocl_cache_entry("tempfile_abc123"));
  CHECK_FALSE(is_pocl_cache_entry("notes.txt"));
  CHECK_FALSE(is_pocl_cache_entry("ZZ"));

  // the manifest reads back what was written; a damaged one is empty, with the reason
  Manifest m = {{"AB/CDE/program.bc", {1234, 0x0123456789abcdefull, {17, 1000, 2000}}},
                {"x y/k.so", {1, 2, {}}}};
  write_manifest(pocl, m);
  std::string problem;
  CHECK(read_manifest(pocl, &problem) == m);
  CHECK(problem.empty());
  write_bytes(pocl / kManifestName, "depthprec-pocl-manifest 1\n12 zz\n");
  CHECK(read_manifest(pocl, &problem).empty());
  CHECK_THAT(problem, Contains("line 2"));
  CHECK(file_checksum("abc") != file_checksum("abd"));
  CHECK(file_checksum(std::string(16, 'a')) != file_checksum(std::string(17, 'a')));
  fs::remove_all(pocl);
  std::remove(out.c_str());
}

TEST_CASE("a fatal signal is reported in words with the file mapped where it struck",
          "[driver_cache]") {
  // A child maps a file larger than it is and reads past its end: the SIGBUS a truncated kernel
  // gives inside dlopen(). Only async-signal-safe calls run in the child after fork().
  const fs::path file = fs::temp_directory_path() / "depthprec_test_sigbus.so";
  write_bytes(file, std::string(100, 'k'));
  const std::string path = file.string();
  const std::string advice = "depthprec: advice for the test\n";  // made before fork()
  int pipe_fds[2];
  REQUIRE(::pipe(pipe_fds) == 0);
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    ::dup2(pipe_fds[1], 2);
    set_fatal_signal_advice(advice, 4);
    install_fatal_signal_report();
    const int fd = ::open(path.c_str(), O_RDONLY);
    const long page = ::sysconf(_SC_PAGESIZE);
    auto* p = static_cast<volatile char*>(::mmap(nullptr, 4 * page, PROT_READ, MAP_PRIVATE, fd, 0));
    if (p == MAP_FAILED) ::_exit(99);
    (void)p[2 * page];  // past the end of the file: SIGBUS
    ::_exit(98);
  }
  ::close(pipe_fds[1]);
  std::string said;
  char buf[512];
  for (ssize_t n; (n = ::read(pipe_fds[0], buf, sizeof buf)) > 0;) said.append(buf, n);
  ::close(pipe_fds[0]);
  int status = 0;
  REQUIRE(::waitpid(child, &status, 0) == child);
  CHECK(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 4);
  CHECK_THAT(said, Contains("crashed with SIGBUS") && Contains(" in " + path) &&
                       Contains("advice for the test"));
  fs::remove(file);
}
