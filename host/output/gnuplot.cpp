#include "host/output/gnuplot.h"

#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "host/base/errors.h"
#include "host/output/report.h"

namespace depthprec {

std::string gnuplot_terminal(const std::string& output) {
  const auto ends_with = [&output](const std::string& e) {
    return output.size() >= e.size() && output.compare(output.size() - e.size(), e.size(), e) == 0;
  };
  if (ends_with(".png")) return "pngcairo size 1200,800 font \"sans,11\"";
  if (ends_with(".svg")) return "svg size 1200,800 font \"sans,11\"";
  throw InputError(fmt::format("plot: output '{}' must end in .png or .svg", output));
}

void check_plot_output(const std::string& path) {
  if (path.empty()) return;
  gnuplot_terminal(path);
  check_writable(path);
}

std::string gnuplot_quote(const std::string& s) {
  std::string out;
  for (char c : s) out += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
  return "\"" + out + "\"";
}

std::string gnuplot_writes(const std::string& output) {
  return is_stream_output(output) ? output : output + ".tmp";
}

void run_gnuplot(const std::string& script, const std::string& output) {
  char path[] = "/tmp/depthprec_plot_XXXXXX";
  const int fd = mkstemp(path);
  if (fd < 0) throw OutputError("plot: cannot create a temporary gnuplot script");
  const bool ok = write(fd, script.data(), script.size()) == static_cast<ssize_t>(script.size());
  close(fd);
  if (!ok) throw OutputError("plot: cannot write the temporary gnuplot script");
  // gnuplot's messages are diagnostics: on stderr, never mixed into a result on standard output.
  const int status = std::system(fmt::format("gnuplot '{}' 1>&2", path).c_str());
  std::remove(path);
  const std::string written = gnuplot_writes(output);
  const bool in_place = written == output;
  const bool drawn = status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (drawn && (in_place || std::rename(written.c_str(), output.c_str()) == 0)) return;
  const int err = errno;
  if (!in_place) std::remove(written.c_str());  // what a failed gnuplot drew is no plot
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) == 127)
    throw RuntimeError("plot: gnuplot did not run: install gnuplot-nox (scripts/setup.sh does)");
  if (!drawn) throw OutputError(fmt::format("plot: gnuplot failed writing '{}'", output));
  throw OutputError(fmt::format("cannot write output '{}': {}", output, std::strerror(err)));
}

}  // namespace depthprec
