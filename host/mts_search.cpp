#include "host/mts_search.h"

#include <cmath>

#include "host/errors.h"

namespace depthprec {

namespace {
// A bisection halves its bracket each probe: past this many, the bracket is below binary64
// resolution and something else (a bracket that cannot shrink) is going on.
constexpr int kMaxProbes = 2200;
}  // namespace

Bisection::Bisection(double z, double rel_precision, double max_separation_factor)
    : z_(z), rel_(rel_precision), limit_(max_separation_factor * z), next_(z) {}

void Bisection::record(Outcome o) {
  history_.emplace_back(next_, o);
  ++probes_;
  const double s = next_;
  if (o == Outcome::non_finite) non_finite_ = true;
  if (o == Outcome::clipped) clipped_ = true;
  const bool fights = o == Outcome::fight || o == Outcome::non_finite ||
                      (o == Outcome::clipped && resolved());
  if (doubling_) {
    if (fights) {
      lo_ = s;
      next_ = 2 * s;
      if (next_ > limit_) done_ = true;  // unresolvable
      return;
    }
    doubling_ = false;
    if (o == Outcome::clean) hi_ = s;
    else ceil_ = s;  // clipped: too far
  } else if (fights) {
    if (s > hi_) non_monotone_ = true;
    lo_ = s;
  } else if (o == Outcome::clean) {
    if (s < lo_) non_monotone_ = true;
    hi_ = s;
  } else {
    ceil_ = s;
  }
  advance();
}

void Bisection::advance() {
  const double upper = resolved() ? hi_ : ceil_;
  if ((upper - lo_) / upper <= rel_ || probes_ >= kMaxProbes) {
    done_ = true;
    return;
  }
  next_ = 0.5 * (lo_ + upper);
  if (!(next_ > lo_ && next_ < upper)) done_ = true;  // bracket at binary64 resolution
}

std::string MtsRow::flags() const {
  std::string f;
  auto add = [&f](bool on, const char* name) {
    if (on) f += (f.empty() ? "" : ",") + std::string(name);
  };
  add(non_finite, "non_finite");
  add(clipped, "clipped");
  add(unresolvable, "unresolvable");
  add(non_monotone, "non_monotone");
  add(uncovered, "uncovered");
  return f;
}

std::vector<MtsRow> search_pair(MtsEvaluator& evaluator, const Scene& scene, const EvalPair& pair,
                                const std::vector<double>& distances,
                                const std::function<void(const MtsRow&)>& on_row,
                                const std::function<bool()>& stop) {
  std::vector<Bisection> searches;
  std::vector<MtsRow> rows(distances.size());
  for (size_t i = 0; i < distances.size(); ++i) {
    searches.emplace_back(distances[i], scene.rel_precision, scene.max_separation_factor);
    rows[i].pair = pair;
    rows[i].z = distances[i];
    rows[i].vertex_bound = vertex_bound(distances[i]);
  }
  std::vector<bool> reported(distances.size(), false);
  for (;;) {
    if (stop && stop()) throw Error(ExitCode::interrupted, "interrupted");
    std::vector<size_t> active;
    std::vector<Probe> probes;
    for (size_t i = 0; i < searches.size(); ++i) {
      if (searches[i].done()) continue;
      active.push_back(i);
      probes.push_back({distances[i], searches[i].next()});
    }
    if (!active.empty()) {
      const auto results = evaluator.run(probes);
      for (size_t k = 0; k < active.size(); ++k) {
        MtsRow& row = rows[active[k]];
        const ProbeResult& r = results[k];
        row.frames += static_cast<uint64_t>(r.frames);
        row.fragment_pairs += r.fragment_pairs;
        row.seconds += r.seconds;
        row.kernel_seconds += r.kernel_seconds;
        row.launches += r.launches;
        row.uncovered |= r.any_uncovered;
        row.clipped_probes += r.any_clipped ? 1 : 0;
        searches[active[k]].record(r.outcome);
      }
    }
    for (size_t i = 0; i < searches.size(); ++i) {
      if (!searches[i].done() || reported[i]) continue;
      reported[i] = true;
      const Bisection& b = searches[i];
      MtsRow& row = rows[i];
      row.probes = b.probes();
      row.lo = b.lo();
      row.hi = b.hi();
      row.unresolvable = !b.resolved();
      row.mts = b.hi();
      row.mts_seen = b.resolved() ? seen_separation(row.z, b.hi()) : b.hi();
      row.non_finite = b.saw_non_finite();
      row.clipped = !b.resolved() && b.saw_clipped();
      row.non_monotone = b.non_monotone();
      if (on_row) on_row(row);
    }
    if (active.empty()) break;
  }
  return rows;
}

}  // namespace depthprec
