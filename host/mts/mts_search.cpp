#include "host/mts/mts_search.h"

#include <algorithm>
#include <cmath>

#include "host/base/errors.h"
#include "host/model/frame_setup.h"
#include "host/model/resolve.h"
#include "host/model/technique.h"

namespace depthprec {

namespace {
// A bisection halves its bracket each probe: past this many, the bracket is below binary64
// resolution and something else (a bracket that cannot shrink) is going on.
constexpr int kMaxProbes = 2200;
}  // namespace

Bisection::Bisection(double z, double rel_precision, double max_separation_factor,
                     double coincide_below)
    : z_(z),
      rel_(rel_precision),
      limit_(max_separation_factor * z),
      coincide_(coincide_below),
      next_(z) {}

Bisection::Bisection(double z, double rel_precision, double max_separation_factor,
                     double coincide_below, double lo, double hi)
    : Bisection(z, rel_precision, max_separation_factor, coincide_below) {
  lo_ = lo;
  next_ = hi;
}

void Bisection::record(Outcome o) {
  history_.emplace_back(next_, o);
  ++probes_;
  const double s = next_;
  if (o == Outcome::non_finite) non_finite_ = true;
  if (o == Outcome::clipped) clipped_ = true;
  if (o == Outcome::uncovered) uncovered_ = true;
  const bool not_accepted = o == Outcome::clipped || o == Outcome::uncovered;
  const bool fights =
      o == Outcome::fight || o == Outcome::non_finite || (not_accepted && resolved());
  if (doubling_) {
    if (fights) {
      lo_ = s;
      next_ = 2 * s;
      if (next_ > limit_) done_ = true;  // unresolvable
      return;
    }
    doubling_ = false;
    if (o == Outcome::clean)
      hi_ = s;
    else
      ceil_ = s;  // clipped or uncovered: too far
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
  if ((upper - lo_) / upper <= rel_ || probes_ >= kMaxProbes ||
      (!resolved() && upper < coincide_)) {
    done_ = true;
    return;
  }
  next_ = 0.5 * (lo_ + upper);
  if (!(next_ > lo_ && next_ < upper)) done_ = true;  // bracket at binary64 resolution
}

void MtsRow::add_probe_work(const ProbeResult& r) {
  frames += static_cast<uint64_t>(r.frames);
  fragment_pairs += r.fragment_pairs;
  seconds += r.seconds;
  kernel_seconds += r.kernel_seconds;
  uncovered |= r.any_uncovered;
  clipped_probes += r.any_clipped ? 1 : 0;
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
  add(beyond_far, "beyond_far_plane");
  add(before_near, "nearer_than_near_plane");
  add(below_one_code, "below_one_code");
  add(below_world_grid, "below_world_grid");
  return f;
}

void MtsRow::set_dominant(double rel_precision) {
  const double v = vertex_bound * (1 + 2 * rel_precision);
  // unresolvable factors are +inf and dominate
  if (storage_mts <= v && arithmetic_mts <= v)
    dominant = "vertex";
  else
    dominant = storage_mts >= arithmetic_mts ? "storage" : "arithmetic";
}

bool MtsRow::factor_above_mts(double rel_precision) const {
  if (!attributed() || unresolvable) return false;
  const double limit = mts * (1 + 2 * rel_precision);
  return storage_mts > limit || arithmetic_mts > limit;
}

const char* to_string(RowSource s) {
  return s == RowSource::rendered ? "rendered" : "emulated";
}

RowSource parse_row_source(const std::string& s) {
  if (s == "emulated") return RowSource::emulated;
  if (s == "rendered") return RowSource::rendered;
  throw InputError("row source '" + s + "': expected emulated or rendered");
}

const char* to_string(Verdict v) {
  switch (v) {
    case Verdict::resolved:
      return "resolved";
    case Verdict::unresolvable:
      return "unresolvable";
    case Verdict::non_finite:
      return "non_finite";
    case Verdict::clipped:
      return "clipped";
    case Verdict::uncovered:
      return "uncovered";
    case Verdict::below_vertex_bound:
      return "below vertex bound";
    case Verdict::beyond_far_plane:
      return "beyond far plane";
    case Verdict::nearer_than_near_plane:
      return "nearer than near plane";
  }
  return "?";
}

Verdict MtsRow::verdict() const {
  if (beyond_far) return Verdict::beyond_far_plane;
  if (before_near) return Verdict::nearer_than_near_plane;
  if (!unresolvable) {
    // B within the vertex bound coincides with A and must fight: a clean answer there is no
    // measurement (e.g. planes that cover no kernel pixel), never a confident number.
    return mts < vertex_bound ? Verdict::below_vertex_bound : Verdict::resolved;
  }
  if (non_finite) return Verdict::non_finite;
  if (clipped) return Verdict::clipped;
  if (uncovered) return Verdict::uncovered;
  return Verdict::unresolvable;
}

void note_outcome(MtsRow& row, double s, Outcome o) {
  if (o == Outcome::fight || o == Outcome::non_finite) row.fight_max = std::max(row.fight_max, s);
  if (o == Outcome::clean) row.clean_min = std::min(row.clean_min, s);
  if (o == Outcome::non_finite) row.non_finite = true;
}

void take_monotone_bracket(MtsRow& row) {
  if (!(row.fight_max > row.clean_min)) return;
  row.non_monotone = true;
  row.monotone_clean = row.clean_min;
  row.monotone_fight = row.fight_max;
}

std::vector<double> stiffness_separations(double lo, double hi, double r, int n) {
  std::vector<double> out;
  double step = r;
  for (int k = 0; k < n; ++k, step *= 8) {
    out.push_back(hi * (1 + step));
    if (lo > 0) out.push_back(lo * (1 - std::min(step, 0.5)));
  }
  return out;
}

namespace {

// A row's fields from its finished search and its stiffness probes' outcomes (extra); a row not
// searched (plane A beyond the far plane or before the near plane) unresolvable.
void finish_row(const Scene& scene, const EvalPair& pair, const Bisection& b,
                const std::vector<std::pair<double, Outcome>>& extra, MtsRow& row) {
  if (!row.beyond_far && !row.before_near) {
    row.probes = b.probes() + static_cast<int>(extra.size());
    row.lo = b.lo();
    row.hi = b.hi();
    row.unresolvable = !b.resolved();
    row.mts = b.hi();
    row.mts_seen = b.resolved() ? seen_separation(row.z, b.hi()) : b.hi();
    row.non_finite = b.saw_non_finite();
    row.clipped = !b.resolved() && b.saw_clipped();
    if (b.resolved()) {
      const double width = code_interval_width(
          mapping_at(pair.technique, scene.near, scene.far, scene.params, row.z),
          scene.storage_format(pair), row.z);
      row.below_one_code = row.mts_seen < width * (1 - 2 * scene.rel_precision);
      if (row.below_one_code) row.code_width = width;
    }
    for (const auto& [s, o] : b.history()) note_outcome(row, s, o);
    for (const auto& [s, o] : extra) note_outcome(row, s, o);
    row.non_monotone = b.non_monotone();
    take_monotone_bracket(row);
    row.orientations = static_cast<uint64_t>(scene.frames);
  } else {
    row.unresolvable = true;
    row.mts = row.hi = row.mts_seen = std::numeric_limits<double>::infinity();
  }
  row.mts_paper = row.mts;
}

}  // namespace

std::vector<MtsRow> search_pair(ProbeEvaluator& evaluator, const Scene& scene, const EvalPair& pair,
                                const std::vector<double>& distances,
                                const std::function<void(const MtsRow&)>& on_row,
                                const std::function<bool()>& stop,
                                const std::vector<SearchStart>& starts) {
  std::vector<Bisection> searches;
  if (!starts.empty() && starts.size() != distances.size())
    throw Error(ExitCode::internal, "search_pair: one start per distance, or none");
  std::vector<MtsRow> rows(distances.size());
  // Per distance: 0 bisecting, 1 stiffness probes to run, 2 finished.
  std::vector<int> phase(distances.size(), 0);
  std::vector<std::vector<std::pair<double, Outcome>>> extra(distances.size());
  for (size_t i = 0; i < distances.size(); ++i) {
    rows[i].pair = pair;
    rows[i].source = evaluator.source();
    if (rows[i].source == RowSource::emulated)
      rows[i].profile = scene.json["pipeline"].value("profile", "custom");
    rows[i].z = distances[i];
    rows[i].vertex_bound = vertex_bound(distances[i]);
    if (starts.empty())
      searches.emplace_back(distances[i], scene.rel_precision, scene.max_separation_factor,
                            rows[i].vertex_bound);
    else
      searches.emplace_back(distances[i], scene.rel_precision, scene.max_separation_factor,
                            rows[i].vertex_bound, starts[i].lo, starts[i].hi);
    if (has_far_plane(pair.technique) && distances[i] > scene.far) {
      rows[i].beyond_far = true;  // plane A itself is clipped: nothing to search
      phase[i] = 2;
    } else if (info(pair.technique).clips_near && distances[i] < scene.near) {
      rows[i].before_near = true;  // likewise
      phase[i] = 2;
    }
  }
  auto finish = [&](size_t i) {
    finish_row(scene, pair, searches[i], extra[i], rows[i]);
    if (on_row) on_row(rows[i]);
  };
  for (size_t i = 0; i < distances.size(); ++i)
    if (phase[i] == 2) finish(i);
  const size_t window = std::max<size_t>(1, evaluator.distances_at_once());
  for (;;) {
    if (stop && stop()) throw Error(ExitCode::interrupted, "interrupted");
    std::vector<std::pair<size_t, bool>> owner;  // (distance, is a stiffness probe)
    std::vector<Probe> probes;
    // The first `window` unfinished distances, in order: a distance joins as one finishes. Each
    // distance's probe sequence is its own, so the window changes rounds, not rows.
    size_t in_flight = 0;
    for (size_t i = 0; i < searches.size(); ++i) {
      if (phase[i] != 2 && in_flight++ == window) break;
      if (phase[i] == 0) {
        owner.push_back({i, false});
        probes.push_back({distances[i], searches[i].next()});
      } else if (phase[i] == 1) {
        for (double s : stiffness_separations(searches[i].lo(), searches[i].hi(),
                                              scene.rel_precision, scene.stiffness_probes)) {
          owner.push_back({i, true});
          probes.push_back({distances[i], s});
        }
      }
    }
    if (probes.empty()) break;
    const auto results = evaluator.run(probes);
    // A launch renders every probe in it: a row whose probes (stiffness probes, several at once)
    // shared this round's launches took part in as many as its busiest probe, not their sum, so
    // a row never counts more launches than the run made.
    std::vector<uint64_t> round_launches(rows.size(), 0);
    for (size_t k = 0; k < probes.size(); ++k)
      round_launches[owner[k].first] =
          std::max(round_launches[owner[k].first], results[k].launches);
    for (size_t i = 0; i < rows.size(); ++i) rows[i].launches += round_launches[i];
    for (size_t k = 0; k < probes.size(); ++k) {
      const size_t i = owner[k].first;
      MtsRow& row = rows[i];
      const ProbeResult& r = results[k];
      row.add_probe_work(r);
      const Outcome o = search_outcome(r);
      if (owner[k].second)
        extra[i].emplace_back(probes[k].s, o);
      else
        searches[i].record(o);
    }
    for (size_t i = 0; i < searches.size(); ++i) {
      if (phase[i] == 1) {
        phase[i] = 2;
        finish(i);
      } else if (phase[i] == 0 && searches[i].done()) {
        // A continued search that stayed in its bracket probed nothing new near it.
        const bool rose = starts.empty() || searches[i].lo() > starts[i].lo;
        const bool stiff = searches[i].resolved() && scene.stiffness_probes > 0 && rose;
        phase[i] = stiff ? 1 : 2;
        if (!stiff) finish(i);
      }
    }
  }
  return rows;
}

}  // namespace depthprec
