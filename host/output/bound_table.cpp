#include "host/output/bound_table.h"

#include <fmt/format.h>

#include <cmath>
#include <map>

#include "host/output/text_table.h"

namespace depthprec {

std::string bound_cell(const MtsRow& r, bool full) {
  if (std::isnan(r.mts_bound)) return full ? "" : "-";
  return full ? exact(r.mts_bound) : human(r.mts_bound);
}

std::string bound_grid(const Scene& scene, const std::vector<MtsRow>& rows, bool md) {
  std::vector<std::string> labels;
  std::map<std::string, size_t> col_of;
  for (const auto& p : scene.evaluate)
    if (col_of.emplace(p.label(), labels.size()).second) labels.push_back(p.label());
  std::map<std::pair<double, std::string>, const MtsRow*> at;
  for (const auto& r : rows) at[{r.z, r.pair.label()}] = &r;
  std::vector<Column> cols = {{"z"}};
  for (const auto& l : labels) cols.push_back({l});
  Cells cells;
  std::map<std::string, std::vector<std::string>> without;  // why -> "pair at z"
  for (double z : scene.distances) {
    std::vector<std::string> c = {human(z)};
    for (const auto& l : labels) {
      const auto it = at.find({z, l});
      if (it == at.end()) {
        c.push_back("");
        continue;
      }
      const MtsRow& r = *it->second;
      c.push_back(bound_cell(r, false));
      if (r.verdict() == Verdict::resolved && !std::isfinite(r.mts_bound))
        without[r.bound_note].push_back(fmt::format("{} at {}", l, human(z)));
    }
    cells.push_back(c);
  }
  std::string out = md ? "\n" : "\n";
  out += fmt::format(
      "Guaranteed MTS (mts_bound, model {}): no pixel fights at or above it in any orientation "
      "within the rotation cube under any implementation of the model (docs/mts.md, \"The "
      "guaranteed bound\"); - = no MTS to bound\n\n",
      scene.bound_model);
  out += grid(cols, cells, md);
  for (const auto& [why, where] : without) {
    out += md ? "\n" : "";
    out += fmt::format("no finite bound ({}): {} rows, {} to {}\n", why, where.size(),
                       where.front(), where.back());
  }
  return out;
}

}  // namespace depthprec
