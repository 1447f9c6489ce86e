// What every batch command shares so no finished result is lost: the journal of finished rows
// beside the output (FILE.rows.jsonl, one JSON object per line, flushed), --resume from it,
// --shard i/N, and a loop that runs the units of work a command lists, journaling each record
// as it finishes and stopping cleanly on Ctrl-C / SIGTERM.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

namespace depthprec {

// --shard i/N: this run holds the units k with k % count == index (k in the batch's order).
struct Shard {
  int index = 0, count = 1;
  static Shard parse(const std::string& text);  // "" = the whole batch; throws a usage Error
  bool holds(size_t k) const { return static_cast<int>(k % static_cast<size_t>(count)) == index; }
};

class RowJournal {
 public:
  // output "" or a device or pipe (is_stream_output): no journal (then resume is a usage error).
  // The journal is locked (fcntl) while this object lives, so a second run with the same output
  // is refused, naming the process that holds it, rather than told to resume a run still going;
  // the lock goes with the process, however it ends.
  // Without resume, a journal holding finished rows is refused (it holds an interrupted run's
  // rows); with it, its complete lines are read, and a line cut short (a kill, a full disk) is
  // cut off so later rows start on a line of their own. A journal without rows -- empty, its
  // first line torn, or that line alone -- is restarted: nothing in it can be lost.
  // identity: what makes this run's rows what they are (program version, command, scene,
  // options that change a row, shard). A new journal starts with it; a resumed one must start
  // with the same, else it is refused naming the first field that differs -- rows of another
  // scene or version must not be mixed into this run's output.
  RowJournal(const std::string& output, bool resume, const nlohmann::json& identity);
  // Releases the lock; a journal that holds no finished row is removed (a run that failed before
  // its first row leaves nothing behind).
  ~RowJournal();
  RowJournal(const RowJournal&) = delete;
  RowJournal& operator=(const RowJournal&) = delete;
  bool active() const { return fd_ >= 0; }
  const std::string& path() const { return path_; }
  const std::vector<nlohmann::json>& earlier() const { return earlier_; }
  size_t rows() const { return rows_; }  // finished rows in the journal, earlier ones included
  // Throws OutputError when the line cannot be written whole; a part written is cut off again.
  void append(const nlohmann::json& record);
  void remove();  // once the final output is in place

 private:
  void open_locked();
  void read_or_start(bool resume, const nlohmann::json& identity);
  void write_line(const std::string& line);  // whole, or cut back to the last whole line
  std::string path_;
  std::vector<nlohmann::json> earlier_;
  int fd_ = -1;
  size_t rows_ = 0;
  long long size_ = 0;  // bytes of whole lines in the journal
};

// Writes a batch's final output and, once it is in place, removes the journal. When the output
// cannot be written, the error says the finished rows are kept and how to write it from them.
void write_batch_output(RowJournal& journal, const std::string& output, const std::string& text);

// The first place two JSON values differ, as "scene.frames: 10 against 100" ("" when equal).
std::string first_difference(const nlohmann::json& a, const nlohmann::json& b,
                             const std::string& path = "");

// The Error a stopped batch ends with: where the finished rows are and how to continue.
[[noreturn]] void throw_interrupted(const RowJournal& journal, size_t finished);

// One unit of a record batch: its key (unique in the batch, stable across runs) and the work
// that makes its record.
struct BatchUnit {
  std::string key;
  std::function<nlohmann::json()> compute;
};

// The batch loop every batch command runs: keys are the units in batch order (unique, stable
// across runs); compute(todo, emit) computes the units whose indices are in todo -- this shard's,
// not in the journal -- calling emit(index, record) as each finishes (emit journals it, with "key"
// set, and advances the progress line; calls must not overlap), and checks interrupt_requested()
// itself, ending in an Error when it stops. Returns the shard's records in unit order, earlier
// ones included. On an interrupt every finished record is kept: with a journal it throws the
// interrupted Error; without one it calls on_partial(finished records in unit order) first, so
// they are shown. mts and table compute all their units together (run_scene shares launches
// between distances); the record batches go through the overload below, one unit at a time.
using Emit = std::function<void(size_t, nlohmann::json)>;
using BulkCompute = std::function<void(const std::vector<size_t>& todo, const Emit& emit)>;
std::vector<nlohmann::json> run_batch(
    const std::vector<std::string>& keys, const BulkCompute& compute, RowJournal& journal,
    const Shard& shard, const std::string& what, bool progress,
    const std::function<void(const std::vector<nlohmann::json>&)>& on_partial);

// Runs the shard's units not already in the journal, journaling each record (with "key" set)
// as it finishes; returns the shard's records in unit order, earlier ones included. On an
// interrupt request it stops between units: with a journal it throws the interrupted Error;
// without one it calls on_partial(finished records in unit order) first, so they are shown.
std::vector<nlohmann::json> run_batch(
    const std::vector<BatchUnit>& units, RowJournal& journal, const Shard& shard,
    const std::string& what, bool progress,
    const std::function<void(const std::vector<nlohmann::json>&)>& on_partial);

// What a batch's journal is keyed to (RowJournal): its output header without the device (a
// resumed run may run elsewhere) and without measured times.
nlohmann::json journal_identity(const nlohmann::json& header);

// The header of a record batch's JSON output: program, version, kind, device, and the shard.
nlohmann::json batch_header(const std::string& kind, const std::string& device,
                            const std::string& shard);
// header + {"records": ...} + the derived fields (results computed from the records); without
// timing the measured-time fields are left out, so two runs compare byte for byte.
std::string records_json(const nlohmann::json& header, const std::vector<nlohmann::json>& records,
                         bool timing, const nlohmann::json& derived = nlohmann::json::object());
std::map<std::string, nlohmann::json> by_key(const std::vector<nlohmann::json>& records);

}  // namespace depthprec
