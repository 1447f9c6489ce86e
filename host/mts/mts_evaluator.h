// Runs kernels/mts.cl for batches of probes (z, s) of one pair: each probe is rendered frame by
// frame until its first fight (docs/spec.md 5.2: a probe stops at its first fighting frame), many
// probes and frames per launch so independent distances share the device.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "host/model/frame_setup.h"
#include "host/model/scene.h"
#include "host/mts/probe.h"
#include "host/runtime/kernel_variant.h"
#include "host/runtime/opencl_runtime.h"
#include "interface/mts_kernel_args.h"

namespace depthprec {

// What mts_coverage_audit found over the cached kernel rows of a set of probes (every frame).
struct CoverageAudit {
  uint64_t rows = 0;                   // cached rows audited
  uint64_t b_differs = 0;              // rows where plane B's own coverage differs from plane A's
  uint64_t certified = 0;              // rows the shortcut would take B's coverage from A's
  uint64_t certified_but_differs = 0;  // both: the shortcut would be wrong (must be 0)
  uint64_t a_differs = 0;       // rows whose record is not plane A's own coverage (must be 0)
  uint64_t from_reference = 0;  // rows that took the reference distance's segments
  CoverageAudit& operator+=(const CoverageAudit& o) {
    rows += o.rows;
    b_differs += o.b_differs;
    certified += o.certified;
    certified_but_differs += o.certified_but_differs;
    a_differs += o.a_differs;
    from_reference += o.from_reference;
    return *this;
  }
};

// The kernels primed in one run (MtsEvaluator::prime_launches): each once, and a job that needs
// one another job is priming waits until that is done.
class LaunchPrimer {
 public:
  // Runs prime() unless it ran for `kernel` (its program, options and name) already; returns
  // once it has run.
  void once(const std::string& kernel, const std::function<void()>& prime);

 private:
  std::mutex m_;
  std::map<std::string, std::once_flag> flags_;
};

class MtsEvaluator : public ProbeEvaluator {
 public:
  // shortcuts: work the kernels save only where a certificate says the answer stays the same —
  // bands of rows decided clean from code bounds (mts_frame_bounds) before rasterising, and plane
  // B's coverage of a row taken from plane A's within A's coverage margin (b_coverage_is_a); off
  // only to check that they never change a result.
  //
  // kernels: production programs hold only what a run needs (kernels/mts.cl); with_tests also
  // builds kernels/mts_test.cl with the same defines for mts_codes and mts_coverage_audit, which
  // codes() and audit_coverage() need. Everything else runs from the production program.
  enum class Kernels { production, with_tests };
  MtsEvaluator(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair, bool shortcuts = true,
               Kernels kernels = Kernels::production)
      : MtsEvaluator(rt, scene, pair, Orientations{}, shortcuts, kernels) {}
  // orientations: the frames' sampled ones where a distance has them (worst-case sampling).
  MtsEvaluator(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
               const Orientations& orientations, bool shortcuts = true,
               Kernels kernels = Kernels::production);

  // A probe that repeats an earlier one's computation takes its result (probes_repeated).
  std::vector<ProbeResult> run(const std::vector<Probe>& probes) override;
  size_t distances_at_once() const override { return max_slots_; }
  FrameCodes codes(const Probe& probe, int frame);  // needs Kernels::with_tests
  // For the tests: checks the coverage shortcut of mts_raster against plane B's own coverage on
  // every cached row of every frame of the probes (their distances in groups of
  // max_plane_a_slots()). Needs Kernels::with_tests.
  CoverageAudit audit_coverage(const std::vector<Probe>& probes);

  const KernelVariant& variant() const { return variant_; }
  uint64_t fragment_pairs() const { return pairs_; }
  uint64_t launches() const { return launches_; }
  double kernel_seconds() const { return kernel_seconds_; }  // device time of all launches
  double wall_seconds() const { return wall_seconds_; }      // host wall time of all launches
  // Fragment pairs spent on probes by their outcome (index: Outcome), and on the frames of a
  // launch batch after a probe's deciding frame: where the work goes (-v prints it).
  const std::array<uint64_t, 4>& pairs_by_outcome() const { return by_outcome_; }
  uint64_t pairs_after_decision() const { return after_decision_; }
  // Fragment pairs in bands decided clean from code bounds, without rasterising.
  uint64_t pairs_decided_by_bounds() const { return by_bounds_; }
  // Rasterised kernel rows, and those of them whose plane-B coverage was plane A's.
  uint64_t rows_rasterised() const { return rows_rasterised_; }
  uint64_t rows_with_coverage_of_a() const { return rows_reused_; }
  // Probes that took an earlier probe's result (full_runs_) instead of being rendered.
  uint64_t probes_repeated() const { return repeats_; }
  // Distances the plane-A cache may hold at once (cache_plane_a): its memory budget's share.
  size_t max_plane_a_slots() const { return max_slots_; }
  // Shares the plane-A cache's budget with this many evaluators in all (pairs run side by side);
  // before the first run.
  void share_plane_a_budget(int evaluators);

