#include "host/cli/record_batch.h"

#include "host/output/progress.h"
#include "host/output/report.h"
#include "host/output/text_table.h"

namespace depthprec::cli {

std::vector<BatchUnit> pair_units(const Scene& scene,
                                  const std::function<nlohmann::json(const EvalPair&)>& record) {
  std::vector<BatchUnit> units;
  for (const EvalPair& pair : scene.evaluate)
    units.push_back({pair.label(), [record, pair] { return record(pair); }});
  return units;
}

std::vector<nlohmann::json> run_record_batch(
    const std::string& kind, const OutputOptions& out, const BatchOptions& batch,
    const GlobalOptions& global,
    const std::function<std::vector<BatchUnit>(OpenClRuntime& rt, nlohmann::json& header)>& prepare,
    const RecordRenderer& render) {
  const Shard shard = Shard::parse(batch.shard);
  if (batch.resume && out.output.empty()) RowJournal(out.output, true, {});  // the usage error
  OpenClRuntime rt(global.device);
  nlohmann::json header = batch_header(kind, rt.description(), batch.shard);
  const std::vector<BatchUnit> units = prepare(rt, header);
  RowJournal journal(out.output, batch.resume, journal_identity(header));
  const auto records =
      run_batch(units, journal, shard, kind, !global.quiet && stderr_is_terminal(),
                [&](const std::vector<nlohmann::json>& done) {
                  write_output("", for_terminal(render(header, done, out), out.format_out));
                });
  write_batch_output(journal, out.output,
                     for_terminal(render(header, records, out), out.format_out));
  return records;
}

}  // namespace depthprec::cli
