#include "host/analysis/profiles.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "host/base/json_number.h"
#include "host/mts/mts_run.h"

namespace depthprec {

nlohmann::json profiles_record(OpenClRuntime& rt, const std::vector<ProfiledScene>& scenes,
                               const EvalPair& pair) {
  nlohmann::json rec = pair.fields();
  const std::vector<double>& zs = scenes.front().scene.distances;
  std::vector<nlohmann::json> rows(zs.size());
  std::vector<double> lo(zs.size(), std::numeric_limits<double>::infinity()), hi(zs.size(), 0);
  std::vector<bool> all_resolved(zs.size(), true);
  for (size_t k = 0; k < zs.size(); ++k) rows[k] = {{"z", zs[k]}};
  for (const ProfiledScene& ps : scenes) {
    Scene one = ps.scene;
    one.evaluate = {pair};
    for (const MtsRow& r : run_scene(rt, one).rows) {
      const size_t k = static_cast<size_t>(std::find(zs.begin(), zs.end(), r.z) - zs.begin());
      const bool resolved = r.verdict() == Verdict::resolved;
      rows[k]["mts"][ps.profile] = resolved ? json_number(r.mts) : nlohmann::json(nullptr);
      rows[k]["verdict"][ps.profile] = to_string(r.verdict());
      if (resolved) {
        lo[k] = std::min(lo[k], r.mts);
        hi[k] = std::max(hi[k], r.mts);
      } else {
        all_resolved[k] = false;
      }
    }
  }
  for (size_t k = 0; k < zs.size(); ++k)
    rows[k]["spread"] = all_resolved[k] ? nlohmann::json(hi[k] / lo[k]) : nlohmann::json(nullptr);
  rec["rows"] = rows;
  return rec;
}

}  // namespace depthprec
