// Worst-case sampling (host/mts/worst_case.h, docs/mts.md "The worst case"): the rounds'
// orientations stay in the rotation cube; the worst case is never below the paper's frames'
// answer; with no rotation to sample it is the paper's answer; and the refined answer agrees with
// one plain search over every orientation the rounds used.
#include "host/mts/worst_case.h"

#include <fmt/format.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <memory>
#include <random>

#include "host/model/frame_setup.h"
#include "host/mts/mts_run.h"
#include "tests/support/mts_fixture.h"

using namespace depthprec;
using namespace depthprec::test;

namespace {

Scene worst_case_scene(const std::vector<std::string>& extra = {}) {
  std::vector<std::string> sets = {
      "kernel=[24,24]",         "viewport=[24,24]",         "frames=12",
      "distances=[2,100,3000]", "worst_case.round_size=16", "worst_case.min_rounds=2",
      "worst_case.max_rounds=4"};
  sets.insert(sets.end(), extra.begin(), extra.end());
  return load_scene("", sets);
}

// Worst-case rows of one pair, and per distance every orientation the answer rests on (the
// paper's frames, then each round's).
struct RefinedRows {
  std::vector<MtsRow> rows;
  std::map<double, std::vector<Angles>> used;
};

RefinedRows refine_rows(const Scene& scene, const EvalPair& pair) {
  RefinedRows out;
  MtsEvaluator paper(runtime(), scene, pair);
  out.rows = search_pair(paper, scene, pair, scene.distances);
  for (double z : scene.distances)
    for (int f = 0; f < scene.frames; ++f) out.used[z].push_back(frame_angles(scene, f));
  // The emulator's evaluators, noting the chunks' orientations (an orientation searched alone is
  // one of its chunk's).
  struct Source : EvaluatorSource<ProbeEvaluator> {
    Source(const Scene& scene, const EvalPair& pair, RefinedRows& out)
        : scene_(scene), pair_(pair), out_(out) {}
    std::unique_ptr<ProbeEvaluator> make(const Scene& s, const Orientations& sampled) override {
      if (s.frames == scene_.worst_case.round_size)
        for (const auto& [z, list] : sampled.at)
          out_.used[z].insert(out_.used[z].end(), list.begin(), list.end());
      return std::make_unique<MtsEvaluator>(runtime(), s, pair_, sampled);
    }
    const Scene& scene_;
    const EvalPair& pair_;
    RefinedRows& out_;
  } source(scene, pair, out);
  refine_worst_case(source, scene, pair, out.rows);
  return out;
}

}  // namespace

TEST_CASE("rounds double, stay in the rotation cube and never repeat an orientation",
          "[worst_case]") {
  const Scene scene = worst_case_scene({"rotation_range_deg=2", "worst_case.round_size=20"});
  const double r = 2 * M_PI / 180;
  std::vector<Angles> all;
  for (int round = 1; round <= 4; ++round) {
    const auto list = round_orientations(scene, round);
    REQUIRE(list.size() == 20u << (round - 1));
    CHECK(list == round_orientations(scene, round));  // deterministic
    for (const Angles& a : list)
      for (double v : a) CHECK(std::abs(v) <= r * (1 + 1e-15));
    if (round == 1)  // the cube's corners first: every axis at its limit
      for (size_t c = 0; c < 8; ++c)
        for (double v : list[c]) CHECK(std::abs(v) == r);
    all.insert(all.end(), list.begin(), list.end());
  }
  std::sort(all.begin(), all.end());
  CHECK(std::adjacent_find(all.begin(), all.end()) == all.end());
  // Each axis is spread over the range as the paper's path spreads it: a sine's share of the
  // points lies in the outer half of the range (|a| > r/2): 2/3 of them.
  size_t outer = 0;
  for (const Angles& a : all) outer += std::abs(a[0]) > r / 2;
  CHECK(static_cast<double>(outer) / static_cast<double>(all.size()) ==
        Approx(2.0 / 3).margin(0.05));
}

TEST_CASE("with no rotation to sample, the worst case is the paper's answer", "[worst_case]") {
  const Scene scene = worst_case_scene({"rotation_range_deg=0"});
  const EvalPair pair{Technique::standard, "unorm24", DepthRange::gl};
  const RefinedRows got = refine_rows(scene, pair);
  for (const MtsRow& r : got.rows) {
    INFO("z = " << r.z);
    REQUIRE(r.verdict() == Verdict::resolved);
    CHECK(r.mts == r.mts_paper);
    CHECK(r.convergence == 0);
    // min_rounds rounds of round_size, then 2 round_size: every row rests on both
    CHECK(r.orientations == static_cast<unsigned>(scene.frames + 3 * scene.worst_case.round_size));
  }
}

