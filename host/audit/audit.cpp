#include "host/audit/audit.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include "host/audit/audit_device.h"
#include "interface/audit_layout.h"

namespace depthprec {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// A pair's pixels over every frame, before they are summarised.
struct PairPixels {
  FightPair pair;
  std::vector<double> depths, separations;
};

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  const size_t m = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + m, v.end());
  return v[m];
}

// The pixels of one frame with `flag` (and, for coplanar, another surface winning), added to the
// pairs by (winner draw, front draw).
void gather(const AuditSetup& a, const SceneGeometry& g, const AuditPixels& px, uint32_t flag,
            int frame, std::map<std::pair<int, int>, PairPixels>& pairs) {
  const auto draw_index = [&g](uint32_t t) {
    return static_cast<int>(&g.draw_of(t) - g.draws.data());
  };
  for (int y = 0; y < px.height; ++y)
    for (int x = 0; x < px.width; ++x) {
      const size_t i = static_cast<size_t>(y) * px.width + x;
      if (!(px.flags[i] & flag) || px.winner[i] == px.front[i] || px.winner[i] == AUDIT_NONE)
        continue;
      const uint32_t w = px.winner[i], f = px.front[i];
      PairPixels& p = pairs[{draw_index(w), draw_index(f)}];
      if (p.pair.pixels == 0) {
        p.pair.winner_draw = draw_index(w);
        p.pair.front_draw = draw_index(f);
        p.pair.winner_triangle = w;
        p.pair.front_triangle = f;
      }
      ++p.pair.pixels;
      const float fx = static_cast<float>(x) + 0.5f, fy = static_cast<float>(y) + 0.5f;
      const double df = ray_depth(a.ray, a.planes[f], fx, fy);
      p.depths.push_back(df);
      p.separations.push_back(ray_depth(a.ray, a.planes[w], fx, fy) - df);
      auto& samples = p.pair.samples;
      if (samples.empty() || samples.back().frame != frame) samples.push_back({frame, {}});
      if (samples.back().pixels.size() < kFixPixels) {
        samples.back().pixels.emplace_back(x, y);
        for (uint32_t t : {w, f})
          if (std::find(p.pair.triangles.begin(), p.pair.triangles.end(), t) ==
              p.pair.triangles.end())
            p.pair.triangles.push_back(t);
      }
    }
}

// The pixel pass of one view, a surface's own seams told apart from fights.
AuditPixels audit_pixels(OpenClRuntime* rt, const Scene& s, const AuditSetup& a,
                         const SceneGeometry& g, bool reference) {
  AuditPixels px = reference ? audit_reference(s, a) : audit_device(*rt, s, a);
  for (size_t i = 0; i < px.flags.size(); ++i)
    if ((px.flags[i] & AUDIT_FIGHT) && g.neighbours(px.winner[i], px.front[i]))
      px.flags[i] = (px.flags[i] & ~AUDIT_FIGHT) | AUDIT_SEAM;
  return px;
}

std::vector<FightPair> summarised(std::map<std::pair<int, int>, PairPixels>& pairs, size_t max) {
  std::vector<FightPair> out;
  for (auto& [key, p] : pairs) {
    FightPair f = p.pair;
    f.depth_min = *std::min_element(p.depths.begin(), p.depths.end());
    f.depth_max = *std::max_element(p.depths.begin(), p.depths.end());
    f.depth_median = median(p.depths);
    f.separation_min = *std::min_element(p.separations.begin(), p.separations.end());
    f.separation_median = median(p.separations);
    out.push_back(std::move(f));
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const FightPair& a, const FightPair& b) { return a.pixels > b.pixels; });
  if (out.size() > max) out.resize(max);
  return out;
}

}  // namespace

