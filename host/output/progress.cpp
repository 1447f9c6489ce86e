#include "host/output/progress.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

namespace depthprec {

bool stderr_is_terminal() {
  return isatty(STDERR_FILENO) == 1;
}

Progress::Progress(std::string what, size_t total, bool enabled, std::string unit)
    : what_(std::move(what)),
      unit_(std::move(unit)),
      total_(total),
      enabled_(enabled && total > 0),
      start_(std::chrono::steady_clock::now()) {}

// Erases the line it drew (carriage return, then ANSI erase-to-end-of-line: it is only drawn on a
// terminal), so what follows starts on a clean line instead of after the last ETA.
Progress::~Progress() {
  if (enabled_ && drawn_) {
    std::fputs("\r\033[K", stderr);
    std::fflush(stderr);
  }
}

void Progress::advance(size_t rows) {
  done_ += rows;
  step_.clear();
  draw();
}

void Progress::doing(const std::string& step) {
  step_ = step;
  draw();
}

void Progress::draw() {
  if (!enabled_) return;
  drawn_ = true;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  // No ETA before a unit has finished: there is nothing to extrapolate from.
  const std::string eta =
      done_ ? fmt::format(", ETA {:.0f} s", elapsed / static_cast<double>(done_) *
                                                static_cast<double>(total_ - done_))
            : "";
  // the erase clears what a longer line before it left
  fmt::print(stderr, "\r{}: {}/{} {}, {:.0f} s elapsed{}{}\033[K", what_, done_, total_, unit_,
             elapsed, eta, step_.empty() ? "" : "; " + step_);
  std::fflush(stderr);
}

}  // namespace depthprec
