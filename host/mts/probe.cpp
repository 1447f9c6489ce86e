// The probe loop's pieces every evaluator shares (host/mts/probe.h): frame batches, the fold of a
// launch's row words into probe results, outcomes by name.
#include "host/mts/probe.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <limits>

#include "host/base/errors.h"
#include "interface/mts_layout.h"

namespace depthprec {

int batch_frames(int done, int total) {
  const int want = done == 0 ? 4 : done < 20 ? 16 : kMaxBatchFrames;
  return std::min(want, total - done);
}

std::vector<size_t> undecided(const std::vector<bool>& decided) {
  std::vector<size_t> out;
  for (size_t i = 0; i < decided.size(); ++i)
    if (!decided[i]) out.push_back(i);
  return out;
}

std::vector<uint64_t> fold_launch(const std::vector<uint32_t>& rows,
                                  const std::vector<size_t>& active, int first_frame, int frames,
                                  size_t kernel_h, std::vector<ProbeResult>& results,
                                  std::vector<bool>& decided, uint64_t& after_decision) {
  std::vector<uint64_t> probe_pairs(active.size(), 0);
  for (size_t i = 0; i < active.size(); ++i) {
    ProbeResult& r = results[active[i]];
    for (int f = 0; f < frames; ++f) {
      uint32_t flags = 0;
      uint64_t frame_pairs = 0;
      for (size_t y = 0; y < kernel_h; ++y) {
        const uint32_t v = rows[(i * frames + f) * kernel_h + y];
        flags |= v;
        frame_pairs += v >> MTS_R_COUNT_SHIFT;
      }
      probe_pairs[i] += frame_pairs;
      if (decided[active[i]]) {  // frames after the deciding one: work, not outcome
        after_decision += frame_pairs;
        continue;
      }
      r.frames = first_frame + f + 1;
      r.any_clipped |= (flags & MTS_R_CLIPPED) != 0;
      r.any_uncovered |= (flags & MTS_R_UNCOVERED) != 0;
      if (flags & MTS_R_NONFINITE) {
        r.any_non_finite = true;
        r.outcome = Outcome::non_finite;
        decided[active[i]] = true;
      } else if (flags & MTS_R_FIGHT) {
        r.outcome = Outcome::fight;
        decided[active[i]] = true;
      }
    }
    r.fragment_pairs += probe_pairs[i];
  }
  return probe_pairs;
}

void finish_outcomes(std::vector<ProbeResult>& results, const std::vector<bool>& decided) {
  for (size_t i = 0; i < results.size(); ++i)
    if (!decided[i] && results[i].any_clipped) results[i].outcome = Outcome::clipped;
}

Outcome search_outcome(const ProbeResult& r) {
  return r.outcome == Outcome::clean && r.any_uncovered ? Outcome::uncovered : r.outcome;
}

const char* to_string(Outcome o) {
  switch (o) {
    case Outcome::clean:
      return "clean";
    case Outcome::fight:
      return "fight";
    case Outcome::clipped:
      return "clipped";
    case Outcome::non_finite:
      return "non_finite";
    case Outcome::uncovered:
      return "uncovered";
  }
  return "?";
}

}  // namespace depthprec
