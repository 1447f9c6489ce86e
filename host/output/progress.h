// Progress of a batch on stderr: rows done of total, elapsed time and an ETA, redrawn on one
// line. Only when stderr is a terminal and not --quiet, so logs and pipes stay clean.
#pragma once

#include <chrono>
#include <string>

namespace depthprec {

class Progress {
 public:
  Progress(std::string what, size_t total, bool enabled);
  ~Progress();  // ends the line it drew
  void advance(size_t rows = 1);

 private:
  std::string what_;
  size_t total_, done_ = 0;
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
};

// True when stderr is a terminal.
bool stderr_is_terminal();

}  // namespace depthprec
