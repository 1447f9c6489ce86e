#include "host/output/progress.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

namespace depthprec {

bool stderr_is_terminal() {
  return isatty(STDERR_FILENO) == 1;
}

Progress::Progress(std::string what, size_t total, bool enabled)
    : what_(std::move(what)),
      total_(total),
      enabled_(enabled && total > 0),
      start_(std::chrono::steady_clock::now()) {}

// Erases the line it drew (carriage return, then ANSI erase-to-end-of-line: it is only drawn on a
// terminal), so what follows starts on a clean line instead of after the last ETA.
Progress::~Progress() {
  if (enabled_ && done_ > 0) {
    std::fputs("\r\033[K", stderr);
    std::fflush(stderr);
  }
}

void Progress::advance(size_t rows) {
  done_ += rows;
  if (!enabled_) return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double eta =
      done_ ? elapsed / static_cast<double>(done_) * static_cast<double>(total_ - done_) : 0;
  fmt::print(stderr, "\r{}: {}/{} rows, {:.0f} s elapsed, ETA {:.0f} s   ", what_, done_, total_,
             elapsed, eta);
  std::fflush(stderr);
}

}  // namespace depthprec
