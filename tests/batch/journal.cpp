// The row journal (FILE.rows.jsonl beside --output FILE) after a failure: what a failed write
// leaves must not stand in a rerun's way, a temporary file must not outlive its run, and two runs
// writing the same output at once must not mistake each other for an interrupted run.
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
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/run_cli.h"

using Catch::Matchers::Contains;
using depthprec::test::fresh;
using depthprec::test::run_cli;
using depthprec::test::run_shell;
using depthprec::test::slurp;

namespace {

const std::string kJsonRun =
    "mts -t standard,reversed -f unorm24 --distances 2,64,2048 --kernel 24x24 --frames 4 "
    "--no-timing -q --format-out json";
// Long enough (about two seconds) to be caught running.
const std::string kLong =
    "table -t standard,linear,reversed,log_fragment -f unorm24,float32 "
    "--distances 2,64,2048,65536,2097152,67108864 --kernel 200x200 --frames 100 --no-timing -q "
    "--format-out json";

bool exists(const std::string& path) {
  struct stat st {};
  return ::lstat(path.c_str(), &st) == 0;
}

// Starts depthprec with args (split at spaces), stderr to err_file; returns its process id.
pid_t start(const std::string& args, const std::string& err_file) {
  std::vector<std::string> words;
  std::istringstream in(args);
  for (std::string w; in >> w;) words.push_back(w);
  std::string exe = DEPTHPREC_EXE;
  std::vector<char*> argv = {exe.data()};
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    std::freopen(err_file.c_str(), "w", stderr);
    std::freopen("/dev/null", "w", stdout);
    execv(exe.c_str(), argv.data());
    _exit(127);
  }
  return pid;
}