  // Evaluators running side by side (run_scene's jobs) must not make PoCL's CPU driver load a
  // kernel's work-group function anew while other launches of it are in flight. PoCL 3.1 keeps
  // the functions it loaded in entries per kernel and local size, each good for grids up to the
  // width of the launch that made it; a wider launch adds an entry in front, and a launch that
  // finishes releases the first entry of its kernel and local size, not necessarily the one it
  // took. A launch in flight while a wider one adds an entry can so release that entry once too
  // often, and PoCL aborts (lib/CL/devices/common.c, pocl_release_dlhandle_cache: "Assertion
  // `found->ref_count > 0' failed"): 10 of 12 runs of `mts -t standard,reversed -f float32
  // --frames 30 --jobs 6` did. prime_launches launches each of its kernels not primed yet in
  // this run (LaunchPrimer) once over a grid as wide as any of its later launches, every
  // work-item returning at once, so that one entry serves them all. run_scene's jobs call it
  // before their first launch, with the widest launches of every evaluator of the run, and every
  // launch after it checks that it is no wider. The priming launches compute nothing and are not
  // counted.
  struct LaunchWidths {  // the widest grid dimension of each kernel's launches, in work-items
    size_t setup = 0, a_rows = 0, a_bands = 0, bounds = 0, raster = 0;
    LaunchWidths& operator|=(const LaunchWidths& o);  // the wider of each
  };
  // variant: the pair's, mts_variant(scene, pair), which the run has in its plan (made once).
  static LaunchWidths widest_launches(const Scene& scene, const KernelVariant& variant,
                                      int evaluators);
  void prime_launches(const LaunchWidths& widths, LaunchPrimer& primer);

  // The plane-A cache's buffers, handed from a finished evaluator to the next of its pair (the
  // worst case's chunks, each an evaluator of its own, with as many slots as distances are still
  // open, up to the budget's): its row records are tens of MB that the kernels otherwise fault in
  // page by page, zeroed, for every chunk. The contents are never read before this evaluator
  // writes them (cache_plane_a fills a slot before any launch reads it, and the reference is
  // marked absent).
  struct PlaneABuffers {
    cl::Buffer consts, tris, vflags, rows, bands, codes, ref_tris, ref_rows;
    size_t bytes() const;  // in all (0: none)
  };
  // This evaluator's, once it has run (none if it never cached plane A).
  PlaneABuffers release_plane_a_buffers();
  // Kept for the first fill of the cache, which takes each buffer at least as large as it needs
  // and at most half as large again.
  void adopt_plane_a_buffers(PlaneABuffers&& spare) { spare_ = std::move(spare); }

 private:
  // Enqueues mts_setup for planes given by their matrices (16 floats each, in mats), written to
  // tris and vflags from first_plane on; plane k uses the probe constants (consts) of
  // (first_plane + k) / per_probe. Returns its event.
  cl::Event setup(const cl::Buffer& consts, const std::vector<float>& mats, cl_uint per_probe,
                  cl_uint first_plane, cl::Buffer& tris, cl::Buffer& vflags);
  // Plane A depends on the distance and frame only, so it is set up, its rows' coverage and codes
  // found and its code bounds per band computed once per distance, for all frames, and kept for
  // every later probe of the distance (kernels/mts/plane_a.cl mts_a_rows, kernels/mts/bounds.cl
  // mts_a_bands). Returns each active probe's slot, filling the slots of distances not held yet;
  // adds their device time, and sets each active probe's launches to those that filled its slot now
  // (0 when it was held).
  std::vector<cl_uint> cache_plane_a(const std::vector<Probe>& probes,
                                     const std::vector<size_t>& active, double& kernel_seconds,
                                     std::vector<int>& launches);
  // Sets up plane B of the active probes for their visits [first_frame, first_frame + frames) (a
  // probe's visit k renders frame (first_visited + k) mod frames), with their constants, plane-A
  // slots and first frames (slot_buf: slot, first frame per probe); returns the set-up kernel's
  // event.
  cl::Event setup_plane_b(const std::vector<Probe>& probes, const std::vector<size_t>& active,
                          const std::vector<cl_uint>& slots, const std::vector<int>& first_visited,
                          int first_frame, int frames, cl::Buffer& probe_buf, cl::Buffer& slot_buf,
                          cl::Buffer& tris, cl::Buffer& vflags);
  // Renders the probes: their results, and which were decided before their last frame (a fight or
  // a non-finite frame).
  std::vector<ProbeResult> run_fresh(const std::vector<Probe>& probes, std::vector<bool>& decided);
  // What a probe's computation depends on besides the evaluator's scene and pair: its distance z
  // (plane A, the probe constants) and the distance plane B is built from (its matrices in every
  // frame).
  std::pair<double, double> plane_b_key(const Probe& probe) const;
  // Marks plane A of these distances, where held, used now (the cache's least-recently-used
  // order).
  void touch_plane_a(const std::vector<double>& zs);
  // The launches of one batch of frames of a probe, plane A already held.
  uint64_t launches_per_batch() const;
  // The launches of a probe rendered through every frame, plane A already held.
  uint64_t full_run_launches() const;
  // Renders the probes of group (distances that fit in the cache together) frame batch by frame
  // batch.
  void run_group(const std::vector<Probe>& probes, const std::vector<size_t>& group,
                 const std::vector<int>& first_visited, std::vector<ProbeResult>& results,
                 std::vector<bool>& decided);
  // audit_coverage for probes whose distances the plane-A cache holds at once.
  CoverageAudit audit_cached(const std::vector<Probe>& probes);
  // The probes (indices) in groups whose distances the plane-A cache holds at once, each group
  // starting at the first probe not yet taken.
  std::vector<std::vector<size_t>> cache_groups(const std::vector<Probe>& probes) const;
  // Grows the plane-A cache (emptying it) to hold the probes' distances, within max_slots_;
  // returns how many distinct distances the probes have.
  size_t reserve_plane_a(const std::vector<Probe>& probes);
  cl_uint bands() const;
  MtsKernelArea area() const;  // the measurement kernel as every launch gets it

