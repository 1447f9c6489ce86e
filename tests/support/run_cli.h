// Runs the depthprec executable as a user would, capturing output and exit code.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace depthprec::test {

struct CliResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// Options for a command's run small enough for a test that checks behaviour, not figures.
inline const std::string kSmallScene = "--kernel 24x24 --frames 4 --no-timing -q ";

// Runs a shell command line, capturing what it writes to its standard output.
inline CliResult run_shell(const std::string& cmd) {
  CliResult r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
  const int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// env: assignments put before the command, e.g. "OCL_ICD_VENDORS=/nonexistent".
inline CliResult run_cli(const std::string& args, const std::string& env = "") {
  return run_shell(env + (env.empty() ? "" : " ") + "'" + DEPTHPREC_EXE + "' " + args + " 2>&1");
}

// Runs depthprec with its standard output sent to stdout_to (e.g. /dev/full, which refuses every
// write as a full disk does); output holds standard error alone.
inline CliResult run_cli_stdout_to(const std::string& args, const std::string& stdout_to) {
  return run_shell("'" + std::string(DEPTHPREC_EXE) + "' " + args + " 2>&1 >'" + stdout_to + "'");
}

// path, with any output and journal (path.rows.jsonl) an earlier, failed run left there removed:
// a test's run must not meet an interrupted run's journal.
inline std::string fresh(const std::string& path) {
  std::remove(path.c_str());
  std::remove((path + ".rows.jsonl").c_str());
  return path;
}

// The whole text of a file ("" if it cannot be read): outputs the commands wrote.
inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace depthprec::test
