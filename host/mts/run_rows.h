// The rows of an MTS run of a scene, whoever computes them (run_scene, host/mts/mts_run.h, in the
// steps of SceneRun, host/mts/scene_run.h; render_scene, host/render/render_run.h): what a run
// gives (MtsRun) and what it leaves out (RunControl), the rows' keys and order, the kernel
// variants' labels.
#pragma once

#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "host/model/scene.h"
#include "host/mts/mts_row.h"
#include "host/mts/run_info.h"
#include "host/runtime/kernel_variant.h"

namespace depthprec {

struct MtsRun {
  std::vector<MtsRow> rows;  // pair order of the scene, distance order within a pair
  RunInfo info;
};

// What a batch run leaves out and where its rows go as they finish.
struct RunControl {
  std::set<std::string> done;  // row keys (row_key) finished by an earlier run: not recomputed
  int shard_index = 0;         // this run computes the rows k with k % shard_count == shard_index,
  int shard_count = 1;         // k = pair index * distances + distance index (scene order)
  std::function<void(const MtsRow&)> on_row;  // each row as it finishes (journal)
  std::function<bool()> stop;                 // interrupt request, checked between launches
  bool attribute = false;  // also the storage- and arithmetic-limited MTS of every row
  // Pairs evaluated side by side, each by its own host thread and queue: the device's cores stay
  // busy while one pair's launch drains or its host waits. Rows are the same for any number;
  // measured times then include the other pairs' share of the device.
  // The jobs share the plane-A cache's budget; with fewer pairs than jobs a pair's distances are
  // split between them. 2: the default table takes 6.0 s with two jobs against 6.8 s with one,
  // 280-300 MB either way (docs/performance.md).
  int jobs = 2;
};

// The units of an MTS batch (mts, table, render, compare): a row key per (pair, distance), in
// scene order, k = pair index x distances + distance index.
struct SceneRows {
  std::vector<std::string> keys;
  std::map<std::string, size_t> index_of;  // key -> k
};
SceneRows scene_rows(const Scene& scene);
// The control that computes only the rows todo (indices into rows.keys), stopping on stop.
RunControl control_for(const SceneRows& rows, const std::vector<size_t>& todo,
                       const std::function<bool()>& stop);

// The kernel variants the scene needs, in pair order (labels): deterministic, whatever a run
// actually had to build.
std::vector<std::string> scene_variants(const Scene& scene);
// The same from the pairs' variants, one per pair in pair order, for a caller that has made them.
std::vector<std::string> variant_labels(const std::vector<KernelVariant>& pair_variants);

// Rows in scene order (pairs as listed, distances as listed).
void sort_rows(const Scene& scene, std::vector<MtsRow>& rows);

}  // namespace depthprec