TEST_CASE("the refined worst case agrees with one search over every orientation it used",
          "[worst_case]") {
  const Scene scene = worst_case_scene();
  for (const EvalPair& pair : {EvalPair{Technique::standard, "float32", DepthRange::gl},
                               EvalPair{Technique::reversed, "unorm24", DepthRange::zero_to_one}}) {
    const RefinedRows got = refine_rows(scene, pair);
    bool rose = false;
    for (const MtsRow& r : got.rows) {
      INFO(pair.label() << " z = " << r.z);
      REQUIRE(r.verdict() == Verdict::resolved);
      const std::vector<Angles>& used = got.used.at(r.z);
      CHECK(r.orientations == used.size());
      Scene brute = scene;
      brute.frames = static_cast<int>(used.size());
      MtsEvaluator ev(runtime(), brute, pair, Orientations{{{r.z, used}}});
      const MtsRow b = search_pair(ev, brute, pair, {r.z})[0];
      REQUIRE(b.verdict() == Verdict::resolved);
      // Both brackets hold the separation where the union of orientations stops fighting.
      if (!r.non_monotone && !b.non_monotone) {
        CHECK(std::max(r.lo, b.lo) <= std::min(r.hi, b.hi));
      }
      CHECK(r.mts >= r.mts_paper);
      rose |= r.mts > r.mts_paper;
    }
    CHECK(rose);  // the scene leaves the paper's frames something to find
  }
}

TEST_CASE("the paper's frames searched one by one agree with one search over them all",
          "[worst_case]") {
  const Scene scene = worst_case_scene({"frames=24", "distances=[2,30,100,3000,2e5]"});
  int rows = 0, equal = 0;
  for (const EvalPair& pair : {EvalPair{Technique::standard, "float32", DepthRange::gl},
                               EvalPair{Technique::reversed, "unorm24", DepthRange::zero_to_one},
                               EvalPair{Technique::log_fragment, "float32", DepthRange::gl}}) {
    PairSource<ProbeEvaluator, MtsEvaluator> source(runtime(), pair);
    const std::vector<MtsRow> one_by_one =
        search_paper_frames(source, scene, pair, scene.distances);
    MtsEvaluator all(runtime(), scene, pair);
    const std::vector<MtsRow> at_once = search_pair(all, scene, pair, scene.distances);
    for (size_t i = 0; i < at_once.size(); ++i) {
      const MtsRow &a = one_by_one[i], &b = at_once[i];
      INFO(pair.label() << " z = " << a.z);
      REQUIRE(a.verdict() == b.verdict());
      if (a.verdict() != Verdict::resolved) continue;
      ++rows;
      CHECK(a.mts_paper == a.mts);
      CHECK(a.orientations == static_cast<unsigned>(scene.frames));
      // A bracket over every frame, as the one search's: all clean at hi, one fighting at lo.
      const auto at = all.run({{a.z, a.hi}, {a.z, a.lo}});
      CHECK(to_string(at[0].outcome) == std::string("clean"));
      CHECK(to_string(at[1].outcome) == std::string("fight"));
      // Where no frame's fights come back above a clean separation, both searches land on the
      // same point of the bisection's grid: the largest frame's answer.
      equal += a.mts == b.mts;
    }
  }
  INFO(equal << " of " << rows << " rows equal");
  CHECK(rows >= 12);
  CHECK(equal * 3 >= rows * 2);
}

TEST_CASE("a paper frame clipped at the answer leaves the row as the one search does",
          "[worst_case]") {
  // Next to the far plane plane B leaves the depth range in some frames: a probe clipped there is
  // not clean, whichever frame it is in, and no separation is clean over all of them.
  const Scene scene =
      load_scene("", {"kernel=[24,24]", "viewport=[24,24]", "far=1000", "distances=[999, 700]"});
  const EvalPair pair{Technique::standard, "float32", DepthRange::gl};
  Scene paper = scene;
  paper.sampling = Sampling::paper;
  const std::vector<MtsRow> worst = search_sampled(runtime(), scene, pair, scene.distances),
                            one = search_sampled(runtime(), paper, pair, scene.distances);
  for (size_t i = 0; i < worst.size(); ++i) {
    INFO("z = " << worst[i].z);
    CHECK(to_string(worst[i].verdict()) == std::string(to_string(one[i].verdict())));
    if (worst[i].verdict() == Verdict::resolved) CHECK(worst[i].mts >= worst[i].mts_paper);
  }
  const auto next_to_far =
      std::find_if(worst.begin(), worst.end(), [](const MtsRow& r) { return r.z == 999; });
  REQUIRE(next_to_far != worst.end());
  CHECK(next_to_far->verdict() == Verdict::clipped);
}

