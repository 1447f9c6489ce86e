#include "host/mts/run_rows.h"

#include <algorithm>
#include <map>
#include <set>

#include "host/mts/row_json.h"
#include "host/runtime/kernel_variant.h"

namespace depthprec {

std::vector<std::string> scene_variants(const Scene& scene) {
  std::vector<KernelVariant> pair_variants;
  for (const auto& pair : scene.evaluate) pair_variants.push_back(mts_variant(scene, pair));
  return variant_labels(pair_variants);
}

std::vector<std::string> variant_labels(const std::vector<KernelVariant>& pair_variants) {
  std::vector<std::string> out;
  std::set<std::string> seen;
  for (const KernelVariant& v : pair_variants)
    if (seen.insert(v.label).second) out.push_back(v.label);
  return out;
}

SceneRows scene_rows(const Scene& scene) {
  SceneRows out;
  for (const auto& pair : scene.evaluate)
    for (double z : scene.distances) {
      out.index_of[row_key(pair, z)] = out.keys.size();
      out.keys.push_back(row_key(pair, z));
    }
  return out;
}

RunControl control_for(const SceneRows& rows, const std::vector<size_t>& todo,
                       const std::function<bool()>& stop) {
  RunControl control;
  const std::set<size_t> wanted(todo.begin(), todo.end());
  for (size_t k = 0; k < rows.keys.size(); ++k)
    if (!wanted.count(k)) control.done.insert(rows.keys[k]);
  control.stop = stop;
  return control;
}

void sort_rows(const Scene& scene, std::vector<MtsRow>& rows) {
  std::map<std::string, size_t> order;
  size_t k = 0;
  for (const auto& pair : scene.evaluate)
    for (double z : scene.distances) order.emplace(row_key(pair, z), k++);
  std::stable_sort(rows.begin(), rows.end(), [&order](const MtsRow& a, const MtsRow& b) {
    return order[row_key(a.pair, a.z)] < order[row_key(b.pair, b.z)];
  });
}

}  // namespace depthprec
