#include "host/output/bound_table.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "host/output/text_table.h"

namespace depthprec {

std::string bound_cell(const MtsRow& r, bool full) {
  if (std::isnan(r.mts_bound)) return full ? "" : "-";
  return full ? exact(r.mts_bound) : human(r.mts_bound);
}

namespace {

// The scene's pair labels, each once, in scene order, and its rows by (z, label).
std::vector<std::string> pair_labels(const Scene& scene) {
  std::vector<std::string> labels;
  for (const auto& p : scene.evaluate)
    if (std::find(labels.begin(), labels.end(), p.label()) == labels.end())
      labels.push_back(p.label());
  return labels;
}

std::map<std::pair<double, std::string>, const MtsRow*> rows_at(const std::vector<MtsRow>& rows) {
  std::map<std::pair<double, std::string>, const MtsRow*> at;
  for (const auto& r : rows) at[{r.z, r.pair.label()}] = &r;
  return at;
}

}  // namespace

std::vector<std::string> rows_without_bound(const Scene& scene, const std::vector<MtsRow>& rows) {
  const std::vector<std::string> labels = pair_labels(scene);
  const auto at = rows_at(rows);
  std::map<std::string, std::vector<std::string>> without;  // why -> "pair at z", by z
  for (double z : scene.distances_ascending())
    for (const auto& l : labels) {
      const auto it = at.find({z, l});
      if (it != at.end() && it->second->verdict() == Verdict::resolved &&
          !std::isfinite(it->second->mts_bound))
        without[it->second->bound_note].push_back(fmt::format("{} at {}", l, human(z)));
    }
  std::vector<std::string> out;
  for (const auto& [why, where] : without)
    out.push_back(where.size() == 1
                      ? fmt::format("no finite bound ({}): 1 row, {}", why, where.front())
                      : fmt::format("no finite bound ({}): {} rows, {} to {}", why, where.size(),
                                    where.front(), where.back()));
  return out;
}

std::string bound_grid(const Scene& scene, const std::vector<MtsRow>& rows, bool md) {
  const std::vector<std::string> labels = pair_labels(scene);
  const auto at = rows_at(rows);
  std::vector<Column> cols = {{"z"}};
  for (const auto& l : labels) cols.push_back({l});
  Cells cells;
  for (double z : scene.distances_ascending()) {
    std::vector<std::string> c = {human(z)};
    for (const auto& l : labels) {
      const auto it = at.find({z, l});
      c.push_back(it == at.end() ? "" : bound_cell(*it->second, false));
    }
    cells.push_back(c);
  }
  std::string out = md ? "\n" : "\n";
  out += fmt::format(
      "Guaranteed MTS (mts_bound, model {}): no pixel fights at or above it in any orientation "
      "within the rotation cube under any implementation of the model (docs/bound.md); - = no "
      "finite bound (why: under the grid) or no MTS to bound\n\n",
      scene.bound_model);
  out += grid(cols, cells, md);
  for (const std::string& line : rows_without_bound(scene, rows))
    out += (md ? "\n" : "") + line + "\n";
  return out;
}

}  // namespace depthprec
