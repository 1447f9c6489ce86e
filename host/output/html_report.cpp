#include "host/output/html_report.h"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <set>

#include "host/base/version.h"
#include "host/model/frame_setup.h"
#include "host/output/bound_table.h"
#include "host/output/implementations.h"
#include "host/output/shadow_output.h"

namespace depthprec {

std::string html_escape(const std::string& s) {
  std::string out;
  for (char c : s) switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  return out;
}

namespace {

// Print-friendly and readable on a laptop: system fonts, numbers right-aligned in tabular
// figures, the plot scaled to the page.
constexpr const char* kStyle = R"(
body { font-family: system-ui, sans-serif; margin: 2em auto; max-width: 75em; color: #222;
       padding: 0 1em; line-height: 1.4; }
h1 { font-size: 1.6em; margin-bottom: 0.2em; }
h2 { font-size: 1.25em; margin-top: 1.8em; border-bottom: 1px solid #ccc; }
table { border-collapse: collapse; font-size: 0.85em; margin: 0.6em 0; }
th, td { border: 1px solid #ccc; padding: 0.2em 0.5em; }
th { background: #f2f2f2; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
td.none { color: #a33; text-align: right; }
td.flag { background: #fff4d6; }
.wide { overflow-x: auto; }
.plot svg { max-width: 100%; height: auto; }
.meta { color: #555; font-size: 0.9em; }
code { font-size: 0.95em; }
)";

std::string cell(const std::string& text, const std::string& cls = "num",
                 const std::string& title = "") {
  return fmt::format("<td class=\"{}\"{}>{}</td>", cls,
                     title.empty() ? "" : " title=\"" + html_escape(title) + "\"",
                     html_escape(text));
}

std::string table(const std::vector<std::string>& head, const std::vector<std::string>& rows) {
  std::string out = "<div class=\"wide\"><table>\n<tr>";
  for (const auto& h : head) out += "<th>" + html_escape(h) + "</th>";
  out += "</tr>\n";
  for (const auto& r : rows) out += "<tr>" + r + "</tr>\n";
  return out + "</table></div>\n";
}

std::string scene_section(const Scene& s, size_t pairs) {
  std::vector<std::string> rows;
  const auto add = [&rows](const std::string& k, const std::string& v) {
    rows.push_back("<th>" + html_escape(k) + "</th>" + cell(v, "left"));
  };
  add("near, far", fmt::format("{}, {}", human(s.near), human(s.far)));
  add("viewport, kernel",
      fmt::format("{}x{}, {}x{}", s.viewport_w, s.viewport_h, s.kernel_w, s.kernel_h));
  add("field of view (y)", fmt::format("{} deg", human(s.fov_y_deg)));
  add("frames", std::to_string(s.frames));
  add("relative precision of the search", human(s.rel_precision));
  add("distances", fmt::format("{}, from {} to {}", s.distances.size(), human(s.distances.front()),
                               human(s.distances.back())));
  add("pairs (technique/format/depth range)", std::to_string(pairs));
  if (s.json.contains("pipeline"))
    for (const auto& [k, v] : s.json["pipeline"].items())
      add("pipeline." + k, v.is_string() ? v.get<std::string>() : v.dump());
  add("source", s.source);
  std::string out = "<h2>Scene</h2>\n";
  if (!s.description.empty()) out += "<p>" + html_escape(s.description) + "</p>\n";
  out += "<div class=\"wide\"><table>\n";
  for (const auto& r : rows) out += "<tr>" + r + "</tr>\n";
  return out + "</table></div>\n";
}

// A table of rows by distance and pair: the scene's pair labels, each once in scene order, the
// distances the rows have, and each row at (z, label).
struct RowGrid {
  std::vector<std::string> labels;
  std::set<double> zs;
  std::map<std::pair<double, std::string>, const MtsRow*> at;
};

RowGrid row_grid(const Scene& scene, const std::vector<MtsRow>& rows) {
  RowGrid g;
  std::set<std::string> seen;
  for (const auto& p : scene.evaluate)
    if (seen.insert(p.label()).second) g.labels.push_back(p.label());
  for (const auto& r : rows) {
    g.at[{r.z, r.pair.label()}] = &r;
    g.zs.insert(r.z);
  }
  return g;
}

std::string mts_section(const Scene& scene, const std::vector<MtsRow>& rows) {
  const RowGrid grid = row_grid(scene, rows);
  const auto& [labels, zs, at] = grid;
  std::vector<std::string> head = {"z", "vertex bound"};
  head.insert(head.end(), labels.begin(), labels.end());
  std::vector<std::string> body;
  // Flagged cells grouped by pair and flags, the distances listed: a pair is often flagged alike
  // over a run of distances.
  std::vector<std::pair<std::string, std::string>> flag_groups;  // (pair, flags), first seen
  std::map<std::pair<std::string, std::string>, std::string> flagged_at;
  for (double z : zs) {
    std::string tr = cell(human(z)) + cell(human(vertex_bound(z)));
    for (const auto& l : labels) {
      const auto it = at.find({z, l});
      if (it == at.end()) {
        tr += cell("");
        continue;
      }
      const MtsRow& r = *it->second;
      const std::string text = table_cell(r, false) + dominant_mark(r);
      const bool resolved = r.verdict() == Verdict::resolved;
      const std::string flags = r.flags();
      tr += cell(text, !resolved ? "none" : flags.empty() ? "num" : "num flag", flags);
      // A cell without a number shows its verdict already; the list names what a number hides.
      if (resolved && !flags.empty()) {
        std::string& at_z = flagged_at[{l, flags}];
        if (at_z.empty()) flag_groups.push_back({l, flags});
        at_z += (at_z.empty() ? "" : ", ") + human(z);
      }
    }
    body.push_back(tr);
  }
  std::string out =
      "<h2>Minimum triangle separation</h2>\n<p>The smallest separation of two planes at eye "
      "distance z (in the scene's units) for which the farther plane never wins the depth test, "
      "per technique, storage format and depth range. <code>inf</code>: no separation up to the "
      "search's limit resolves; other words name the verdict where there is no number. Shaded "
      "cells carry flags (hover for them, or see the list below).";
  bool attributed = false;
  for (const auto& r : rows) attributed |= r.attributed();
  if (attributed)
    out +=
        " S, A, V: the dominant factor -- storage quantisation, binary32 arithmetic or the "
        "binary32 vertex bound.";
  out += "</p>\n" + table(head, body);
  std::vector<std::string> flagged;
  for (const auto& g : flag_groups)
    flagged.push_back(cell(g.first, "left") + cell(g.second, "left") +
                      cell(flagged_at.at(g), "left"));
  if (!flagged.empty())
    out += "<p>Flagged cells (docs/mts.md says what each flag means):</p>\n" +
           table({"pair", "flags", "at z"}, flagged);
  return out;
}

// The guaranteed MTS of each row (docs/bound.md): with the sampled MTS of
// the table above, each answer's bracket.
std::string bound_section(const Scene& scene, const std::vector<MtsRow>& rows) {
  std::string model;
  for (const auto& r : rows)
    if (!std::isnan(r.mts_bound) && model.empty()) model = r.bound_model;
  if (model.empty()) return "";
  const RowGrid grid = row_grid(scene, rows);
  const auto& [labels, zs, at] = grid;
  std::vector<std::string> head = {"z"};
  head.insert(head.end(), labels.begin(), labels.end());
  std::vector<std::string> body;
  for (double z : zs) {
    std::string tr = cell(human(z));
    for (const auto& l : labels) {
      const auto it = at.find({z, l});
      tr += cell(it == at.end() ? "" : bound_cell(*it->second, false));
    }
    body.push_back(tr);
  }
  std::string out = fmt::format(
      "<h2>Guaranteed MTS</h2>\n<p>The separation at and above which no pixel fights in any "
      "orientation within the rotation cube, under any implementation of the bound model "
      "<code>{}</code> (docs/bound.md). A fight was seen just below the "
      "MTS above, none can happen at this: what an implementation of the model needs lies "
      "between the two. -: no finite bound (why: under the grid) or no MTS to bound.</p>\n",
      html_escape(model));
  out += table(head, body);
  for (const std::string& line : rows_without_bound(scene, rows))
    out += "<p>" + html_escape(line) + "</p>\n";
  return out;
}

// What the profiles and bound models are (host/output/implementations.h), the one this page's
// bound holds for marked: a reader sees what else the answer could have been asked under.
std::string implementations_section(const Scene& scene) {
  std::vector<std::string> body;
  for (const Implementation& i : implementations()) {
    const bool used = i.name == scene.bound_model;
    body.push_back(cell(i.name + (used ? " (this page's bound)" : ""), "left") +
                   cell(i.kind, "left") + cell(i.what, "left") + cell(i.source, "left"));
  }
  return "<h2>Implementations and envelopes</h2>\n<p>The profiles depthprec emulates "
         "(<code>--profile NAME</code>) and the models its guaranteed MTS holds for "
         "(<code>bound_model</code>), the API envelopes among them (docs/spec.md 2, "
         "\"Envelopes\").</p>\n" +
         table({"name", "kind", "what", "source"}, body);
}

std::string attribution_section(const Scene& scene, const std::vector<MtsRow>& rows) {
  std::vector<std::string> body;
  for (const auto& r : rows) {
    if (!r.attributed()) continue;
    body.push_back(
        cell(r.pair.label(), "left") + cell(human(r.z)) + cell(table_cell(r, false)) +
        cell(human(r.storage_mts)) + cell(human(r.arithmetic_mts)) + cell(human(r.vertex_bound)) +
        cell(r.dominant, "left") +
        cell(r.factor_above_mts(scene.rel_precision) ? "a factor exceeds the MTS" : "", "left"));
  }
  if (body.empty()) return "";
  return "<h2>Attribution</h2>\n<p>What limits each MTS: the storage-limited MTS (the binary64 "
         "pipeline, stored in the format), the arithmetic-limited MTS (the binary32 pipeline "
         "without storage quantisation) and the vertex bound; the largest dominates.</p>\n" +
         table({"pair", "z", "mts", "storage", "arithmetic", "vertex bound", "dominant", "note"},
               body);
}

std::string lj_section(const std::vector<LjFigure>& lj, const Scene& scene) {
  if (lj.empty()) return "";
  std::vector<std::string> body;
  for (const auto& f : lj)
    body.push_back(cell(f.pair, "left") + cell(f.buffer, "left") + cell(f.format, "left") +
                   cell(human(f.ae)));
  return fmt::format(
             "<h2>Lapidous-Jiao average depth error</h2>\n<p>For the pairs whose technique is one "
             "of Lapidous and Jiao's buffers: the average eye-distance error over [near, far] = "
             "[{}, {}], normalised by (far - near), uniform sampling, 10<sup>6</sup> samples, "
             "analytic in binary64.</p>\n",
             html_escape(human(scene.near)), html_escape(human(scene.far))) +
         table({"pair", "buffer", "format", "ae"}, body);
}

// The scene's shadow block, as `depthprec shadow` prints it: the proven biases per cascade and
// the engines' settings.
std::string shadow_section(const ReportPage& page) {
  if (page.shadow_records.empty()) return "";
  const ShadowTables t = shadow_tables(page.shadow_header, page.shadow_records, "text");
  auto rows = [](const Cells& cells) {
    std::vector<std::string> out;
    for (const auto& r : cells) {
      std::string row;
      for (size_t i = 0; i < r.size(); ++i) row += cell(r[i], i < 2 ? "left" : "num");
      out.push_back(row);
    }
    return out;
  };
  auto names = [](const std::vector<Column>& cols) {
    std::vector<std::string> out;
    for (const Column& c : cols) out.push_back(c.name);
    return out;
  };
  std::string out = "<h2>Shadow-map bias</h2>\n<p>" + html_escape(t.caption) + ".</p>\n" +
                    table(names(t.cascade_cols), rows(t.cascades));
  if (t.engines.empty()) return out;
  return out + "<p>" + html_escape(t.engine_caption) + "</p>\n" +
         table(names(t.engine_cols), rows(t.engines));
}

// gnuplot's SVG without its XML prolog and doctype, which are not allowed inside HTML.
std::string inline_svg(const std::string& svg) {
  const size_t start = svg.find("<svg");
  return start == std::string::npos ? "" : svg.substr(start);
}

}  // namespace

std::string html_report(const ReportPage& page) {
  const Scene& scene = *page.scene;
  std::string out = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  out += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  out += "<title>depthprec report: " + html_escape(scene.name) + "</title>\n";
  out += std::string("<style>") + kStyle + "</style>\n</head>\n<body>\n";
  out += "<h1>Depth precision report: " + html_escape(scene.name) + "</h1>\n";
  out += fmt::format("<p class=\"meta\">depthprec {}, {} on {}. Made by <code>{}</code>.</p>\n",
                     html_escape(kVersion), page.run.rendered.empty() ? "emulated" : "rendered",
                     html_escape(page.run.device), html_escape(page.command));
  out += scene_section(scene, scene.evaluate.size());
  out += mts_section(scene, page.rows);
  if (!page.plot_svg.empty())
    out +=
        "<h2>MTS by distance</h2>\n<div class=\"plot\">\n" + inline_svg(page.plot_svg) + "</div>\n";
  out += bound_section(scene, page.rows);
  out += attribution_section(scene, page.rows);
  out += lj_section(page.lj, scene);
  out += shadow_section(page);
  out += implementations_section(scene);
  out += "<p class=\"meta\">" + html_escape(footer(page.run)) + "</p>\n</body>\n</html>\n";
  return out;
}

}  // namespace depthprec
