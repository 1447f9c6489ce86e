// libFuzzer target: a JSON output as `merge` and `compare --emulated/--rendered` read it (a shard
// of a batch, an mts/table/render output), damaged any way. A document with rows is read as
// merge_rows does -- its scene through scene_from_json, every row through row_from_json -- and
// rendered again as text and JSON; a document with records of `compare` is summarised. Bad input
// must end in depthprec::Error with a message, or in a JSON type error, which both commands report
// as bad input; a crash, a sanitizer report or another exception is a bug. Built and run by
// scripts/fuzz.sh shard; see docs/fuzzing.md.
#include <cstdint>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host/analysis/compare.h"
#include "host/base/errors.h"
#include "host/batch/batch.h"
#include "host/model/scene.h"
#include "host/mts/mts_run.h"
#include "host/mts/row_json.h"
#include "host/output/report.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto doc = nlohmann::json::parse(data, data + size, nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) return 0;  // merge refuses these by name
  try {
    (void)depthprec::Shard::parse(doc.value("shard", std::string()));
    if (doc.contains("rows") && doc.contains("scene")) {
      if (!doc["rows"].is_array()) throw depthprec::InputError("rows is not an array");
      const depthprec::Scene scene = depthprec::scene_from_json(doc["scene"], "fuzz.json");
      std::vector<depthprec::MtsRow> rows;
      for (const auto& r : doc["rows"]) rows.push_back(depthprec::row_from_json(r));
      depthprec::sort_rows(scene, rows);
      depthprec::RunInfo info;
      for (const char* format : {"text", "csv", "json"}) {
        (void)depthprec::render_rows(scene, rows, info, format);
        (void)depthprec::render_table(scene, rows, info, format);
      }
    }
    if (doc.value("kind", "") == "compare" && doc.contains("records") &&
        doc["records"].is_array()) {
      std::vector<nlohmann::json> records = doc["records"];
      (void)depthprec::summary_line(depthprec::summarise(records, 1.0 / 1024));
      (void)depthprec::summarise_by_pair(records, 1.0 / 1024);
    }
  } catch (const depthprec::Error& e) {
    if (std::string(e.what()).empty()) std::abort();  // errors must say something
  } catch (const nlohmann::json::exception&) {
    // A field of the wrong type: merge and compare turn these into input errors (exit 3).
  }
  return 0;
}
