// What the plain host reference pipeline (host/mts/reference_pipeline.cpp: every kernel pixel of
// every frame, no shortcuts) says of a probe: the independent check of the kernel's outcomes and
// of a row's bracket.
#pragma once

#include "host/model/technique.h"
#include "host/mts/reference_pipeline.h"

namespace depthprec::test {

struct ReferenceOutcome {
  Outcome outcome =
      Outcome::clean;  // fight / non_finite at the first frame with one, else clipped or clean
  int frames = 0;      // frames up to the deciding one (all when not decided)
  bool any_uncovered = false;  // a kernel pixel that a plane did not cover, in the frames seen
};

// Frames in order 0, 1, ...; a frame decides with a non-finite value or a fight (B's code passes
// the depth test against A's: LEQUAL, or GEQUAL for the reversed mappings).
inline ReferenceOutcome reference_outcome(const Scene& scene, const EvalPair& pair,
                                          const Probe& probe) {
  ReferenceOutcome out;
  bool any_clipped = false;
  for (int frame = 0; frame < scene.frames; ++frame) {
    const FrameCodes r = reference_frame(scene, pair, probe, frame);
    bool fight = false, nonfinite = false;
    for (size_t i = 0; i < r.code_a.size(); ++i) {
      const int sa = r.status_a[i], sb = r.status_b[i];
      if (sa == 2 || sb == 2)
        nonfinite = true;
      else if (sa == 1 || sb == 1)
        any_clipped = true;
      else if (sa == 3 || sb == 3)
        out.any_uncovered = true;
      else if (info(pair.technique).greater ? r.code_b[i] >= r.code_a[i]
                                            : r.code_b[i] <= r.code_a[i])
        fight = true;
    }
    out.frames = frame + 1;
    if (nonfinite)
      out.outcome = Outcome::non_finite;
    else if (fight)
      out.outcome = Outcome::fight;
    if (out.outcome != Outcome::clean) return out;
  }
  if (any_clipped) out.outcome = Outcome::clipped;
  return out;
}

}  // namespace depthprec::test
