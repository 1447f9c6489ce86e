#include "host/batch/batch.h"

#include <fmt/format.h>

#include <cstdio>
#include <map>

#include "host/base/errors.h"
#include "host/base/interrupt.h"
#include "host/base/version.h"
#include "host/output/json_header.h"
#include "host/output/progress.h"
#include "host/output/report.h"

namespace depthprec {

Shard Shard::parse(const std::string& text) {
  Shard s;
  if (text.empty()) return s;
  int i = 0, n = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%d/%d%c", &i, &n, &tail) != 2 || n < 1 || i < 1 || i > n)
    throw Error(ExitCode::usage,
                fmt::format("--shard '{}': expected i/N with 1 <= i <= N, e.g. 2/8", text));
  s.index = i - 1;
  s.count = n;
  return s;
}

std::string first_difference(const nlohmann::json& a, const nlohmann::json& b,
                             const std::string& path) {
  if (a.is_object() && b.is_object()) {
    for (const auto& [k, v] : a.items()) {
      const std::string at = path.empty() ? k : path + "." + k;
      if (!b.contains(k)) return fmt::format("{}: {} against nothing", at, v.dump());
      const std::string d = first_difference(v, b.at(k), at);
      if (!d.empty()) return d;
    }
    for (const auto& [k, v] : b.items())
      if (!a.contains(k))
        return fmt::format("{}: nothing against {}", path.empty() ? k : path + "." + k, v.dump());
    return "";
  }
  if (a == b) return "";
  return fmt::format("{}: {} against {}", path.empty() ? "(the whole value)" : path, a.dump(),
                     b.dump());
}

RowJournal::RowJournal(const std::string& output, bool resume, const nlohmann::json& identity) {
  if (output.empty() || is_stream_output(output)) {
    if (resume)
      throw Error(ExitCode::usage,
                  "--resume needs --output FILE, a regular file: the journal of finished rows "
                  "lives beside it");
    return;
  }
  path_ = output + ".rows.jsonl";
  std::ifstream in(path_);
  const bool fresh_journal = !in.good();
  if (in.good() && !resume)
    throw Error(ExitCode::output,
                fmt::format("{} holds the finished rows of an interrupted run: continue it "
                            "with --resume, or delete it to start over",
                            path_));
  std::string line;
  int number = 0;
  if (resume && in.good()) {
    // The first line says which run wrote the journal.
    ++number;
    const auto head =
        std::getline(in, line) ? nlohmann::json::parse(line, nullptr, false) : nlohmann::json();
    if (!head.is_object() || !head.contains("journal_of"))
      throw InputError(fmt::format(
          "{}: not a journal this depthprec wrote (its first line does not say which run it "
          "belongs to); delete it to start over",
          path_));
    const std::string diff = first_difference(head["journal_of"], identity);
    if (!diff.empty())
      throw InputError(fmt::format(
          "{} was written by another run ({}: the journal's value, then this run's); run the "
          "same command to resume it, or delete it to start over",
          path_, diff));
  }
  while (resume && std::getline(in, line)) {
    ++number;
    if (line.empty()) continue;
    auto j = nlohmann::json::parse(line, nullptr, false);
    if (j.is_discarded() || !j.is_object()) {
      // a line cut short by a kill: everything before it is whole
      fmt::print(stderr, "depthprec: {}:{}: incomplete row left out (it will be recomputed)\n",
                 path_, number);
      break;
    }
    earlier_.push_back(std::move(j));
  }
  in.close();
  out_ = std::make_unique<std::ofstream>(path_, std::ios::app);
  if (!*out_) throw OutputError(fmt::format("cannot write the row journal '{}'", path_));
  if (fresh_journal) append({{"journal_of", identity}});
}

void RowJournal::append(const nlohmann::json& record) {
  if (!out_) return;
  *out_ << record.dump() << '\n';
  out_->flush();
  if (!*out_) throw OutputError(fmt::format("cannot append to the row journal '{}'", path_));
}

void RowJournal::remove() {
  if (!out_) return;
  out_.reset();
  std::remove(path_.c_str());
}

void throw_interrupted(const RowJournal& journal, size_t finished) {
  if (journal.active())
    throw Error(
        ExitCode::interrupted,
        fmt::format(
            "interrupted: {} finished rows kept in {}; the same command with --resume continues",
            finished, journal.path()));
  throw Error(ExitCode::interrupted,
              fmt::format("interrupted: the {} finished rows are above", finished));
}

std::vector<nlohmann::json> run_batch(
    const std::vector<std::string>& keys, const BulkCompute& compute, RowJournal& journal,
    const Shard& shard, const std::string& what, bool progress,
    const std::function<void(const std::vector<nlohmann::json>&)>& on_partial) {
  std::map<std::string, nlohmann::json> have;
  for (const auto& r : journal.earlier())
    if (r.contains("key") && r["key"].is_string()) have[r["key"].get<std::string>()] = r;
  std::vector<size_t> todo;
  for (size_t k = 0; k < keys.size(); ++k)
    if (shard.holds(k) && !have.count(keys[k])) todo.push_back(k);
  install_interrupt_handlers();
  auto in_order = [&] {
    std::vector<nlohmann::json> out;
    for (size_t k = 0; k < keys.size(); ++k)
      if (shard.holds(k) && have.count(keys[k])) out.push_back(have[keys[k]]);
    return out;
  };
  {
    Progress bar(what, todo.size(), progress);
    const auto emit = [&](size_t k, nlohmann::json record) {
      record["key"] = keys[k];
      journal.append(record);
      have[keys[k]] = std::move(record);
      bar.advance();
    };
    try {
      compute(todo, emit);
    } catch (...) {
      // A signal can also break what a unit was doing (a kernel build inside PoCL's compiler
      // fails when SIGINT lands in it): once a stop is requested, any failure is the
      // interruption, and the finished units are kept.
      if (!interrupt_requested()) throw;
      const auto done = in_order();
      if (!journal.active() && on_partial) on_partial(done);
      throw_interrupted(journal, done.size());
    }
  }
  return in_order();
}

std::vector<nlohmann::json> run_batch(
    const std::vector<BatchUnit>& units, RowJournal& journal, const Shard& shard,
    const std::string& what, bool progress,
    const std::function<void(const std::vector<nlohmann::json>&)>& on_partial) {
  std::vector<std::string> keys;
  for (const auto& u : units) keys.push_back(u.key);
  // One unit after another, the interrupt checked between them.
  const BulkCompute one_by_one = [&units](const std::vector<size_t>& todo, const Emit& emit) {
    for (size_t k : todo) {
      if (interrupt_requested()) throw Error(ExitCode::interrupted, "interrupted");
      emit(k, units[k].compute());
    }
  };
  return run_batch(keys, one_by_one, journal, shard, what, progress, on_partial);
}

nlohmann::json journal_identity(const nlohmann::json& header) {
  nlohmann::json id = header;
  for (const char* k : {"device", "wall_seconds", "kernel_seconds", "kernel_launches",
                        "emulated_seconds", "rendered_seconds"})
    id.erase(k);
  return id;
}

nlohmann::json batch_header(const std::string& kind, const std::string& device,
                            const std::string& shard) {
  nlohmann::json h = output_header(kind, device);
  if (!shard.empty()) h["shard"] = shard;
  return h;
}

namespace {
// Fields holding measured times: left out with --no-timing.
const char* const kTimingFields[] = {"seconds", "kernel_seconds", "ns_per_fragment_pair",
                                     "frames_per_second"};

void strip_timing(nlohmann::json& j) {
  if (j.is_object())
    for (const char* f : kTimingFields) j.erase(f);
  if (j.is_object() || j.is_array())
    for (auto& v : j) strip_timing(v);
}
}  // namespace

std::string records_json(const nlohmann::json& header, const std::vector<nlohmann::json>& records,
                         bool timing, const nlohmann::json& derived) {
  nlohmann::json j = header;
  for (auto& [k, v] : derived.items()) {
    j[k] = v;
    if (!timing) strip_timing(j[k]);
  }
  j["records"] = nlohmann::json::array();
  for (nlohmann::json r : records) {
    if (!timing) strip_timing(r);
    j["records"].push_back(std::move(r));
  }
  return j.dump(2) + "\n";
}

std::map<std::string, nlohmann::json> by_key(const std::vector<nlohmann::json>& records) {
  std::map<std::string, nlohmann::json> out;
  for (const auto& r : records) out[r.at("key").get<std::string>()] = r;
  return out;
}

}  // namespace depthprec
