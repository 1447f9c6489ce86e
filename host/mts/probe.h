// A probe of the MTS search and what the evaluators say of it: the types the evaluators, the
// search and the tests share, and the probe loop every evaluator runs (host/mts/probe.cpp). No
// OpenCL: the rendering evaluator (host/render/) runs the same loop.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace depthprec {

// Where probes are decided: the emulated pipeline (kernels/mts.cl) or a real rasterizer through
// OpenGL (`depthprec render`, host/render/).
enum class RowSource { emulated, rendered };

struct Probe {
  double z;  // requested distance of plane A
  double s;  // requested separation: plane B at fl32(z + s)
};

// uncovered: no fight, but a kernel pixel that a plane does not cover (the search's reading of a
// clean result with any_uncovered; the evaluator itself reports clean and the flag).
enum class Outcome { clean, fight, clipped, non_finite, uncovered };
const char* to_string(Outcome o);

struct ProbeResult {
  Outcome outcome = Outcome::clean;
  int frames = 0;           // frames rendered up to and including the deciding one (all if clean)
  int deciding_frame = -1;  // the frame (index into the scene's frames) that decided it; -1: none
  uint64_t fragment_pairs = 0;  // pairs the kernel evaluated for this probe
  bool any_clipped = false, any_non_finite = false, any_uncovered = false;
  double seconds = 0;         // share of the launches' wall time, by fragment pairs
  double kernel_seconds = 0;  // share of the launches' device time (profiling events), likewise
  uint64_t launches = 0;      // kernel launches this probe took part in
};

// The outcome as a search reads it: nothing was compared at an uncovered pixel, so a clean result
// with any_uncovered is uncovered, never clean.
Outcome search_outcome(const ProbeResult& r);

// Stored codes and status (0 ok, 1 clipped, 2 non-finite, 3 uncovered) of both planes at every
// kernel pixel of one frame, row-major from the kernel's bottom-left pixel.
struct FrameCodes {
  int width = 0, height = 0;
  std::vector<uint32_t> code_a, code_b;
  std::vector<uint8_t> status_a, status_b;
};

// Frames per launch: most fighting probes fight in their first frames, so start small; a clean
// probe needs every frame, so grow.
constexpr int kMaxBatchFrames = 64;  // batch_frames' largest batch
int batch_frames(int done, int total);

// Indices of the probes not decided yet: the ones the next launch renders.
std::vector<size_t> undecided(const std::vector<bool>& decided);

// One launch's row words (flags | fragment pairs << 8 per (active probe, frame, kernel row), the
// layout of interface/mts_layout.h, which kernels/mts.cl and kernels/mts_exact.cl write), folded
// frame by frame into the active probes' results: a probe is decided at its first frame with a
// fight or a non-finite value. Returns each active probe's fragment pairs (all frames); those of
// frames after a probe's deciding one are also added to after_decision.
std::vector<uint64_t> fold_launch(const std::vector<uint32_t>& rows,
                                  const std::vector<size_t>& active, int first_frame, int frames,
                                  size_t kernel_h, std::vector<ProbeResult>& results,
                                  std::vector<bool>& decided, uint64_t& after_decision);
// After the last frame: an undecided probe that saw clipping is clipped, not clean.
void finish_outcomes(std::vector<ProbeResult>& results, const std::vector<bool>& decided);

// Decides batches of probes: the emulated pipeline (MtsEvaluator) or the storage-limited one
// (ExactEvaluator, host/mts/mts_exact.h), so one search drives both.
class ProbeEvaluator {
 public:
  virtual ~ProbeEvaluator() = default;
  virtual std::vector<ProbeResult> run(const std::vector<Probe>& probes) = 0;
  virtual RowSource source() const { return RowSource::emulated; }
  // How many distances a launch round should hold at most: an evaluator that keeps per-distance
  // state (the emulator's plane-A cache) names what fits its memory budget, so the search runs a
  // window of distances and never evicts one it will probe again.
  virtual size_t distances_at_once() const { return SIZE_MAX; }
};

}  // namespace depthprec
