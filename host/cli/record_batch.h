// The run every record batch (lj-table, tradeoff, cost, pipelines) shares: shard and journal
// checked before any device work, the units run with journaling and progress, the output
// written (on an interrupt without a journal, whatever finished is shown), and the journal
// removed once the output is in place.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host/batch/batch.h"
#include "host/cli/commands.h"
#include "host/model/scene.h"
#include "host/runtime/opencl_runtime.h"

namespace depthprec::cli {

using RecordRenderer =
    std::function<std::string(const nlohmann::json& header,
                              const std::vector<nlohmann::json>& records, const OutputOptions&)>;

// The units of a batch with one record per pair of the scene, keyed by the pair's label, in
// scene order: what advise, bias, cost, pipelines and --profiles run.
std::vector<BatchUnit> pair_units(const Scene& scene,
                                  const std::function<nlohmann::json(const EvalPair&)>& record);

// prepare fills the header (batch_header's fields are set already) and lists the units; they may
// keep a reference to the runtime, which lives until the output is written. Returns the records.
std::vector<nlohmann::json> run_record_batch(
    const std::string& kind, const OutputOptions& out, const BatchOptions& batch,
    const GlobalOptions& global,
    const std::function<std::vector<BatchUnit>(OpenClRuntime& rt, nlohmann::json& header)>& prepare,
    const RecordRenderer& render);

}  // namespace depthprec::cli
