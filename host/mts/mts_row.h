// One row of the MTS table: a (pair, distance) with its MTS or verdict, the bracket, the work
// and the flags (docs/spec.md 5.4), as the search fills it and every output reads it.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "host/model/scene.h"
#include "host/mts/probe.h"

namespace depthprec {

// What a row finally says: a number (resolved) or why there is none.
enum class Verdict {
  resolved,
  unresolvable,
  non_finite,
  clipped,
  uncovered,
  below_vertex_bound,
  beyond_far_plane,
  nearer_than_near_plane,
};
const char* to_string(Verdict v);  // "resolved", ..., "below vertex bound", "beyond far plane"

const char* to_string(RowSource s);                // "emulated", "rendered"
RowSource parse_row_source(const std::string& s);  // throws InputError

struct MtsRow {
  EvalPair pair;
  RowSource source = RowSource::emulated;
  // The implementation profile an emulated row's pipeline matches (docs/spec.md 2: ideal,
  // llvmpipe, or custom); empty for a rendered row, whose arithmetic is the driver's.
  std::string profile;
  double z = 0;
  double mts = 0;  // hi: the smallest separation seen that never fought; +inf if unresolvable
  double lo = 0, hi = 0;
  double mts_seen = 0;  // fl32(z + mts) - fl32(z)
  double vertex_bound = 0;
  int probes = 0;
  uint64_t frames = 0;
  uint64_t fragment_pairs = 0;
  // Kernel launches its probes took part in. Launches render the probes of every distance of a
  // pair at once, so rows share them: a row never counts more than the run made, and the rows of
  // a run add up to more than its total (the footer's "kernel launches").
  uint64_t launches = 0;
  double seconds = 0;            // attributed wall time of the launches (by fragment pairs)
  double kernel_seconds = 0;     // attributed device time of the launches (profiling events)
  double frames_per_second = 0;  // rendered rows: frames / seconds (a measured time)
  int clipped_probes = 0;        // probes in which some fragment left the clip volume
  // clipped: the row has no MTS because every separation that did not fight was clipped.
  bool non_finite = false, clipped = false, unresolvable = false, non_monotone = false,
       uncovered = false;
  bool beyond_far = false;  // z past the far plane of a technique that has one: not searched
  bool before_near =
      false;  // z nearer than the near plane of a technique that clips there: not searched
  // A resolved MTS (as seen, mts_seen) below the width of the code interval holding z (less the
  // bisection's precision twice over): the planes' depths in the kernel did not span one code,
  // so where z falls between two codes decided the answer, and a z nearby can need up to
  // code_width (docs/mts.md, "Below one code").
  bool below_one_code = false;
  double code_width = 0;  // that width, when below_one_code
  // Away from the world origin: a resolved MTS below world_grid_reach (host/model/frame_setup.h),
  // the depth the rounding of the planes' world coordinates can move; which orientations meet
  // such a rounding is a coincidence sampling finds at random (docs/mts.md, "Below the world
  // grid").
  bool below_world_grid = false;
  double world_grid_reach = 0;  // that reach, when below_world_grid
  // Over every probe (search and stiffness): the largest separation that fought and the
  // smallest clean one. fight_max > clean_min is a non-monotone bracket; fight_max is then the
  // upper MTS (every clean answer lies above it). 0 / +inf when there is none.
  double fight_max = 0, clean_min = std::numeric_limits<double>::infinity();
  // Why a row is non_monotone: in one search, over one set of frames, a clean probe at
  // monotone_clean below one that fought at monotone_fight (NaN: none seen). Kept from the search
  // that first saw it, when later searches (the worst case's) replace the bracket.
  double monotone_clean = std::numeric_limits<double>::quiet_NaN(),
         monotone_fight = std::numeric_limits<double>::quiet_NaN();
  // Worst-case sampling (docs/mts.md, "The worst case"): the MTS over the scene's frames alone
  // (the paper's; equal to mts under sampling paper), how many orientations the answer rests on,
  // and the relative rise of the MTS in the last refinement (0 when it found nothing higher).
  double mts_paper = std::numeric_limits<double>::quiet_NaN();
  uint64_t orientations = 0;
  double convergence = 0;
  // The guaranteed MTS (host/mts/mts_bound.h) under bound_model (the scene's,
  // host/model/bound_model.h): a separation at and above which
  // no pixel can fight in any orientation of the cube under any implementation of the model. NaN
  // where the row has no MTS or the model has no bound (bound_note says why), +inf where no
  // separation up to the search's ceiling clears the error bounds; otherwise bound_note names the
  // error term that weighs most.
  double mts_bound = std::numeric_limits<double>::quiet_NaN();
  std::string bound_model, bound_note;
  // MTS attribution (table --attribute; NaN when not computed): the MTS of the storage-limited
  // pipeline (exact up to binary64, then stored) and of the arithmetic-limited one (the binary32
  // pipeline, no storage quantisation); the vertex bound is the third factor.
  double storage_mts = std::numeric_limits<double>::quiet_NaN();
  double arithmetic_mts = std::numeric_limits<double>::quiet_NaN();
  bool attributed() const { return !std::isnan(storage_mts); }
  // The largest factor: "storage", "arithmetic" or "vertex" ("" when not attributed). The
  // binary32 pipeline holds the vertex rounding too, so its factor never falls below the vertex
  // bound: "vertex" is named when neither other factor exceeds it by more than the bisection's
  // resolution (set_dominant).
  std::string dominant;
  void set_dominant(double rel_precision);
  // A factor larger than the MTS itself (by more than the bisection's precision twice over):
  // the factors interact, and rounding errors can cancel (docs/stability.md).
  bool factor_above_mts(double rel_precision) const;
  // A probe's work (frames, fragment pairs, times) and the clipping and uncovered pixels it saw;
  // its launches are the caller's to count (rows share them).
  void add_probe_work(const ProbeResult& r);
  std::string flags() const;  // "non_finite,clipped" or "" when none
  Verdict verdict() const;
};

}  // namespace depthprec