int wait_exit(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Waits (up to ten seconds) until the journal holds more than `lines` lines.
bool wait_for_lines(const std::string& journal, size_t lines) {
  for (int i = 0; i < 2000; ++i) {
    const std::string text = slurp(journal);
    if (static_cast<size_t>(std::count(text.begin(), text.end(), '\n')) > lines) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

}  // namespace

// A full disk at the journal's first line left a 0-byte journal: every rerun was then told to
// --resume, and --resume that it was no journal of depthprec's. ulimit -f 0 fails every write to
// a regular file (EFBIG, SIGXFSZ ignored) as a full disk does, before any OpenCL work.
TEST_CASE("a journal a failed write leaves is no rerun's obstacle", "[batch][journal]") {
  const std::string out = fresh("/tmp/depthprec_test_jfail.json"), journal = out + ".rows.jsonl";
  const std::string reference = fresh("/tmp/depthprec_test_jref.json");
  REQUIRE(run_cli(kJsonRun + " -o " + reference).exit_code == 0);
  const auto failed = run_shell("trap '' XFSZ; ulimit -f 0; '" + std::string(DEPTHPREC_EXE) + "' " +
                                kJsonRun + " -o " + out + " 2>&1");
  CHECK(failed.exit_code == 5);
  CHECK_THAT(failed.output, Contains("cannot append to the row journal"));
  CHECK_FALSE(exists(journal));
  CHECK_FALSE(exists(out + ".tmp"));
  REQUIRE(run_cli(kJsonRun + " -o " + out).exit_code == 0);
  CHECK(slurp(out) == slurp(reference));

  // The states such failures (or a kill) leave, made directly: a journal of this program's with
  // no finished row in it is started afresh, with --resume or without.
  // The first line of a journal as depthprec begins one (the run it names does not matter: a
  // journal without rows is started afresh whichever run it names).
  const std::string header =
      "{\"journal_of\":{\"kind\":\"mts\",\"program\":\"depthprec\",\"scene\":{\"near\":1}}}\n";
  for (const std::string& left : {std::string(), header.substr(0, 40), header}) {
    for (const bool resume : {false, true}) {
      INFO("journal of " << left.size() << " bytes, --resume " << resume);
      fresh(out);
      std::ofstream(journal) << left;
      const auto r = run_cli(kJsonRun + " -o " + out + (resume ? " --resume" : ""));
      INFO(r.output);
      CHECK(r.exit_code == 0);
      CHECK(slurp(out) == slurp(reference));
      CHECK_FALSE(exists(journal));
    }
  }
  // A file that is not this program's is the user's: refused and left as it is.
  fresh(out);
  std::ofstream(journal) << "my notes\n";
  CHECK(run_cli(kJsonRun + " -o " + out).exit_code == 5);
  CHECK(run_cli(kJsonRun + " -o " + out + " --resume").exit_code == 3);
  CHECK(slurp(journal) == "my notes\n");
  std::remove(journal.c_str());
}

// Before, a failed final write left FILE.tmp behind.
TEST_CASE("a failed output leaves no temporary file", "[batch][journal]") {
  for (const std::string& cmd :
       {std::string("formats"), std::string("resolve -t standard -f unorm16 --code 1")}) {
    INFO(cmd);
    const std::string out = fresh("/tmp/depthprec_test_tmpfail.txt");
    const auto r = run_shell("trap '' XFSZ; ulimit -f 0; '" + std::string(DEPTHPREC_EXE) + "' " +
                             cmd + " -o " + out + " 2>&1");
    CHECK(r.exit_code == 5);
    CHECK_THAT(r.output, Contains("cannot write output '" + out + "'"));
    CHECK_FALSE(exists(out + ".tmp"));
    CHECK_FALSE(exists(out));
  }
  // An output that is a directory is refused before the run, not found at its end.
  std::system("rm -rf /tmp/depthprec_test_outdir* && mkdir /tmp/depthprec_test_outdir");
  const auto dir = run_cli(kJsonRun + " -o /tmp/depthprec_test_outdir");
  CHECK(dir.exit_code == 5);
  CHECK_THAT(dir.output, Contains("'/tmp/depthprec_test_outdir': it is a directory"));
  CHECK_FALSE(exists("/tmp/depthprec_test_outdir.tmp"));
  CHECK_FALSE(exists("/tmp/depthprec_test_outdir.rows.jsonl"));
  // A batch whose output cannot be put in place (here: a directory appeared where it goes)
  // keeps its rows in the journal, says so, and --resume writes the output from them.
  const std::string out = fresh("/tmp/depthprec_test_tmpbatch.json"), journal = out + ".rows.jsonl";
  std::system(("rm -rf " + out).c_str());
  const std::string reference = fresh("/tmp/depthprec_test_tmpbatch_ref.json");
  REQUIRE(run_cli(kLong + " -o " + reference).exit_code == 0);
  const pid_t pid = start(kLong + " -o " + out, "/tmp/depthprec_test_tmpbatch.err");
  REQUIRE(wait_for_lines(journal, 1));  // a finished row
  kill(pid, SIGSTOP);
  REQUIRE_FALSE(exists(out));  // stopped before its end
  REQUIRE(::mkdir(out.c_str(), 0755) == 0);
  kill(pid, SIGCONT);
  CHECK(wait_exit(pid) == 5);
  const std::string err = slurp("/tmp/depthprec_test_tmpbatch.err");
  INFO(err);
  CHECK_THAT(err, Contains("cannot write output '" + out + "'") && Contains("--resume"));
  CHECK_FALSE(exists(out + ".tmp"));
  REQUIRE(::rmdir(out.c_str()) == 0);
  REQUIRE(run_cli(kLong + " -o " + out + " --resume").exit_code == 0);
  CHECK(slurp(out) == slurp(reference));
  CHECK_FALSE(exists(journal));
}

// Before, the second run was told to --resume the first, which was still running.
TEST_CASE("a second run with the same output is refused, naming the running one",
          "[batch][journal]") {
  const std::string out = fresh("/tmp/depthprec_test_twice.json"), journal = out + ".rows.jsonl";
  const pid_t first = start(kLong + " -o " + out, "/tmp/depthprec_test_twice.err");
  REQUIRE(wait_for_lines(journal, 1));  // it has started and finished a row
  kill(first, SIGSTOP);                 // and is held there, lock and all, while the second runs
  const auto second = run_cli(kLong + " -o " + out);
  const auto resumed = run_cli(kLong + " -o " + out + " --resume");
  kill(first, SIGCONT);
  INFO(second.output);
  CHECK(second.exit_code == 3);
  CHECK_THAT(second.output, Contains(journal) && Contains("process " + std::to_string(first)));
  CHECK(resumed.exit_code == 3);
  CHECK_THAT(resumed.output, Contains("process " + std::to_string(first)));
  CHECK(wait_exit(first) == 0);  // the first run was not disturbed
  CHECK_FALSE(exists(journal));
  // Once it has ended, the output is free again.
  CHECK(run_cli(kLong + " -o " + out).exit_code == 0);
}
