// Progress of a batch on stderr: units done of total, elapsed time and an ETA, redrawn on one
// line. Only when stderr is a terminal and not --quiet, so logs and pipes stay clean.
#pragma once

#include <chrono>
#include <string>

namespace depthprec {

class Progress {
 public:
  // unit: what the total counts ("rows", "set-ups").
  Progress(std::string what, size_t total, bool enabled, std::string unit = "rows");
  ~Progress();  // ends the line it drew
  void advance(size_t rows = 1);
  // Redraws the line with the step under way ("standard/unorm24/gl: fixes"): a unit that takes
  // minutes shows what it is doing, not a line frozen since the last unit.
  void doing(const std::string& step);

 private:
  void draw();
  std::string what_, unit_, step_;
  size_t total_, done_ = 0;
  bool enabled_, drawn_ = false;
  std::chrono::steady_clock::time_point start_;
};

// True when stderr is a terminal.
bool stderr_is_terminal();

}  // namespace depthprec