  OpenClRuntime& rt_;
  const Scene& scene_;
  EvalPair pair_;
  Orientations orientations_;
  KernelVariant variant_;
  // The kernel's bottom-left corner in window coordinates (the kernel is centred in the viewport).
  float origin_x() const { return static_cast<float>((scene_.viewport_w - scene_.kernel_w) / 2); }
  float origin_y() const { return static_cast<float>((scene_.viewport_h - scene_.kernel_h) / 2); }

  cl::Program program_, test_program_;  // test_program_: with Kernels::with_tests only
  cl::Kernel setup_, a_rows_, a_bands_, bounds_, raster_;
  const cl::Program& test_program()
      const;                  // test_program_, or an internal error without the test kernels
  size_t plane_floats_ = 0;   // floats per plane record (interface/mts_layout.h MTS_PLANE_STRIDE)
  size_t row_words_ = 0;      // words per cached row of plane A (MTS_ROW_WORDS)
  size_t band_words_ = 0;     // words per band of plane A (MTS_BAND_WORDS)
  size_t decided_words_ = 0;  // words per band of mts_frame_bounds' verdicts (MTS_DECIDED_WORDS)
  size_t max_slots_ = 1;
  struct PlaneACache {
    size_t capacity = 0;    // slots, each one distance with all its frames
    std::vector<double> z;  // the distance in each slot (NaN: free)
    std::vector<uint64_t> last_use;
    uint64_t clock = 0;
    cl::Buffer consts, tris, vflags, rows, bands, codes;
    // The first distance filled, every frame: rows at later distances take its segments where
    // they provably are theirs (kernels/mts/plane_a.cl, row_from_reference).
    cl::Buffer ref_tris, ref_rows;
    bool has_ref = false;
  } a_;
  PlaneABuffers spare_;
  // spare, when it holds at least bytes and at most half as much again, else a new buffer.
  cl::Buffer reuse_or_make(cl::Buffer& spare, size_t bytes);
  bool shortcuts_ = true;
  // Whether mts_a_rows fills the plane-A cache's codes (CACHE_A_CODES variants): they pay for
  // themselves over a search's many probes of a distance, not in a chunk's one (Orientations::
  // chunk), where mts_raster computes A's codes only in the bands it rasterises.
  bool fill_a_codes_ = true;
  // Frame order: a probe visits the frames cyclically from the one that decided the last fighting
  // probe of its distance (0 before there is one). Below the MTS a distance fights in few frames,
  // mostly the same ones probe after probe, so a fighting probe is decided in its first launch
  // instead of after most frames. Whether a probe fights does not depend on the order; which of
  // its frames decides it, and so its frames count and a non_finite or clipped seen before the
  // fight, does (docs/mts.md, frame order).
  std::map<double, int> last_fight_frame_;
  // Probes that went through every frame (clean, clipped or uncovered), by plane_b_key. Plane B's
  // distance is a binary32, so a search whose bracket spans a few of its ulps asks for the same
  // plane B again and again while it bisects to a fraction of the MTS (and its stiffness probes
  // ask for the MTS's own plane B): such a probe takes the earlier one's result, work counts
  // included, as a row taken over from an identical computation does (run_scene). A probe a fight
  // decided is rendered again: which frame decides it depends on the frame order.
  std::map<std::pair<double, double>, ProbeResult> full_runs_;
  uint64_t pairs_ = 0, launches_ = 0, after_decision_ = 0, by_bounds_ = 0, rows_rasterised_ = 0,
           rows_reused_ = 0, repeats_ = 0;
  std::array<uint64_t, 4> by_outcome_{};
  double kernel_seconds_ = 0, wall_seconds_ = 0;
  LaunchWidths primed_;  // prime_launches' widths; 0: not primed (one job)
  // Enqueues kernel k over global (local: kLocal in the first dimension), after checking that no
  // dimension is wider than primed (0: no check).
  void launch(cl::Kernel& k, size_t primed, const cl::NDRange& global, const cl::NDRange& local,
              cl::Event* done = nullptr);
};

}  // namespace depthprec
