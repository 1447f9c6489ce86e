// What a run of MTS rows says of itself beside its rows: the device, what rendered rows were
// rendered with, the kernel variants, the work and the times, and how the output is to be read
// back (kind, shard). The runs fill it (host/mts/mts_run.h, host/render/render_run.h) and every
// output prints it (host/output/report.h).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace depthprec {

// What rendered rows were rendered with (`depthprec render`): empty for the emulator.
struct RenderedWith {
  std::string renderer, version, platform;           // GL_RENDERER, GL_VERSION, EGL platform
  std::map<std::string, std::string> depth_buffers;  // format -> what the driver allocated
  bool empty() const { return renderer.empty(); }
};

struct RunInfo {
  std::string device;
  RenderedWith rendered;
  std::vector<std::string> variants;  // kernel variants built, as labels
  uint64_t fragment_pairs = 0;  // the rows' work: what the measurement takes, however it was run
  uint64_t evaluated_pairs =
      0;  // what this process's kernels evaluated (rows taken over from an
          // identical computation, or resumed, cost nothing): the rate's numerator
  uint64_t launches = 0;
  double wall_seconds = 0;
  double kernel_seconds = 0;
  bool timing = true;        // false: leave every measured time out (--no-timing)
  std::string kind = "mts";  // "mts" (one line per row) or "table" (wide): what merge re-renders
  std::string shard;         // "i/N" when this output is one shard of a batch
};

}  // namespace depthprec
