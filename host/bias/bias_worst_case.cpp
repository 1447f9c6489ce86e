#include "host/bias/bias_worst_case.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "host/mts/refinement.h"

namespace depthprec {

namespace {

constexpr unsigned kKinds[] = {kBiasUnits, kBiasFactor, kBiasWithFactor};

// Depth bias under refinement: an item is a distance, a slot one of its answers (distance * 3 +
// the kind's index in kKinds); a probe at an answer fails when the decal does not pass, and the
// failing orientation is searched alone for that kind, the answer becoming the larger of the two.
class BiasRefinement : public Refinement<BiasEvaluator> {
 public:
  BiasRefinement(const Scene& scene, const EvalPair& pair, const BiasOptions& options,
                 const std::vector<double>& distances, std::vector<BiasAnswers>& answers)
      : scene_(scene), pair_(pair), options_(options), distances_(distances), answers_(answers) {}

  std::vector<size_t> slots(const std::vector<size_t>& open) const override {
    std::vector<size_t> out;  // the resolved answers of the open distances
    for (const size_t k : open)
      for (size_t i = 0; i < 3; ++i)
        if (answer(k * 3 + i).resolved() && !std::isnan(answer(k * 3 + i).value))
          out.push_back(k * 3 + i);
    return out;
  }
  double z(size_t slot) const override { return distances_[slot / 3]; }
  std::vector<ProbeResult> probe(BiasEvaluator& ev, const std::vector<size_t>& slots) override {
    std::vector<BiasProbe> probes;
    for (const size_t s : slots)
      probes.push_back(bias_probe(scene_, pair_, options_, kind(s), z(s), answer(s).value));
    std::vector<ProbeResult> results = ev.run(probes);
    for (size_t k = 0; k < slots.size(); ++k) {
      ++answer(slots[k]).probes;
      answers_[slots[k] / 3].seconds += results[k].seconds;
    }
    return results;
  }
  bool fails(size_t, const ProbeResult& r) const override { return !bias_passes(r); }
  // Each kind alone: a distance's answers can fail in different orientations.
  int groups() const override { return 3; }
  int group(size_t slot) const override { return static_cast<int>(slot % 3); }
  std::vector<bool> search(BiasEvaluator& single, const Scene& one,
                           const std::vector<size_t>& slots) override {
    std::vector<double> zs;
    for (const size_t s : slots) zs.push_back(z(s));
    const unsigned k = kind(slots.front());  // one group: one kind
    std::vector<BiasAnswers> alone = search_bias(single, one, pair_, options_, zs, k);
    std::vector<bool> rose;
    for (size_t i = 0; i < slots.size(); ++i) {
      BiasAnswer& current = answer(slots[i]);
      const BiasAnswer& found = alone[i].of(k);
      answers_[slots[i] / 3].seconds += alone[i].seconds;
      current.probes += found.probes;
      rose.push_back(false);
      if (!found.resolved()) {  // more than the search's limit, or not measurable there
        current = BiasAnswer{found.verdict};
        current.probes += found.probes;
        continue;
      }
      if (!(found.value > current.value)) continue;
      current.value = found.value;
      current.next_down = found.next_down;
      rose.back() = true;  // probe the chunk again with the larger answer
    }
    return rose;
  }
  void chunk_done(const std::vector<size_t>& open, const std::vector<size_t>&, size_t n) override {
    for (const size_t k : open) answers_[k].orientations += n;
  }
  void round_begin(const std::vector<size_t>& open) override {
    before_.clear();
    for (const size_t k : open) before_.push_back(answers_[k]);
  }
  std::vector<size_t> round_end(int round, const std::vector<size_t>& open) override {
    std::vector<size_t> still;
    for (size_t i = 0; i < open.size(); ++i) {
      BiasAnswers& a = answers_[open[i]];
      double rise = 0;  // the largest relative rise of the three answers in this round
      for (const unsigned kind : kKinds) {
        const double was = before_[i].of(kind).value, now = a.of(kind).value;
        if (was > 0 && now > was) rise = std::max(rise, (now - was) / was);
        if (was == 0 && now > 0) rise = INFINITY;  // no bias needed became some
      }
      a.convergence = rise;
      if (round < scene_.worst_case.min_rounds || rise > scene_.worst_case.tolerance)
        still.push_back(open[i]);
    }
    return still;
  }

 private:
  static unsigned kind(size_t slot) { return kKinds[slot % 3]; }
  BiasAnswer& answer(size_t slot) const { return answers_[slot / 3].of(kind(slot)); }

  const Scene& scene_;
  const EvalPair& pair_;
  const BiasOptions& options_;
  const std::vector<double>& distances_;
  std::vector<BiasAnswers>& answers_;
  std::vector<BiasAnswers> before_;
};

}  // namespace

void refine_bias_worst_case(EvaluatorSource<BiasEvaluator>& source, const Scene& scene,
                            const EvalPair& pair, const BiasOptions& options,
                            const std::vector<double>& distances,
                            std::vector<BiasAnswers>& answers) {
  std::vector<size_t> open;
  for (size_t k = 0; k < distances.size(); ++k) open.push_back(k);
  BiasRefinement refinement(scene, pair, options, distances, answers);
  refine_rounds<BiasEvaluator>(refinement, source, scene, std::move(open));
}

std::vector<BiasAnswers> search_bias_sampled(EvaluatorSource<BiasEvaluator>& source,
                                             const Scene& scene, const EvalPair& pair,
                                             const BiasOptions& options,
                                             const std::vector<double>& distances) {
  std::vector<BiasAnswers> answers;
  {
    const std::unique_ptr<BiasEvaluator> ev = source.make(scene, {});
    answers = search_bias(*ev, scene, pair, options, distances);
    source.retire(*ev);
  }
  // Under worst-case sampling the answers hold in every orientation sampled, as the MTS does.
  if (scene.sampling == Sampling::worst_case)
    refine_bias_worst_case(source, scene, pair, options, distances, answers);
  return answers;
}

}  // namespace depthprec
