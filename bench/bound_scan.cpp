// The guaranteed MTS against a dense scan of the rotation cube (docs/bound.md): at a dozen rows of
// the default scene, under each profile and its own bound model, N uniform orientations (and the
// cube's corners) probed at mts_bound; none may fight. Prints one line per row and profile, and
// the total.
//   build/bench/bound_scan [N [PROFILE]]      (default 100000, every profile)
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "host/model/frame_setup.h"
#include "host/model/profile.h"
#include "host/mts/mts_bound.h"
#include "host/mts/mts_evaluator.h"
#include "host/mts/mts_search.h"
#include "host/mts/reference_pipeline.h"
#include "host/runtime/opencl_runtime.h"
#include "tests/support/bound_scan_rows.h"

using namespace depthprec;

int main(int argc, char** argv) {
  const size_t n = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 100000;
  const size_t chunk = 5000;  // orientations per evaluator: plane A's memory stays bounded
  const std::vector<std::pair<EvalPair, double>>& rows = test::bound_scan_rows();
  OpenClRuntime rt;
  // Whether any of the angles fights at separation sep (one evaluator over them all).
  const auto fights = [&rt](const Scene& s, const EvalPair& pair, double z, double sep,
                            const std::vector<Angles>& angles) {
    Scene part = s;
    part.frames = static_cast<int>(angles.size());
    Orientations o;
    o.at[z] = angles;
    MtsEvaluator ev(rt, part, pair, o);
    const Outcome out = ev.run({{z, sep}}).at(0).outcome;
    return out == Outcome::fight || out == Outcome::non_finite;
  };
  int fought_rows = 0;
  std::vector<std::string> profs = {"ideal", "llvmpipe", "softpipe"};
  if (argc > 2) profs = {argv[2]};
  for (const std::string& prof : profs) {
    std::vector<std::string> sets = profile(prof).sets;
    sets.push_back("bound_model=" + prof);
    Scene s = load_scene("", sets);
    const double r = s.rotation_range_deg * M_PI / 180;
    uint64_t seed = 1;
    for (const auto& [pair, z] : rows) {
      const MtsBound b = mts_bound(s, pair, z);
      if (!std::isfinite(b.s)) {  // no separation clears the bounds: the bound claims nothing
        fmt::print("{:<9} {:<36} z = {:<9g} mts_bound {:<11.4g} no finite bound: nothing to scan\n",
                   prof, pair.label(), z, b.s);
        continue;
      }
      std::mt19937_64 rng(seed++);
      std::uniform_real_distribution<double> u(-r, r);
      std::vector<Angles> fighting;  // the chunk that fought
      for (size_t done = 0; done < n && fighting.empty(); done += chunk) {
        std::vector<Angles> angles;
        if (done == 0)
          for (int c = 0; c < 8; ++c)
            angles.push_back({c & 1 ? r : -r, c & 2 ? r : -r, c & 4 ? r : -r});
        while (angles.size() < std::min(chunk, n - done) + (done == 0 ? 8 : 0))
          angles.push_back({u(rng), u(rng), u(rng)});
        if (fights(s, pair, z, b.s, angles)) fighting = angles;
      }
      if (fighting.empty()) {
        fmt::print("{:<9} {:<36} z = {:<9g} mts_bound {:<11.4g} clean over {} orientations\n", prof,
                   pair.label(), z, b.s, n + 8);
        std::fflush(stdout);
        continue;
      }
      ++fought_rows;
      // Halve the chunk down to one orientation that fights, then search its own MTS.
      while (fighting.size() > 1) {
        const std::vector<Angles> half(fighting.begin(), fighting.begin() + fighting.size() / 2);
        if (fights(s, pair, z, b.s, half))
          fighting = half;
        else
          fighting.erase(fighting.begin(), fighting.begin() + fighting.size() / 2);
      }
      Scene one = s;
      one.frames = 1;
      Orientations o;
      o.at[z] = fighting;
      MtsEvaluator ev(rt, one, pair, o);
      const MtsRow own = search_pair(ev, one, pair, {z}).at(0);
      fmt::print(
          "{:<9} {:<36} z = {:<9g} mts_bound {:<11.4g} FIGHTS at ({:.17g}, {:.17g}, {:.17g}) "
          "rad, whose own MTS is {:.4g}\n",
          prof, pair.label(), z, b.s, fighting[0][0], fighting[0][1], fighting[0][2], own.mts);
      // The same orientation as the scene's one frame (rotation_offset), without the kernel's
      // shortcuts and through the host reference pipeline: which of them says it fights.
      Scene frame = s;
      frame.frames = 1;
      for (int i = 0; i < 3; ++i) frame.rotation_offset[i] = std::asin(fighting[0][i] / r);
      MtsEvaluator plain(rt, frame, pair, Orientations{}, false);
      MtsEvaluator fast(rt, frame, pair, Orientations{});
      const Outcome o_plain = plain.run({{z, b.s}}).at(0).outcome,
                    o_fast = fast.run({{z, b.s}}).at(0).outcome;
      const FrameCodes ref = reference_frame(frame, pair, {z, b.s}, 0);
      int ref_fights = 0;
      size_t first = 0;
      for (size_t i = 0; i < ref.code_a.size(); ++i) {
        if (ref.status_a[i] != 0 || ref.status_b[i] != 0) continue;
        const bool f = info(pair.technique).greater ? ref.code_b[i] >= ref.code_a[i]
                                                    : ref.code_b[i] <= ref.code_a[i];
        if (f && ref_fights++ == 0) first = i;
      }
      fmt::print(
          "          as a frame: kernel {}, without shortcuts {}, host reference {} fighting "
          "pixels{}\n",
          to_string(o_fast), to_string(o_plain), ref_fights,
          ref_fights ? fmt::format(" (first: pixel {}, codes A {} B {})", first, ref.code_a[first],
                                   ref.code_b[first])
                     : "");
      std::fflush(stdout);
    }
  }
  const int fights_total = fought_rows;
  fmt::print("{} of {} rows fight at mts_bound\n", fights_total, profs.size() * rows.size());
  return fights_total == 0 ? 0 : 1;
}
