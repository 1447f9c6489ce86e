#include "host/audit/audit_fixes.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <tuple>

#include "host/bias/bias_rule.h"
#include "host/bias/bias_search.h"
#include "host/mts/mts_run.h"
#include "interface/audit_layout.h"
#include "interface/bias_formula.h"

namespace depthprec {

namespace {

// The triangles of `keep`, in their draws, as a scene of their own (draw order kept).
SceneGeometry only(const SceneGeometry& g, const std::vector<uint32_t>& keep) {
  SceneGeometry sub;
  sub.source = g.source;
  for (const Draw& d : g.draws) {
    Draw s = d;
    s.triangles.clear();
    for (size_t t = 0; t < d.triangles.size(); ++t)
      if (std::find(keep.begin(), keep.end(), d.first_triangle + t) != keep.end())
        s.triangles.push_back(d.triangles[t]);
    if (s.triangles.empty()) continue;
    s.first_triangle = static_cast<uint32_t>(sub.triangles);
    sub.triangles += s.triangles.size();
    sub.draws.push_back(std::move(s));
  }
  return sub;
}

// The camera moved by d metres along its view direction (the eye and what it looks at together).
AuditCamera along_view(AuditCamera c, double d) {
  const double back[3] = {c.view[8], c.view[9], c.view[10]};  // the eye looks down -back
  for (int i = 0; i < 3; ++i) c.eye[i] -= d * back[i];
  c.view[11] += d;
  return c;
}

bool any_fight(const AuditPixels& p) {
  return std::any_of(p.flags.begin(), p.flags.end(),
                     [](uint32_t f) { return (f & AUDIT_FIGHT) != 0; });
}

// Whether a fighting pair's sampled pixels still fight under a scene and set-up, in every view
// the pair fought in (each with its own pixels), drawn with only the pair's triangles (sub),
// optionally with the front surface's draw biased and every view moved along its view direction.
class PairCheck {
 public:
  // front_draw: the front surface's draw in sub.
  PairCheck(const SceneGeometry& sub, const std::vector<AuditCamera>& frames, const FightPair& fp,
            size_t front_draw)
      : sub_(sub), frames_(frames), fp_(fp), front_draw_(front_draw) {}

  bool fights(const Scene& scene, const EvalPair& pair) const {
    for (const PixelSample& ps : fp_.samples) {
      const AuditCamera& cam = frames_.at(ps.frame);
      const Scene s = audit_scene(scene, cam);
      if (any_fight(audit_reference_at(s, audit_setup(s, pair, sub_, cam), ps.pixels))) return true;
    }
    return false;
  }
  // With the front draw's triangles offset by `units` of the API's constant bias, each view moved
  // by `move` metres along its view direction.
  bool fights_biased(const Scene& scene, const EvalPair& pair, const BiasRule& rule, int sign,
                     double units, double move) const {
    for (const PixelSample& ps : fp_.samples) {
      const AuditCamera cam = along_view(frames_.at(ps.frame), move);
      const Scene s = audit_scene(scene, cam);
      AuditSetup a = audit_setup(s, pair, sub_, cam);
      const Draw& front = sub_.draws[front_draw_];
      for (size_t r = 0; r < a.records.size(); ++r) {
        if (a.source[r] < front.first_triangle ||
            a.source[r] >= front.first_triangle + front.triangles.size())
          continue;
        const auto& z = a.window_depths[r];
        a.records[r].bias = depth_bias(rule.units_term(sign * units), rule.float_rule ? 1 : 0, 0.0f,
                                       0.0f, 0.0f, z[0], z[1], z[2]);
      }
      if (any_fight(audit_reference_at(s, a, ps.pixels))) return true;
    }
    return false;
  }

