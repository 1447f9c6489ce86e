// No lost results: a batch killed mid-way keeps its finished rows, --resume completes it to the
// same bytes as an uninterrupted run, and shards merge to the same bytes too.
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "tests/support/run_cli.h"

using Catch::Matchers::Contains;
using depthprec::test::fresh;
using depthprec::test::run_cli;
using depthprec::test::slurp;

namespace {

const std::string kBatch =
    "table -t standard,linear,reversed -f unorm24 --distances 2,64,2048,65536,2097152,67108864 "
    "--kernel 120x120 --frames 40 --no-timing --format-out json";

// Finished rows in a journal: its lines with a row key (the first line names the run).
size_t rows_in(const std::string& path) {
  std::istringstream in(slurp(path));
  size_t n = 0;
  for (std::string line; std::getline(in, line);) n += line.find("\"key\"") != std::string::npos;
  return n;
}

std::vector<std::string> words(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  std::string w;
  while (in >> w) out.push_back(w);
  return out;
}

// Starts depthprec with args, waits until `journal` holds a finished row, sends `sig`, and
// returns the exit code.
int run_and_interrupt(const std::string& args, const std::string& journal, int sig) {
  const auto argv_words = words(args);
  std::vector<char*> argv;
  std::string exe = DEPTHPREC_EXE;
  argv.push_back(exe.data());
  std::vector<std::string> keep(argv_words);
  for (auto& w : keep) argv.push_back(w.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    std::freopen("/dev/null", "w", stderr);
    execv(exe.c_str(), argv.data());
    _exit(127);
  }
  for (int i = 0; i < 2000 && rows_in(journal) == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  kill(pid, sig);
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST_CASE("an interrupted table keeps its finished rows and resumes to identical bytes",
          "[batch]") {
  const std::string full = fresh("/tmp/depthprec_test_full.json"),
                    cut = fresh("/tmp/depthprec_test_cut.json");
  for (const auto& f : {full, cut, cut + ".rows.jsonl"}) std::remove(f.c_str());
  REQUIRE(run_cli(kBatch + " -o " + full).exit_code == 0);
  for (const int sig : {SIGINT, SIGTERM}) {
    std::remove(cut.c_str());
    std::remove((cut + ".rows.jsonl").c_str());
    const int code = run_and_interrupt(kBatch + " -o " + cut, cut + ".rows.jsonl", sig);
    INFO("signal " << sig);
    CHECK(code == 130);
    const size_t kept = rows_in(cut + ".rows.jsonl");
    CHECK(kept >= 1);
    CHECK(kept < 18);                        // stopped before the end
    CHECK_FALSE(std::ifstream(cut).good());  // no half-written final file
    // starting over would lose the kept rows: refused
    const auto again = run_cli(kBatch + " -o " + cut);
    CHECK(again.exit_code == 5);
    CHECK_THAT(again.output, Contains("--resume"));
    // Rows of another scene (here: another near plane) must not be mixed in: refused, naming it.
    const auto other = run_cli(kBatch + " --near 2 -o " + cut + " --resume");
    CHECK(other.exit_code == 3);
    CHECK_THAT(other.output, Contains("written by another run") && Contains("scene.near"));
    REQUIRE(run_cli(kBatch + " -o " + cut + " --resume").exit_code == 0);
    CHECK(slurp(cut) == slurp(full));
    CHECK_FALSE(std::ifstream(cut + ".rows.jsonl").good());  // journal gone once complete
  }
}

// infinite's rows are standard's computations (n = 1, f = 1e9): with two jobs its pair waits for
// standard's. An interrupt then ends the run at once, the waiting pair included.
TEST_CASE("an interrupt stops a run whose pairs are waiting for each other", "[batch]") {
  const std::string cut = fresh("/tmp/depthprec_test_wait.json");
  for (const auto& f : {cut, cut + ".rows.jsonl"}) std::remove(f.c_str());
  const auto t0 = std::chrono::steady_clock::now();
  const int code = run_and_interrupt(
      // the paper's frames: their rows reach the journal one by one as each search ends, long
      // before the run does (a worst-case row waits for its rounds, and the run's rows then
      // land close together, leaving the interrupt little time to arrive before the end)
      "table -t standard,infinite -f unorm24 --distances 2,64,2048,65536,2097152 "
      "--kernel 160x160 --frames 60 --jobs 2 --no-timing --format-out json --set sampling=paper "
      "-o " +
          cut,
      cut + ".rows.jsonl", SIGINT);
  CHECK(code == 130);
  CHECK(rows_in(cut + ".rows.jsonl") >= 1);
  CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < 30);
}

TEST_CASE("shards merge to the bytes of the whole batch", "[batch]") {
  const std::string full = fresh("/tmp/depthprec_test_whole.json");
  REQUIRE(run_cli(kBatch + " -o " + full).exit_code == 0);
  std::string parts;
  for (int i = 1; i <= 3; ++i) {
    const std::string part = fresh("/tmp/depthprec_test_part" + std::to_string(i) + ".json");
    REQUIRE(run_cli(kBatch + " --shard " + std::to_string(i) + "/3 -o " + part).exit_code == 0);
    parts += " " + part;
  }
  const std::string merged = fresh("/tmp/depthprec_test_merged.json");
  REQUIRE(run_cli("merge" + parts + " --no-timing --format-out json -o " + merged).exit_code == 0);
  CHECK(slurp(merged) == slurp(full));
  // A part of another batch (another far plane) is refused, naming the field.
  const std::string stray = fresh("/tmp/depthprec_test_stray.json");
  REQUIRE(run_cli(kBatch + " --far 1e6 --shard 3/3 -o " + stray).exit_code == 0);
  const auto mixed =
      run_cli("merge /tmp/depthprec_test_part1.json /tmp/depthprec_test_part2.json " + stray);
  CHECK(mixed.exit_code == 3);
  CHECK_THAT(mixed.output, Contains("is not a shard of the batch") && Contains("scene.far"));
  // A damaged part (a field of the wrong type) is bad input, not an internal error.
  std::ofstream(stray) << "{\"rows\": [], \"scene\": {}, \"kind\": 7}";
  CHECK(run_cli("merge " + stray).exit_code == 3);
}

// What docs/scale-out.md shows: the parts run by GNU parallel (Debian's `parallel`, installed by
// scripts/setup.sh), merged to exactly what one run writes.
TEST_CASE("a batch split by GNU parallel merges to the bytes of one run", "[batch]") {
  const std::string whole = fresh("/tmp/depthprec_test_par_whole.json");
  REQUIRE(run_cli(kBatch + " -o " + whole).exit_code == 0);
  for (int i = 1; i <= 3; ++i) fresh("/tmp/depthprec_test_par" + std::to_string(i) + ".json");
  const std::string cmd = "parallel --will-cite -j 2 \"'" + std::string(DEPTHPREC_EXE) + "' " +
                          kBatch +
                          " -q --shard {}/3 -o /tmp/depthprec_test_par{}.json\" ::: 1 2 3 2>&1";
  REQUIRE(std::system(cmd.c_str()) == 0);
  const std::string merged = fresh("/tmp/depthprec_test_par_merged.json");
  REQUIRE(run_cli("merge /tmp/depthprec_test_par3.json /tmp/depthprec_test_par1.json "
                  "/tmp/depthprec_test_par2.json --no-timing --format-out json -o " +
                  merged)
              .exit_code == 0);
  CHECK(slurp(merged) == slurp(whole));
}

TEST_CASE("batch option errors are usage errors", "[batch][errors]") {
  const auto shard = run_cli("table --shard 0/3");
  CHECK(shard.exit_code == 2);
  CHECK_THAT(shard.output, Contains("expected i/N"));
  const auto resume = run_cli("table --resume");
  CHECK(resume.exit_code == 2);
  CHECK_THAT(resume.output, Contains("--resume needs --output"));
  const auto merge = run_cli("merge /nonexistent/part.json");
  CHECK(merge.exit_code == 3);
  CHECK_THAT(merge.output, Contains("cannot read"));
}

// With fewer pairs than jobs a pair's distances are split between jobs, each part with its own
// evaluator (and plane-A cache and reference distance): the rows stay the same, and -v still says
// one line of the pair, with its parts' counts summed.
TEST_CASE("a lone pair split between jobs gives the bytes of one job", "[batch]") {
  const std::string args =
      "mts -t standard -f unorm24 --distances 2,64,2048,65536,1048576 --kernel 40x40 --frames 10 "
      "--no-timing --format-out json";
  std::string first;
  for (const int jobs : {1, 2, 3}) {
    const std::string out = fresh("/tmp/depthprec_test_split" + std::to_string(jobs) + ".json");
    const auto r = run_cli("-v " + args + " --jobs " + std::to_string(jobs) + " -o " + out);
    REQUIRE(r.exit_code == 0);
    INFO("--jobs " << jobs);
    CHECK_THAT(r.output, Contains("standard/unorm24/gl: 5 distances, "));
    CHECK(r.output.find("standard/unorm24/gl:") == r.output.rfind("standard/unorm24/gl:"));
    if (jobs == 1)
      first = slurp(out);
    else
      CHECK(slurp(out) == first);
  }
}

// Jobs side by side launch the same kernels over grids of many widths. PoCL 3.1 aborted such runs
// ("pocl_release_dlhandle_cache: Assertion `found->ref_count > 0' failed") unless the kernels are
// primed first (MtsEvaluator::prime_launches): this run aborted 8 times in 8 before, and the same
// command with its output on stdout 10 in 12, so four passing runs leave a regression about one
// chance in 1,300.
TEST_CASE("many jobs launching the same kernels run to the end with the bytes of one job",
          "[batch]") {
  const std::string args =
      "mts -t standard,reversed -f float32 --frames 30 --no-timing "
      "--format-out json";
  const std::string one = fresh("/tmp/depthprec_test_prime1.json");
  REQUIRE(run_cli(args + " --jobs 1 -o " + one).exit_code == 0);
  for (int run = 0; run < 4; ++run) {
    const std::string out = fresh("/tmp/depthprec_test_prime6.json");
    const auto r = run_cli(args + " --jobs 6 -o " + out);
    INFO("run " << run << ": " << r.output);
    REQUIRE(r.exit_code == 0);
    CHECK(slurp(out) == slurp(one));
  }
  // Every launch checks that it is no wider than the kernels were primed for
  // (MtsEvaluator::widest_launches): more stiffness probes per distance, more frames than a batch
  // and more bands than the default scene's stay within it.
  const std::string wide =
      "mts -t linear -f unorm24 --kernel 64x300 --frames 70 --distances "
      "2,16,128,1024,8192 --set stiffness_probes=3 --no-timing "
      "--format-out json";
  REQUIRE(run_cli(wide + " --jobs 1 -o " + one).exit_code == 0);
  const std::string out = fresh("/tmp/depthprec_test_prime4.json");
  const auto r = run_cli(wide + " --jobs 4 -o " + out);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(slurp(out) == slurp(one));
}

// Attribution runs side by side too: a pair's arithmetic-limited MTS is its float32 sibling's
// where an earlier pair is that sibling (unorm16 here, which waits for it) and a search of its own
// where none is (unorm24, listed before float32), so the bytes are one job's whichever job gets
// there first. Several jobs also run the storage-limited kernel side by side, each launch as wide
// as every other.
TEST_CASE("attribution gives the bytes of one job with several", "[batch][attribution]") {
  const std::string args =
      "table -t standard,log_fragment -f unorm24,float32,unorm16 --kernel 48x48 --frames 12 "
      "--distances 2,300,40000 --attribute --no-timing --format-out json";
  const std::string one = fresh("/tmp/depthprec_test_attr1.json");
  REQUIRE(run_cli(args + " --jobs 1 -o " + one).exit_code == 0);
  const std::string text = slurp(one);
  CHECK(text.find("\"arithmetic_mts\"") != std::string::npos);
  for (const int jobs : {2, 5}) {
    const std::string out = fresh("/tmp/depthprec_test_attr" + std::to_string(jobs) + ".json");
    const auto r = run_cli(args + " --jobs " + std::to_string(jobs) + " -o " + out);
    INFO("--jobs " << jobs << ": " << r.output);
    REQUIRE(r.exit_code == 0);
    CHECK(slurp(out) == text);
  }
}

// An output that is a device or a pipe (-o /dev/null, a FIFO) is written in place: replacing it
// through a temporary file would, as root, leave a regular file where /dev/null was. Nor is a
// journal made beside it. A FIFO stands for /dev/null here, so a regression breaks no device.
TEST_CASE("an output that is a pipe is written into in place and gets no journal", "[batch]") {
  const std::string fifo = "/tmp/depthprec_test_output.fifo";
  std::remove(fifo.c_str());
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  // Open for reading first (without blocking), so the run's writer does not wait for a reader;
  // one row of JSON fits in the pipe's buffer.
  const int fd = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  REQUIRE(fd >= 0);
  const auto r = run_cli(
      "mts -t standard -f unorm24 --distances 64 --kernel 16x16 --frames 2 "
      "--no-timing --format-out json -q -o " +
      fifo);
  std::string got;
  char buf[4096];
  for (ssize_t n; (n = ::read(fd, buf, sizeof buf)) > 0;) got.append(buf, static_cast<size_t>(n));
  ::close(fd);
  struct stat st {};
  REQUIRE(::stat(fifo.c_str(), &st) == 0);
  CHECK(S_ISFIFO(st.st_mode));
  CHECK(r.exit_code == 0);
  CHECK(nlohmann::json::parse(got, nullptr, false).value("kind", "") == "mts");
  CHECK(::access((fifo + ".rows.jsonl").c_str(), F_OK) != 0);
  const auto resume = run_cli("mts -t standard -f unorm24 --distances 64 --resume -o " + fifo);
  CHECK(resume.exit_code == 2);
  CHECK_THAT(resume.output, Contains("a regular file"));
  std::remove(fifo.c_str());
}

// lj-table, tradeoff, cost, pipelines, advise, world, bias, render and compare are batches
// (host/batch/batch.h): the same guarantees.
TEST_CASE("every record batch resumes and merges to the bytes of a whole run", "[batch]") {
  const std::vector<std::pair<std::string, std::string>> batches = {
      {"lj-table", "lj-table --samples 20000 --no-timing --format-out json"},
      {"cost",
       "cost -t standard,reversed,linear,log_fragment -f unorm24 --distances 2,1024,1048576 "
       "--kernel 60x60 "
       "--frames 20 --no-timing --format-out json"},
      {"tradeoff",
       "tradeoff -t reversed -f float32 --depth-range zero_to_one --distances 2,1024 --no-timing "
       "--format-out json"},
      {"pipelines",
       "pipelines -t standard,reversed,linear,log_fragment -f unorm24 --distances 2,1024,1048576 "
       "--kernel 60x60 --frames 20 --no-timing --format-out json"},
      {"advise",
       "advise --range 10,100 --separation 0.05 -t standard,reversed,linear -f unorm24 "
       "--kernel 60x60 --frames 20 --no-timing --format-out json"},
      {"world",
       "world -t standard,reversed,linear -f unorm24 --separation 0.05 --kernel 60x60 --frames 20 "
       "--set sampling=paper --no-timing --format-out json"},
      {"bias",
       "bias -t standard,reversed,infinite,log_vertex -f unorm24 --distances 2,1024,1048576 "
       "--kernel 60x60 --frames 20 --no-timing --format-out json"},
      {"profiles",
       "table --profiles ideal,llvmpipe -t standard,reversed,infinite -f float32 --distances "
       "2,1024,1048576 --kernel 60x60 --frames 20 --no-timing --format-out json"},
      // The rendered batches (llvmpipe here): rows of `render`, records of `compare`.
      {"render",
       "render -t standard,reversed,linear -f unorm24 --distances 2,1024,1048576 --kernel 64x64 "
       "--frames 20 --no-timing --format-out json"},
      {"compare",
       "compare -t standard,reversed,linear -f unorm24 --distances 2,1024,1048576 --kernel 64x64 "
       "--frames 20 --no-timing --format-out json"}};
  // Worst-case sampling (the default; lj-table has no scene) in rounds of 10 orientations: its
  // refinement runs, is interrupted, resumed and sharded as the default's 100 are, in a tenth of
  // the frames.
  for (const auto& [name, batch_args] : batches) {
    INFO(name);
    const std::string args =
        name == "lj-table" ? batch_args : batch_args + " --set worst_case.round_size=10";
    const std::string base = "/tmp/depthprec_test_" + name;
    const std::string full = fresh(base + "_full.json"), cut = fresh(base + "_cut.json");
    for (const auto& f : {full, cut, cut + ".rows.jsonl"}) std::remove(f.c_str());
    REQUIRE(run_cli(args + " -o " + full).exit_code == 0);
    CHECK(run_and_interrupt(args + " -o " + cut, cut + ".rows.jsonl", SIGINT) == 130);
    CHECK(rows_in(cut + ".rows.jsonl") >= 1);
    CHECK_FALSE(std::ifstream(cut).good());
    CHECK(run_cli(args + " -o " + cut).exit_code == 5);  // would lose the kept rows
    REQUIRE(run_cli(args + " -o " + cut + " --resume").exit_code == 0);
    CHECK(slurp(cut) == slurp(full));
    CHECK_FALSE(std::ifstream(cut + ".rows.jsonl").good());
    std::string parts;
    for (int i = 2; i >= 1; --i) {  // merge takes the shards in any order
      const std::string part = base + "_part" + std::to_string(i) + ".json";
      REQUIRE(run_cli(args + " --shard " + std::to_string(i) + "/2 -o " + part).exit_code == 0);
      parts += " " + part;
    }
    const auto merged =
        run_cli("merge" + parts + " --no-timing --format-out json -o " + base + "_merged.json");
    REQUIRE(merged.exit_code == 0);
    CHECK(slurp(base + "_merged.json") == slurp(full));
    const auto one = run_cli("merge " + base + "_part1.json");
    CHECK(one.exit_code == 3);
    CHECK_THAT(one.output, Contains("shard 2/2 is missing"));
  }
}

// standard and infinite compute the same thing with binary32 matrices (n = 1, f = 1e9): one run
// takes infinite's rows over from standard's; shards that split them still merge to its bytes.
TEST_CASE("rows taken over from an identical computation read the same in shards", "[batch]") {
  const std::string args =
      "table -t standard,infinite -f unorm24 --distances 2,64,2048,65536 --kernel 40x40 "
      "--frames 10 --no-timing --format-out json";
  const std::string whole = fresh("/tmp/depthprec_test_taken_whole.json");
  REQUIRE(run_cli(args + " -o " + whole).exit_code == 0);
  const auto j = nlohmann::json::parse(slurp(whole));
  REQUIRE(j["rows"].size() == 8);
  for (size_t i = 0; i < 4; ++i) {
    auto a = j["rows"][i], b = j["rows"][4 + i];
    CHECK(a["technique"] == "standard");
    CHECK(b["technique"] == "infinite");
    a.erase("technique");
    b.erase("technique");
    CHECK(a == b);
  }
  std::string parts;
  for (int i = 1; i <= 2; ++i) {
    const std::string part = fresh("/tmp/depthprec_test_taken_part" + std::to_string(i) + ".json");
    REQUIRE(run_cli(args + " --shard " + std::to_string(i) + "/2 -o " + part).exit_code == 0);
    parts += " " + part;
  }
  REQUIRE(run_cli("merge" + parts + " --no-timing --format-out json -o " +
                  fresh("/tmp/depthprec_test_taken_merged.json"))
              .exit_code == 0);
  CHECK(slurp("/tmp/depthprec_test_taken_merged.json") == slurp(whole));
}

// Pairs run side by side (--jobs) with their own queues; a pair whose rows an earlier pair
// computes waits for it. Neither may change a byte of the rows, nor the order of the verbose
// lines (printed in pair order, whichever job finishes first).
TEST_CASE("any number of jobs gives the same bytes and the same verbose lines in pair order",
          "[batch]") {
  const std::string args =
      "table -t standard,infinite,linear,reversed -f unorm24,float32 --distances 2,2048,65536 "
      "--kernel 60x60 --frames 20 --no-timing --format-out json";
  std::string first_output, first_lines;
  for (const int jobs : {1, 3, 8}) {
    const std::string out = fresh("/tmp/depthprec_test_jobs" + std::to_string(jobs) + ".json");
    const auto r = run_cli("-v " + args + " --jobs " + std::to_string(jobs) + " -o " + out);
    REQUIRE(r.exit_code == 0);
    // each verbose line up to its first number: the pair or variant it names, in order
    std::string lines;
    std::istringstream in(r.output);
    for (std::string line; std::getline(in, line);)
      if (line.find(':') != std::string::npos)
        lines += line.substr(0, line.find_first_of("0123456789")) + "\n";
    INFO("--jobs " << jobs);
    // 6 variants built, 6 pairs computed, 2 (infinite) taken over from standard
    CHECK(std::count(lines.begin(), lines.end(), '\n') == 6 + 6 + 2);
    if (jobs == 1) {
      first_output = slurp(out);
      first_lines = lines;
      CHECK_THAT(
          r.output,
          Contains("infinite/unorm24/gl: 3 distances computed exactly as by an earlier pair"));
      continue;
    }
    CHECK(slurp(out) == first_output);
    CHECK(lines == first_lines);
  }
}
