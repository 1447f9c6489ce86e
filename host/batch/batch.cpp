#include "host/batch/batch.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
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

namespace {

// Whether the start of a journal is the start of the line this depthprec begins one with: a first
// line torn by a full disk or a kill is still recognisably its own.
bool starts_like_journal(const std::string& head) {
  static const std::string kStart = "{\"journal_of\":";
  return head.compare(0, kStart.size(), kStart, 0, std::min(head.size(), kStart.size())) == 0;
}

// The whole file behind fd, from its start.
std::string read_all(int fd, const std::string& path) {
  std::string text;
  char buf[65536];
  for (off_t at = 0;;) {
    const ssize_t n = ::pread(fd, buf, sizeof buf, at);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0)
      throw OutputError(
          fmt::format("cannot read the row journal '{}': {}", path, std::strerror(errno)));
    if (n == 0) return text;
    text.append(buf, static_cast<size_t>(n));
    at += n;
  }
}

}  // namespace

void RowJournal::open_locked() {
  // The lock is on the file the path names now: a run that held it may have finished and removed
  // it between our open and our lock, so the inode is compared after locking and the open retried.
  for (int attempt = 0;; ++attempt) {
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0)
      throw OutputError(
          fmt::format("cannot write the row journal '{}': {}", path_, std::strerror(errno)));
    struct flock lock {};
    lock.l_type = F_WRLCK;
    lock.l_whence = SEEK_SET;
    if (::fcntl(fd_, F_SETLK, &lock) != 0) {
      const int err = errno;
      struct flock holder {};
      holder.l_type = F_WRLCK;
      holder.l_whence = SEEK_SET;
      const bool known = ::fcntl(fd_, F_GETLK, &holder) == 0 && holder.l_type != F_UNLCK;
      ::close(fd_);
      fd_ = -1;
      if (err != EACCES && err != EAGAIN) {
        // A file system without locks (some network mounts): the run goes on, unguarded.
        fmt::print(stderr,
                   "depthprec: note: cannot lock the row journal '{}' ({}): a second run writing "
                   "the same output at the same time would not be noticed\n",
                   path_, std::strerror(err));
        fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        if (fd_ < 0)
          throw OutputError(
              fmt::format("cannot write the row journal '{}': {}", path_, std::strerror(errno)));
        return;
      }
      if (!known && attempt < 10) continue;  // released in between: try again
      throw InputError(fmt::format(
          "{} is in use by another depthprec run{} writing the same output now; wait for it to "
          "finish (or stop it and continue with --resume), or choose another --output",
          path_, known && holder.l_pid > 0 ? fmt::format(" (process {})", holder.l_pid) : ""));
    }
    struct stat held = {};
    struct stat named = {};
    if (::fstat(fd_, &held) == 0 && ::stat(path_.c_str(), &named) == 0 &&
        held.st_dev == named.st_dev && held.st_ino == named.st_ino)
      return;
    ::close(fd_);
    fd_ = -1;
    if (attempt >= 10)
      throw OutputError(
          fmt::format("cannot lock the row journal '{}': it keeps being replaced", path_));
  }
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
  open_locked();
  try {
    read_or_start(resume, identity);
  } catch (...) {
    // A constructor that throws runs no destructor: the lock is released here, and a journal
    // left empty (this run's, or an empty one it found) removed, so it is in no rerun's way.
    struct stat st {};
    if (::fstat(fd_, &st) == 0 && st.st_size == 0) ::unlink(path_.c_str());
    ::close(fd_);
    fd_ = -1;
    throw;
  }
}