 private:
  const SceneGeometry& sub_;
  const std::vector<AuditCamera>& frames_;
  const FightPair& fp_;
  size_t front_draw_;
};

// How far, in eye depth, a constant window-depth offset of `units` moves a surface at eye depths
// [z_lo, z_hi]: the offset r * units over the steepest the technique's map D(w) is there (the least
// movement), with r taken at the depth whose exponent is smallest under the float rule (again the
// least). Zero where the map is flat or unknown.
double bias_eye_shift(const Scene& scene, const EvalPair& pair, const BiasRule& rule, double units,
                      double z_lo, double z_hi) {
  double shift = INFINITY;
  for (const double w : {z_lo, z_hi}) {
    const double h = 1e-6 * w;
    const auto D = [&](double x) {
      return depth_of_distance(pair.technique, scene.near, scene.far, scene.params, x);
    };
    const double slope = std::fabs(D(w + h) - D(w - h)) / (2 * h);
    const double r = rule.float_rule ? std::min(rule.r_at(static_cast<float>(D(z_lo))),
                                                rule.r_at(static_cast<float>(D(z_hi))))
                                     : rule.r_fixed;
    shift = std::min(shift, slope > 0 ? r * units / slope : 0.0);
  }
  return std::isfinite(shift) ? shift : 0.0;
}

// The index in sub of draw d of the whole scene (sub keeps the draws' order, nodes and primitives).
size_t draw_in(const SceneGeometry& sub, const Draw& d) {
  for (size_t k = 0; k < sub.draws.size(); ++k)
    if (sub.draws[k].node_index == d.node_index && sub.draws[k].primitive == d.primitive &&
        sub.draws[k].mesh_index == d.mesh_index)
      return k;
  return 0;
}

}  // namespace

std::vector<EvalPair> default_alternatives(const Scene& scene, const EvalPair& audited) {
  std::vector<EvalPair> out;
  for (Technique t : {Technique::standard, Technique::reversed, Technique::log_threejs})
    for (const char* f : {"unorm24", "float32"}) {
      const EvalPair p{t, f, scene.range_for(t)};
      if (p.label() != audited.label()) out.push_back(p);
    }
  return out;
}

namespace {

// The MTS and the guaranteed MTS of a set-up at eye depth z, in the measurement scene placed where
// the pair is (world_position: the eye of the view it fights in, so the vertex transform's rounding
// far from the origin is the pair's) under the near plane and transform tried; NaN without a
// device (the bound, too: it comes with the row). One search per (set-up, transform, near, z,
// place), kept.
struct MtsAndBound {
  double mts = NAN, bound = NAN;
  // What a fix must clear: the bound, or the sampled MTS where the model has none.
  double needed() const { return std::isnan(bound) ? mts : bound; }
};
class MtsAtPair {
 public:
  MtsAtPair(OpenClRuntime* rt, const Scene& measurement, const FixRequest& req)
      : rt_(rt), measurement_(measurement), req_(req) {}
  MtsAndBound operator()(const EvalPair& p, const Scene& tried, double z,
                         const std::array<double, 3>& at) {
    if (!req_.mts || !rt_) return {};
    const auto key = std::make_tuple(p.label(), tried.pipeline.transform, tried.near, z, at);
    if (!known_.count(key)) {
      Scene m = measurement_;
      m.near = tried.near;
      m.pipeline.transform = tried.pipeline.transform;
      m.evaluate = {p};
      m.distances = {z};
      m.world_position = at;
      MtsAndBound v;
      if (z > tried.near && z < m.far) {
        const MtsRow row = run_scene(*rt_, m, req_.log).rows.at(0);
        v = {row.mts, row.mts_bound};
      }
      known_[key] = v;
    }
    return known_[key];
  }