TEST_CASE("over random scenes the worst case is never below the paper's frames",
          "[worst_case][property]") {
  std::mt19937 rng(20261126);
  auto pick = [&rng](const auto& v) {
    return v[std::uniform_int_distribution<size_t>(0, v.size() - 1)(rng)];
  };
  int resolved = 0;
  for (int k = 0; k < 6; ++k) {
    const double near = pick(std::vector<double>{0.1, 1, 3});
    const std::vector<std::string> sets = {
        fmt::format("kernel=[{0},{0}]", pick(std::vector<int>{12, 20, 32})),
        "viewport=[32,32]",
        fmt::format("frames={}", pick(std::vector<int>{3, 8, 16})),
        fmt::format("near={}", near),
        fmt::format("far={}", pick(std::vector<double>{1e4, 1e9})),
        fmt::format("rotation_range_deg={}", pick(std::vector<double>{0.5, 1, 5, 20})),
        fmt::format("distances=[{},{}]", near * 2, near * pick(std::vector<double>{50, 3000})),
        fmt::format("evaluate=[{{\"technique\":\"{}\",\"format\":\"{}\"}}]",
                    pick(technique_table()).name,
                    pick(std::vector<std::string>{"unorm16", "unorm24", "float32"})),
        "worst_case.round_size=8",
        "worst_case.min_rounds=1",
        "worst_case.max_rounds=3"};
    const Scene scene = load_scene("", sets);
    const MtsRun run = run_scene(runtime(), scene);
    for (const MtsRow& r : run.rows) {
      INFO("scene " << k << " " << r.pair.label() << " z = " << r.z);
      if (r.verdict() != Verdict::resolved) continue;
      ++resolved;
      CHECK(r.mts >= r.mts_paper);
      CHECK(r.orientations >= static_cast<unsigned>(scene.frames + scene.worst_case.round_size));
      CHECK(r.convergence >= 0);
    }
  }
  CHECK(resolved >= 6);
}

TEST_CASE("the evaluator's shortcuts change no probe result over a round's orientations",
          "[worst_case][bounds]") {
  // A chunk is an ordinary scene whose frames take the round's orientations (the cube's corners
  // first, where the planes are steepest): probes from s = z down past the MTS decide the same
  // with the certified shortcuts (code bounds, B's coverage from A's, the gap certificate) and
  // without them, and with plane A's codes cached and without.
  Scene scene = worst_case_scene({"kernel=[48,48]", "viewport=[48,48]", "rotation_range_deg=5"});
  const std::vector<Angles> chunk = round_orientations(scene, 1);
  scene.frames = static_cast<int>(chunk.size());
  std::vector<Probe> probes;
  Orientations sampled;
  for (double z : {1.005, 30.0, 3000.0, 2e6}) {
    sampled.at[z] = chunk;
    for (double f = 1.0; f > 1e-9; f /= 8) probes.push_back({z, z * f});
  }
  for (const EvalPair& pair : {EvalPair{Technique::standard, "unorm24", DepthRange::gl},
                               EvalPair{Technique::reversed, "float32", DepthRange::zero_to_one},
                               EvalPair{Technique::log_fragment, "unorm24", DepthRange::gl}}) {
    // and as a round's chunk, which leaves plane A's codes to mts_raster (log_fragment caches
    // them otherwise): the same probes, the same results
    Orientations as_chunk = sampled;
    as_chunk.chunk = true;
    MtsEvaluator with(runtime(), scene, pair, sampled),
        without(runtime(), scene, pair, sampled, false), chunked(runtime(), scene, pair, as_chunk);
    const auto a = with.run(probes), b = without.run(probes), c = chunked.run(probes);
    int fights = 0;
    for (size_t k = 0; k < probes.size(); ++k) {
      INFO(pair.label() << " z = " << probes[k].z << " s = " << probes[k].s);
      for (const auto* other : {&b, &c}) {
        CHECK(to_string(a[k].outcome) == std::string(to_string((*other)[k].outcome)));
        CHECK(a[k].frames == (*other)[k].frames);
        CHECK(a[k].deciding_frame == (*other)[k].deciding_frame);
        CHECK(a[k].any_uncovered == (*other)[k].any_uncovered);
      }
      CHECK(a[k].fragment_pairs == c[k].fragment_pairs);
      fights += a[k].outcome == Outcome::fight;
    }
    INFO(pair.label());
    CHECK(fights > 0);  // the descent reaches separations that fight
  }
}