void RowJournal::read_or_start(bool resume, const nlohmann::json& identity) {
  const std::string text = read_all(fd_, path_);
  const size_t first_end = text.find('\n');
  const auto head = first_end == std::string::npos
                        ? nlohmann::json()
                        : nlohmann::json::parse(text.substr(0, first_end), nullptr, false);
  const bool ours = head.is_object() && head.contains("journal_of");
  if (!ours && !(text.empty() || (first_end == std::string::npos && starts_like_journal(text)))) {
    // Someone else's file, theirs to delete.
    const std::string what = fmt::format(
        "{}: not a journal this depthprec wrote (its first line does not say which run it "
        "belongs to); delete it to start over, or choose another --output",
        path_);
    if (resume) throw InputError(what);
    throw OutputError(what);
  }
  // The whole rows after the first line; a line cut short (no newline, or not an object) ends
  // them: everything before it is whole.
  std::vector<nlohmann::json> rows;
  size_t whole = ours ? first_end + 1 : 0, torn_line = 0;
  for (size_t at = whole, number = 2; ours && at < text.size(); ++number) {
    const size_t end = text.find('\n', at);
    if (end == std::string::npos) {
      torn_line = number;
      break;
    }
    if (end > at) {
      auto j = nlohmann::json::parse(text.substr(at, end - at), nullptr, false);
      if (j.is_discarded() || !j.is_object()) {
        torn_line = number;
        break;
      }
      rows.push_back(std::move(j));
    }
    at = whole = end + 1;
  }
  if (!rows.empty()) {
    if (!resume)
      throw Error(ExitCode::output,
                  fmt::format("{} holds the finished rows of an interrupted run: continue it "
                              "with --resume, or delete it to start over",
                              path_));
    const std::string diff = first_difference(head["journal_of"], identity);
    if (!diff.empty())
      throw InputError(fmt::format(
          "{} was written by another run ({}: the journal's value, then this run's); run the "
          "same command to resume it, or delete it to start over",
          path_, diff));
    if (torn_line > 0) {
      // Cut off, so the next row starts on a line of its own.
      fmt::print(stderr, "depthprec: {}:{}: incomplete row left out (it will be recomputed)\n",
                 path_, torn_line);
      if (::ftruncate(fd_, static_cast<off_t>(whole)) != 0)
        throw OutputError(
            fmt::format("cannot write the row journal '{}': {}", path_, std::strerror(errno)));
    }
    earlier_ = std::move(rows);
    rows_ = earlier_.size();
    size_ = static_cast<long long>(whole);
    return;
  }
  // No finished row in it -- empty (a disk that was full), its first line torn, or that line
  // alone (a run stopped before its first row): nothing is lost by starting it afresh.
  if (!text.empty())
    fmt::print(stderr, "depthprec: note: {} held no finished rows; starting it afresh\n", path_);
  if (::ftruncate(fd_, 0) != 0)
    throw OutputError(
        fmt::format("cannot write the row journal '{}': {}", path_, std::strerror(errno)));
  write_line(nlohmann::json{{"journal_of", identity}}.dump() + "\n");
}

RowJournal::~RowJournal() {
  if (fd_ < 0) return;
  if (rows_ == 0) ::unlink(path_.c_str());  // while still locked: no other run has it open
  ::close(fd_);
}

void RowJournal::write_line(const std::string& line) {
  size_t done = 0;
  while (done < line.size()) {
    const ssize_t n = ::pwrite(fd_, line.data() + done, line.size() - done,
                               static_cast<off_t>(size_ + static_cast<long long>(done)));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : ENOSPC;
      // What was written of the line is cut off again: the journal keeps whole lines only.
      (void)::ftruncate(fd_, static_cast<off_t>(size_));
      throw OutputError(fmt::format(
          "cannot append to the row journal '{}': {}{}", path_, std::strerror(err),
          rows_ > 0 ? fmt::format("; its {} finished rows are kept: the same command with "
                                  "--resume continues once there is room",
                                  rows_)
                    : ""));
    }
    done += static_cast<size_t>(n);
  }
  size_ += static_cast<long long>(line.size());
}

void RowJournal::append(const nlohmann::json& record) {
  if (fd_ < 0) return;
  write_line(record.dump() + "\n");
  ++rows_;
}

void RowJournal::remove() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());
  ::close(fd_);
  fd_ = -1;
}

void write_batch_output(RowJournal& journal, const std::string& output, const std::string& text) {
  try {
    write_output(output, text);
  } catch (const OutputError& e) {
    if (!journal.active() || journal.rows() == 0) throw;
    throw OutputError(fmt::format(
        "{}; the {} finished rows are kept in {}: the same command with --resume writes the "
        "output from them",
        e.what(), journal.rows(), journal.path()));
  }
  journal.remove();
}

void throw_interrupted(const RowJournal& journal, size_t finished) {
  if (journal.active() && finished == 0)  // the journal goes with the run: it holds no row
    throw Error(ExitCode::interrupted, "interrupted before any row finished: nothing to keep");
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