 private:
  OpenClRuntime* rt_;
  const Scene& measurement_;
  const FixRequest& req_;
  std::map<std::tuple<std::string, Transform, double, double, std::array<double, 3>>, MtsAndBound>
      known_;
};

// The constant bias: the smallest whole number of units (IntegerBiasSearch, as `bias` searches
// it, up to kMaxBiasUnits) that resolves the pixels in every view the pair fought in, each moved
// along its view by up to twice the MTS (so the surfaces' depths cross a few codes, and the
// answer is not one rounding's luck), and that moves the front surface by at least what the MTS
// asks beyond the separation (offset).
void add_bias_fix(const Scene& scene, const EvalPair& pair, const PairCheck& check, FightPair& fp) {
  const std::string not_applicable = bias_not_applicable(scene, pair);
  if (!not_applicable.empty()) {
    fp.bias_note = not_applicable;
    return;
  }
  BiasOptions options;  // OpenGL's rule, with the r of the scene's profile (llvmpipe: 2 steps)
  options.unorm_r = scene_unorm_r(scene);
  const BiasRule rule = bias_rule(options, scene.storage_format(pair));
  const int sign = bias_sign(scene, pair);
  const double span = std::isnan(fp.mts) ? 0.0 : 2 * fp.mts;
  const auto fights = [&](double units) {
    if (!std::isnan(fp.offset) &&
        bias_eye_shift(scene, pair, rule, units, fp.depth_min, fp.depth_max) < fp.offset)
      return true;
    for (int k = 0; k < 8; ++k)
      if (check.fights_biased(scene, pair, rule, sign, units, span * k / 8)) return true;
    return false;
  };
  IntegerBiasSearch search(kMaxBiasUnits);
  while (!search.done()) {
    ProbeResult probe;
    probe.outcome = fights(search.next()) ? Outcome::fight : Outcome::clean;
    search.record(probe);
  }
  const BiasAnswer answer = search.answer();
  if (answer.resolved())
    fp.bias_units = sign * answer.value;
  else
    fp.bias_note = fmt::format("no constant bias up to {} units resolves it", kMaxBiasUnits);
}

}  // namespace

void add_fixes(OpenClRuntime* rt, const Scene& scene, const Scene& measurement,
               const SceneGeometry& g, const std::vector<AuditCamera>& frames, SetupAudit& audit,
               const FixRequest& req) {
  const auto start = std::chrono::steady_clock::now();
  const EvalPair& pair = audit.pair;
  MtsAtPair mts_of(rt, measurement, req);
  for (FightPair& fp : audit.pairs) {
    const double z = std::stod(fmt::format("{:.3g}", fp.depth_median));
    const std::array<double, 3> at =
        fp.samples.empty() ? std::array<double, 3>{} : frames.at(fp.samples[0].frame).eye;
    const MtsAndBound here = mts_of(pair, scene, z, at);
    fp.mts = here.mts;
    fp.mts_bound = here.bound;
    fp.offset = std::isnan(here.needed()) ? NAN : std::max(0.0, here.needed() - fp.separation_min);
    const SceneGeometry sub = only(g, fp.triangles);
    const PairCheck check(sub, frames, fp, draw_in(sub, g.draws[fp.front_draw]));
    if (fp.samples.empty() || !check.fights(scene, pair)) {
      fp.bias_note = "the fight needs surfaces other than the pair's (not reproduced alone)";
      continue;
    }
    // A fix holds when the pair's pixels no longer fight in any view and the pair's smallest
    // separation is at least the guaranteed MTS there (so it holds for every orientation and
    // every implementation of the bound model, not by the luck of one rounding; the sampled MTS
    // where the model has no bound).
    const auto holds = [&](const Scene& s, const EvalPair& p) {
      if (check.fights(s, p)) return false;
      const double needed = mts_of(p, s, z, at).needed();
      return std::isnan(needed) || needed <= fp.separation_min;
    };
    // The nearest near plane: steps of 2^(1/4) out to the pair's nearest depth.
    for (double n = scene.near * 1.189207115002721; n < fp.depth_min / 1.01;
         n *= 1.189207115002721) {
      Scene s = scene;
      s.near = n;
      if (holds(s, pair)) {
        fp.near_plane = n;
        break;
      }
    }
    for (const EvalPair& alt : req.alternatives)
      if (holds(scene, alt)) fp.resolving.push_back(alt.label());
    // The vertex transform: far from the world origin binary32 world matrices lose the positions
    // (docs/spec.md 2, "World position"); camera-relative rendering keeps them.
    if (scene.pipeline.transform == Transform::absolute) {
      Scene relative = scene;
      relative.pipeline.transform = Transform::camera_relative;
      if (holds(relative, pair)) fp.resolving.push_back(pair.label() + "/camera_relative");
    }
    add_bias_fix(scene, pair, check, fp);
  }
  audit.fix_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace depthprec
