#include "host/output/report.h"

#include <fmt/format.h>
#include <stdio_ext.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "host/base/errors.h"
#include "host/base/version.h"
#include "host/model/frame_setup.h"
#include "host/mts/row_json.h"
#include "host/output/bound_table.h"
#include "host/output/json_header.h"
#include "host/output/text_table.h"

namespace depthprec {

using nlohmann::json;

namespace {

json header(const Scene& scene, const RunInfo& run) {
  json h = output_header(run.kind, run.device);
  h["scene_name"] = scene.name;
  h["scene_source"] = scene.source;
  h["scene"] = scene.json;
  h["kernel_variants"] = run.variants;
  h["fragment_pairs"] = run.fragment_pairs;
  if (!run.rendered.empty()) {
    h["gl_renderer"] = run.rendered.renderer;
    h["gl_version"] = run.rendered.version;
    h["egl_platform"] = run.rendered.platform;
    h["depth_buffers"] = run.rendered.depth_buffers;
  }
  h["separation_reported"] = "requested s (plane B at fl32(z+s)); mts_seen = fl32(z+mts) - fl32(z)";
  if (!run.shard.empty()) h["shard"] = run.shard;
  if (run.timing) {  // measured, and specific to this process (a resumed run does less)
    h["wall_seconds"] = run.wall_seconds;
    h["kernel_seconds"] = run.kernel_seconds;
    h["kernel_launches"] = run.launches;
  }
  return h;
}

}  // namespace

std::string table_cell(const MtsRow& r, bool full) {
  switch (r.verdict()) {
    case Verdict::resolved:
    case Verdict::unresolvable:
      return full ? exact(r.mts) : human(r.mts);
    case Verdict::non_finite:
      return "non-finite";
    case Verdict::clipped:
      return "clipped";
    case Verdict::uncovered:
      return "uncovered";
    case Verdict::below_vertex_bound:
      return "<vb";
    case Verdict::beyond_far_plane:
      return "beyond far";
    case Verdict::nearer_than_near_plane:
      return "before near";
  }
  return "?";
}

std::string dominant_mark(const MtsRow& r) {
  const bool has_number = r.verdict() == Verdict::resolved || r.verdict() == Verdict::unresolvable;
  if (!r.attributed() || !has_number) return "";
  return " " + std::string(1, static_cast<char>(std::toupper(r.dominant[0])));
}

std::string footer(const RunInfo& run) {
  if (!run.rendered.empty()) {
    std::string s = fmt::format(
        "rendered on {} (OpenGL {}, EGL {}); kernel pixel pairs compared: {}",
        run.rendered.renderer, run.rendered.version, run.rendered.platform, run.fragment_pairs);
    if (run.timing && run.wall_seconds > 0)
      s += fmt::format(", wall time: {:.2f} s", run.wall_seconds);
    return s;
  }
  std::string s = fmt::format("fragment pairs evaluated: {}, kernel variants: {}",
                              run.fragment_pairs, run.variants.size());
  if (run.timing && run.wall_seconds > 0)
    s += fmt::format(
        ", kernel launches: {}, wall time: {:.2f} s (kernels {:.2f} s), {} evaluated by this run, "
        "{:.3g} fragment pairs/s",
        run.launches, run.wall_seconds, run.kernel_seconds, run.evaluated_pairs,
        static_cast<double>(run.evaluated_pairs) / run.wall_seconds);
  return s;
}

namespace {

// A worst-case row's convergence: the last refinement's relative rise of the MTS.
// The row's flags, and on the text page why it is non_monotone (JSON and CSV carry the numbers:
// monotone_clean, monotone_fight).
std::string flags_cell(const MtsRow& r, bool full) {
  std::string f = r.flags();
  if (!full && r.non_monotone && !std::isnan(r.monotone_fight))
    f += fmt::format(" (clean at {} below a fight at {})", human(r.monotone_clean),
                     human(r.monotone_fight));
  return f;
}

std::string convergence_cell(const MtsRow& r, bool full) {
  return full ? exact(r.convergence) : fmt::format("{:.2g}", r.convergence);
}

// The paper's frames alone more than 5 % below the worst case (the table marks it ^).
bool paper_far_below(const MtsRow& r) {
  return std::isfinite(r.mts) && r.mts_paper < 0.95 * r.mts;
}

// "100 frames", or how the worst case was sampled.
std::string sampling_caption(const Scene& s) {
  if (s.sampling == Sampling::paper) return fmt::format("{} frames", s.frames);
  const WorstCaseSettings& w = s.worst_case;
  return fmt::format(
      "worst case over rotations within ±{}°: the paper's {} frames, then rounds of {}, {}, ... "
      "orientations, each doubling them, {} to {} rounds until one raises the MTS by at most {}",
      human(s.rotation_range_deg), s.frames, w.round_size, 2 * w.round_size, w.min_rounds,
      w.max_rounds, human(w.tolerance));
}

}  // namespace

std::string render_rows(const Scene& scene, const std::vector<MtsRow>& rows, const RunInfo& run,
                        const std::string& format) {
  if (format == "json") {
    json j = header(scene, run);
    j["rows"] = json::array();
    for (const auto& r : rows) j["rows"].push_back(row_to_json(r, run.timing));
    return j.dump(2) + "\n";
  }
  const bool full = format == "csv";
  auto num = [full](double v) { return full ? exact(v) : human(v); };
  std::vector<Column> cols = {{"technique", true},
                              {"format", true},
                              {"depth_range", true},
                              {"z"},
                              {"mts"},
                              {"mts_bound"},
                              {"lo"},
                              {"hi"},
                              {"mts_seen"},
                              {"vertex_bound"},
                              {"mts/vb"},
                              {"mts_upper"},
                              {"verdict", true},
                              {"probes"},
                              {"frames"},
                              {"fragment_pairs"},
                              {"launches"}};
  bool attributed = false, rendered = false;
  for (const auto& r : rows) {
    attributed |= r.attributed();
    rendered |= r.source == RowSource::rendered;
  }
  // Emulated outputs keep their columns; a rendered row says so (JSON rows always carry it).
  if (rendered) cols.insert(cols.begin(), {"source", true});
  // Worst-case sampling: the paper's frames' answer and how far the worst case converged, after
  // the MTS (docs/cli.md, "Reading a worst-case row").
  const bool worst_case = scene.sampling == Sampling::worst_case;
  const size_t sampling_at = rendered ? 7 : 6;  // after mts and mts_bound
  if (worst_case)
    cols.insert(cols.begin() + static_cast<long>(sampling_at),
                {{"mts_paper"}, {"orientations"}, {"convergence"}});
  if (attributed)
    for (const char* c : {"storage_mts", "arithmetic_mts"}) cols.push_back({c});
  if (attributed) cols.push_back({"dominant", true});
  if (run.timing) {
    cols.push_back({"seconds"});
    cols.push_back({"kernel_s"});
    if (rendered) cols.push_back({"frames/s"});
  }
  if (full) cols.push_back({"bound_model", true});
  cols.push_back({"bound_by", true});
  cols.push_back({"flags", true});
  std::vector<std::vector<std::string>> cells;
  for (const auto& r : rows) {
    std::vector<std::string> c = {info(r.pair.technique).name,
                                  r.pair.format,
                                  to_string(r.pair.depth_range),
                                  num(r.z),
                                  num(r.mts),
                                  bound_cell(r, full),
                                  num(r.lo),
                                  num(r.hi),
                                  num(r.mts_seen),
                                  num(r.vertex_bound),
                                  num(r.mts / r.vertex_bound),
                                  r.non_monotone && r.fight_max > r.mts ? num(r.fight_max)
                                  : full                                ? ""
                                                                        : "-",
                                  to_string(r.verdict()),
                                  std::to_string(r.probes),
                                  std::to_string(r.frames),
                                  std::to_string(r.fragment_pairs),
                                  std::to_string(r.launches)};
    if (rendered) c.insert(c.begin(), to_string(r.source));
    if (worst_case)
      c.insert(c.begin() + static_cast<long>(sampling_at),
               {num(r.mts_paper), std::to_string(r.orientations), convergence_cell(r, full)});
    if (attributed) {
      c.push_back(num(r.storage_mts));
      c.push_back(num(r.arithmetic_mts));
      c.push_back(r.dominant + (r.factor_above_mts(scene.rel_precision) ? " (factor > mts)" : ""));
    }
    if (run.timing) {
      c.push_back(number_cell(r.seconds, format, "{:.3f}"));
      c.push_back(number_cell(r.kernel_seconds, format, "{:.3f}"));
      if (rendered) c.push_back(full ? exact(r.frames_per_second) : human(r.frames_per_second));
    }
    if (full) c.push_back(r.bound_model);
    c.push_back(r.bound_note);
    c.push_back(flags_cell(r, full));
    cells.push_back(c);
  }
  if (format == "csv") return csv(cols, cells);
  std::string out = grid(cols, cells, format == "markdown");
  out += (format == "markdown" ? "\n" : "") + footer(run) + "\n";
  return format == "markdown" ? out : wrap_text(out);
}

namespace {

// Columns in the scene's pair order, rows in distance order. CSV (full) keeps what text marks with
// ~, * and S/A/V as columns of their own beside each pair's.
struct WideTable {
  std::vector<std::string> labels;
  std::map<std::pair<double, std::string>, const MtsRow*> at;
  bool full = false, attributed = false, worst_case = false;
};

// The cells the text table marks, for the legends under it.
struct TableMarks {
  std::vector<const MtsRow*> marked;  // cells marked *, in table order
  bool below_code = false, paper_below = false;
};

WideTable wide_table(const Scene& scene, const std::vector<MtsRow>& rows, bool full) {
  WideTable t;
  std::map<std::string, size_t> col_of;
  for (const auto& p : scene.evaluate) {
    const std::string l = p.label();
    if (col_of.emplace(l, t.labels.size()).second) t.labels.push_back(l);
  }
  for (const auto& r : rows) t.at[{r.z, r.pair.label()}] = &r;
  t.full = full;
  for (const auto& r : rows) t.attributed |= r.attributed();
  t.worst_case = scene.sampling == Sampling::worst_case;
  return t;
}

std::vector<Column> wide_columns(const WideTable& t) {
  std::vector<Column> cols = {{"z"}, {"vertex_bound"}};
  for (const auto& l : t.labels) {
    cols.push_back({l});
    if (t.full) cols.push_back({l + " mts_bound"});
    if (t.full) cols.push_back({l + " flags"});
    if (t.full && t.attributed) cols.push_back({l + " dominant"});
    if (t.full && t.worst_case) {
      cols.push_back({l + " mts_paper"});
      cols.push_back({l + " convergence"});
    }
  }
  return cols;
}

void add_csv_cells(const WideTable& t, const MtsRow* r, std::vector<std::string>& c) {
  if (!r) {
    c.insert(c.end(), {"", "", ""});
    if (t.attributed) c.push_back("");
    if (t.worst_case) c.insert(c.end(), {"", ""});
    return;
  }
  c.push_back(table_cell(*r, true));
  c.push_back(bound_cell(*r, true));
  c.push_back(r->flags());
  if (t.attributed) c.push_back(r->dominant);
  if (t.worst_case) c.insert(c.end(), {exact(r->mts_paper), convergence_cell(*r, true)});
}

std::string marked_cell(const MtsRow& r, bool worst_case, TableMarks& marks) {
  std::string v = table_cell(r, false) + dominant_mark(r);
  if (worst_case && paper_far_below(r)) {
    v += "^";
    marks.paper_below = true;
  }
  if (r.below_one_code) {
    v += "~";
    marks.below_code = true;
  }
  if (r.non_monotone || r.non_finite || r.clipped || r.uncovered) {
    v += "*";
    marks.marked.push_back(&r);
  }
  return v;
}

std::vector<std::string> wide_row(const WideTable& t, double z, TableMarks& marks) {
  std::vector<std::string> c = {t.full ? exact(z) : human(z),
                                t.full ? exact(vertex_bound(z)) : human(vertex_bound(z))};
  for (const auto& l : t.labels) {
    const auto it = t.at.find({z, l});
    const MtsRow* r = it == t.at.end() ? nullptr : it->second;
    if (t.full)
      add_csv_cells(t, r, c);
    else
      c.push_back(r ? marked_cell(*r, t.worst_case, marks) : "");
  }
  return c;
}

std::string wide_caption(const Scene& scene) {
  return fmt::format(
      "MTS by eye distance z, both in scene units (scene {}, near {}, far {}, kernel {}x{}, {}, "
      "rel. precision {}); inf = unresolvable, non-finite / clipped / uncovered / beyond far / "
      "before near / <vb (below the vertex bound) = the verdict where there is no MTS\n\n",
      scene.name, human(scene.near), human(scene.far), scene.kernel_w, scene.kernel_h,
      sampling_caption(scene), human(scene.rel_precision));
}

std::string flagged_cells(const std::vector<const MtsRow*>& marked, bool md) {
  if (marked.empty()) return "";
  std::string out = "\n";
  out += "* flagged: the cells and their flags (docs/mts.md says what each means)\n\n";
  Cells fcells;
  for (const MtsRow* r : marked)
    fcells.push_back({r->pair.label(), human(r->z), flags_cell(*r, false)});
  return out + grid({{"pair", true}, {"z"}, {"flags", true}}, fcells, md);
}

std::string mark_legends(const TableMarks& marks, const Scene& scene, bool md) {
  std::string out;
  if (marks.below_code) {
    out += md ? "\n" : "";
    out +=
        "~ below one storage code at its z (flag below_one_code): the planes' depths in the kernel "
        "did not "
        "span a code, so where z falls between codes decided it; a z nearby can need up to one "
        "code "
        "(code_width in --format-out json)\n";
  }
  if (marks.paper_below) {
    out += md ? "\n" : "";
    out += fmt::format(
        "^ the paper's {} frames alone give an MTS more than 5 % below the worst case (mts_paper "
        "in --format-out csv or json): a separation between the two fights in an orientation the "
        "paper's path does not reach\n",
        scene.frames);
  }
  return out;
}

std::string attribution_section(const Scene& scene, const std::vector<MtsRow>& rows, bool md) {
  std::string out = "\n";
  out +=
      "S / A / V: the dominant factor -- storage (the MTS of the binary64 pipeline stored in the "
      "format), "
      "arithmetic (the binary32 pipeline without storage quantisation) or vertex (the vertex "
      "bound). "
      "The factors:\n\n";
  std::vector<Column> acols = {{"pair", true},     {"z"},          {"mts"},
                               {"storage"},        {"arithmetic"}, {"vertex_bound"},
                               {"dominant", true}, {"note", true}};
  std::vector<std::vector<std::string>> acells;
  for (const auto& r : rows) {
    if (!r.attributed()) continue;
    acells.push_back({r.pair.label(), human(r.z), table_cell(r, false), human(r.storage_mts),
                      human(r.arithmetic_mts), human(r.vertex_bound), r.dominant,
                      r.factor_above_mts(scene.rel_precision) ? "a factor exceeds the MTS" : ""});
  }
  return out + grid(acols, acells, md);
}

}  // namespace

std::string render_table(const Scene& scene, const std::vector<MtsRow>& rows, const RunInfo& run,
                         const std::string& format) {
  if (format == "json") return render_rows(scene, rows, run, "json");
  const WideTable t = wide_table(scene, rows, format == "csv");
  std::vector<std::vector<std::string>> cells;
  TableMarks marks;
  for (double z : scene.distances_ascending()) cells.push_back(wide_row(t, z, marks));
  if (format == "csv") return csv(wide_columns(t), cells);
  const bool md = format == "markdown";
  std::string out = wide_caption(scene);
  out += grid(wide_columns(t), cells, md);
  out += flagged_cells(marks.marked, md);
  out += mark_legends(marks, scene, md);
  out += bound_grid(scene, rows, md);
  if (t.attributed) out += attribution_section(scene, rows, md);
  out += (md ? "\n" : "") + footer(run) + "\n";
  return md ? out : wrap_text(out);
}

bool is_stream_output(const std::string& path) {
  std::error_code ec;
  const auto st = std::filesystem::status(path, ec);
  return !ec && std::filesystem::exists(st) && !std::filesystem::is_regular_file(st) &&
         !std::filesystem::is_directory(st);
}

void check_writable(const std::string& path) {
  if (path.empty()) return;
  // A directory takes no output; found only at the final rename, it would cost the whole run.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw OutputError(fmt::format("cannot write output '{}': it is a directory", path));
  if (is_stream_output(path)) {  // opening a FIFO would wait for its reader
    if (::access(path.c_str(), W_OK) != 0)
      throw OutputError(fmt::format("cannot write output '{}': {}", path, std::strerror(errno)));
    return;
  }
  const std::string tmp = path + ".tmp";
  FILE* f = std::fopen(tmp.c_str(), "w");
  if (!f)
    throw OutputError(fmt::format("cannot write output '{}': {}", path, std::strerror(errno)));
  std::fclose(f);
  std::remove(tmp.c_str());
}

void write_output(const std::string& path, const std::string& text) {
  if (path.empty()) {
    // A full disk or /dev/full fails here, at the write or at the flush: the result is lost, and
    // the run must not end as if it had been delivered.
    const bool ok = std::fwrite(text.data(), 1, text.size(), stdout) == text.size();
    if (std::fflush(stdout) != 0 || !ok) {
      const int err = errno;
      __fpurge(stdout);  // what did not go out is dropped, so the exit's check does not fail again
      std::clearerr(stdout);
      throw OutputError(fmt::format("cannot write standard output: {}", std::strerror(err)));
    }
    return;
  }
  const bool in_place = is_stream_output(path);
  const std::string tmp = in_place ? path : path + ".tmp";
  FILE* f = std::fopen(tmp.c_str(), "w");
  if (!f)
    throw OutputError(fmt::format("cannot write output '{}': {}", path, std::strerror(errno)));
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  const bool closed = std::fclose(f) == 0;
  if (ok && closed && (in_place || std::rename(tmp.c_str(), path.c_str()) == 0)) return;
  const int err = errno;
  if (!in_place) std::remove(tmp.c_str());  // a failed write leaves nothing half written behind
  throw OutputError(fmt::format("cannot write output '{}': {}", path, std::strerror(err)));
}

}  // namespace depthprec