SetupAudit audit_setup_pair(OpenClRuntime* rt, const Scene& scene, const EvalPair& pair,
                            const SceneGeometry& g, const AuditRequest& req) {
  SetupAudit out;
  out.pair = pair;
  if (scene.pipeline.shader_precision != ShaderPrecision::highp)
    out.reduced_precision = to_string(scene.pipeline.shader_precision);
  std::map<std::pair<int, int>, PairPixels> fights, coplanar;
  for (size_t k = 0; k < req.frames.size(); ++k) {
    const Scene s = audit_scene(scene, req.frames[k]);
    auto t0 = std::chrono::steady_clock::now();
    const AuditSetup a = audit_setup(s, pair, g, req.frames[k]);
    out.setup_seconds += seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    AuditPixels px = audit_pixels(rt, s, a, g, req.reference);
    if (!out.reduced_precision.empty()) {  // the same view with highp shaders: which fights the
                                           // reduced precision alone makes
      Scene highp = s;
      highp.pipeline.shader_precision = ShaderPrecision::highp;
      const AuditPixels hp =
          audit_pixels(rt, highp, audit_setup(highp, pair, g, req.frames[k]), g, req.reference);
      for (size_t i = 0; i < px.flags.size(); ++i)
        out.precision_only_pixels += (px.flags[i] & AUDIT_FIGHT) && !(hp.flags[i] & AUDIT_FIGHT);
    }
    out.pixel_seconds += seconds_since(t0);  // the highp pass's too
    ++out.frames;
    out.pixels += px.flags.size();
    for (uint32_t f : px.flags) {
      out.covered_pixels += (f & AUDIT_COVERED) != 0;
      out.fighting_pixels += (f & AUDIT_FIGHT) != 0;
      out.coplanar_pixels += (f & AUDIT_COPLANAR) != 0;
      out.discarded_pixels += (f & AUDIT_DISCARDED) != 0;
      out.undrawn_pixels += (f & AUDIT_UNDRAWN) != 0;
      out.seam_pixels += (f & AUDIT_SEAM) != 0;
      out.at_risk_pixels += (f & AUDIT_AT_RISK) != 0;
    }
    gather(a, g, px, AUDIT_FIGHT, static_cast<int>(k), fights);
    gather(a, g, px, AUDIT_COPLANAR, static_cast<int>(k), coplanar);
    if (k == 0) {
      out.records = a.records.size();
      out.culled = a.culled;
      out.clipped = a.clipped;
      out.non_finite = a.non_finite;
      out.shade.assign(px.flags.size(), 0);
      for (size_t i = 0; i < px.front.size(); ++i) {
        if (px.front[i] == AUDIT_NONE) continue;
        const auto& n = a.planes[px.front[i]];
        const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        out.shade[i] = static_cast<uint8_t>(70 + 150 * (len > 0 ? std::fabs(n[2]) / len : 0));
      }
      out.image = std::move(px);
    }
  }
  out.pairs = summarised(fights, req.max_pairs);
  out.coplanar_pairs = summarised(coplanar, req.max_pairs);
  return out;
}

std::vector<AuditCamera> jittered_frames(const AuditCamera& camera, int frames, double jitter) {
  std::vector<AuditCamera> out{camera};
  // Halton sequence in bases 2, 3, 5: evenly spread offsets in [-jitter, jitter]^3.
  const auto halton = [](int i, int b) {
    double f = 1, r = 0;
    for (; i > 0; i /= b) {
      f /= b;
      r += f * (i % b);
    }
    return r;
  };
  for (int k = 1; k < frames; ++k) {
    AuditCamera c = camera;
    const double d[3] = {jitter * (2 * halton(k, 2) - 1), jitter * (2 * halton(k, 3) - 1),
                         jitter * (2 * halton(k, 5) - 1)};
    for (int i = 0; i < 3; ++i) c.eye[i] += d[i];
    for (int r = 0; r < 3; ++r)
      c.view[r * 4 + 3] -=
          c.view[r * 4] * d[0] + c.view[r * 4 + 1] * d[1] + c.view[r * 4 + 2] * d[2];
    c.description += fmt::format(" moved ({:.4g}, {:.4g}, {:.4g})", d[0], d[1], d[2]);
    out.push_back(c);
  }
  return out;
}

}  // namespace depthprec
