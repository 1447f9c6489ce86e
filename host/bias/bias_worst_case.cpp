#include "host/bias/bias_worst_case.h"

#include <algorithm>
#include <cmath>

#include "host/mts/worst_case.h"

namespace depthprec {

namespace {

constexpr unsigned kKinds[] = {kBiasUnits, kBiasFactor, kBiasWithFactor};

// One answer of one distance.
struct Slot {
  size_t distance;
  unsigned kind;
};

// Probes the slots' answers over one chunk of orientations until each passes there: where one
// fails, the failing orientation alone is searched and the answer raised to what it needs.
void refine_chunk(const WithBiasEvaluator& with_evaluator, const Scene& scene, const EvalPair& pair,
                  const BiasOptions& options, const std::vector<double>& distances,
                  const std::vector<Angles>& part, std::vector<BiasAnswers>& answers,
                  const std::vector<Slot>& slots) {
  Scene chunk = scene;
  chunk.frames = static_cast<int>(part.size());
  Orientations sampled;
  for (const Slot& s : slots) sampled.at[distances[s.distance]] = part;
  with_evaluator(chunk, sampled, [&](BiasEvaluator& ev) {
    std::vector<Slot> pending = slots;
    while (!pending.empty()) {
      std::vector<BiasProbe> probes;
      for (const Slot& s : pending)
        probes.push_back(bias_probe(scene, pair, options, s.kind, distances[s.distance],
                                    answers[s.distance].of(s.kind).value));
      const std::vector<ProbeResult> results = ev.run(probes);
      std::vector<Slot> raised;
      // Each kind alone: a distance's answers can fail in different orientations.
      for (const unsigned kind : kKinds) {
        Scene one = scene;
        one.frames = 1;
        Orientations one_orientation;
        std::vector<Slot> failed;
        std::vector<double> zs;
        for (size_t k = 0; k < pending.size(); ++k) {
          BiasAnswers& a = answers[pending[k].distance];
          if (pending[k].kind != kind) continue;
          ++a.of(kind).probes;
          a.seconds += results[k].seconds;
          if (bias_passes(results[k]) || results[k].deciding_frame < 0) continue;
          failed.push_back(pending[k]);
          zs.push_back(distances[pending[k].distance]);
          one_orientation.at[zs.back()] = {part[static_cast<size_t>(results[k].deciding_frame)]};
        }
        if (failed.empty()) continue;
        std::vector<BiasAnswers> alone;
        with_evaluator(one, one_orientation, [&](BiasEvaluator& single) {
          alone = search_bias(single, one, pair, options, zs, kind);
        });
        for (size_t k = 0; k < failed.size(); ++k) {
          BiasAnswers& a = answers[failed[k].distance];
          BiasAnswer& current = a.of(kind);
          const BiasAnswer& found = alone[k].of(kind);
          a.seconds += alone[k].seconds;
          current.probes += found.probes;
          if (!found.resolved()) {  // more than the search's limit, or not measurable there
            current = BiasAnswer{found.verdict};
            current.probes += found.probes;
            continue;
          }
          if (!(found.value > current.value)) continue;
          current.value = found.value;
          current.next_down = found.next_down;
          raised.push_back(failed[k]);  // probe the chunk again with the larger answer
        }
      }
      pending = std::move(raised);
    }
  });
}

}  // namespace

void refine_bias_worst_case(const WithBiasEvaluator& with_evaluator, const Scene& scene,
                            const EvalPair& pair, const BiasOptions& options,
                            const std::vector<double>& distances,
                            std::vector<BiasAnswers>& answers) {
  std::vector<size_t> open;
  for (size_t k = 0; k < distances.size(); ++k) open.push_back(k);
  for (int round = 1; round <= scene.worst_case.max_rounds && !open.empty(); ++round) {
    std::vector<BiasAnswers> before;
    for (const size_t k : open) before.push_back(answers[k]);
    for (const std::vector<Angles>& part : round_chunks(scene, round)) {
      std::vector<Slot> slots;  // the resolved answers of the open distances
      for (const size_t k : open)
        for (const unsigned kind : kKinds)
          if (answers[k].of(kind).resolved() && !std::isnan(answers[k].of(kind).value))
            slots.push_back({k, kind});
      if (!slots.empty())
        refine_chunk(with_evaluator, scene, pair, options, distances, part, answers, slots);
      for (const size_t k : open) answers[k].orientations += part.size();
    }
    std::vector<size_t> still;
    for (size_t i = 0; i < open.size(); ++i) {
      BiasAnswers& a = answers[open[i]];
      double rise = 0;  // the largest relative rise of the three answers in this round
      for (const unsigned kind : kKinds) {
        const double was = before[i].of(kind).value, now = a.of(kind).value;
        if (was > 0 && now > was) rise = std::max(rise, (now - was) / was);
        if (was == 0 && now > 0) rise = INFINITY;  // no bias needed became some
      }
      a.convergence = rise;
      if (round < scene.worst_case.min_rounds || rise > scene.worst_case.tolerance)
        still.push_back(open[i]);
    }
    open = std::move(still);
  }
}

}  // namespace depthprec
