// libFuzzer target: a row journal (FILE.rows.jsonl) as --resume reads it, damaged any way a crash,
// a full disk or a user's editor can damage it. The bytes become the journal behind a valid first
// line (or replace it, when the first byte is odd), RowJournal reads them, and every record it
// keeps is read back as an MTS row, as mts/table/render do when they render a resumed run. Bad
// input must end in depthprec::Error with a message; a crash, a sanitizer report or another
// exception is a bug. Built and run by scripts/fuzz.sh journal; see docs/fuzzing.md.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "host/base/errors.h"
#include "host/batch/batch.h"
#include "host/mts/row_json.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string out = "/tmp/depthprec_journal_fuzz_" + std::to_string(getpid());
  const nlohmann::json run = {{"kind", "mts"}, {"scene", {{"frames", 4}}}};
  const std::string body(reinterpret_cast<const char*>(data), size);
  {
    std::ofstream f(out + ".rows.jsonl", std::ios::binary | std::ios::trunc);
    if (size == 0 || data[0] % 2 == 0) f << nlohmann::json{{"journal_of", run}}.dump() << '\n';
    f << body;
  }
  try {
    depthprec::RowJournal journal(out, true, run);
    for (const auto& record : journal.earlier()) {
      const depthprec::MtsRow row = depthprec::row_from_json(record);
      // what a row read back must survive: its key and its JSON again
      (void)depthprec::row_key(row.pair, row.z);
      (void)depthprec::row_to_json(row, true).dump();
    }
  } catch (const depthprec::Error& e) {
    if (std::string(e.what()).empty()) std::abort();  // errors must say something
  }
  std::remove((out + ".rows.jsonl").c_str());
  return 0;
}
