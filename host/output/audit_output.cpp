#include "host/output/audit_output.h"

#include <fmt/format.h>

#include <cmath>

#include "host/base/json_number.h"
#include "host/output/report.h"
#include "host/output/text_table.h"

namespace depthprec {

namespace {

nlohmann::json surface_json(const SceneGeometry& g, int draw, uint32_t triangle) {
  const Draw& d = g.draws[draw];
  return {{"node", d.node},
          {"mesh", d.mesh},
          {"primitive", d.primitive},
          {"triangle", triangle - d.first_triangle}};
}

nlohmann::json optional_number(double v) {
  return std::isnan(v) ? nlohmann::json(nullptr) : json_number(v);
}

nlohmann::json pair_json(const SceneGeometry& g, const FightPair& p) {
  nlohmann::json j = {
      {"winner", surface_json(g, p.winner_draw, p.winner_triangle)},
      {"front", surface_json(g, p.front_draw, p.front_triangle)},
      {"fighting_pixels", p.pixels},
      {"eye_depth_min", json_number(p.depth_min)},
      {"eye_depth_median", json_number(p.depth_median)},
      {"eye_depth_max", json_number(p.depth_max)},
      {"separation_min", json_number(p.separation_min)},
      {"separation_median", json_number(p.separation_median)},
      {"mts", optional_number(p.mts)},
      {"mts_bound", optional_number(p.mts_bound)},
      {"offset_needed", optional_number(p.offset)},
      {"near_plane_that_resolves",
       p.near_plane ? json_number(*p.near_plane) : nlohmann::json(nullptr)},
      {"setups_that_resolve", p.resolving},
      {"bias_units_that_resolve", p.bias_units ? nlohmann::json(static_cast<int64_t>(*p.bias_units))
                                               : nlohmann::json(nullptr)}};
  if (!p.bias_note.empty()) j["bias_note"] = p.bias_note;
  return j;
}

// Two names of this width beside technique, format and depth range leave room for two number
// columns a block in text's 120 columns.
constexpr size_t kNameWidth = 24;

std::string short_name(const SceneGeometry& g, int draw) {
  const Draw& d = g.draws[draw];
  return d.node == d.mesh && d.primitive == 0
             ? d.node
             : fmt::format("{}/{}#{}", d.node, d.mesh, d.primitive);
}

}  // namespace

nlohmann::json audit_json(const AuditReport& r, bool timing) {
  nlohmann::json j = r.header;
  // Over several views a set-up's pixel counts (and a pair's) add up every view's pixels, while
  // the images are drawn from the first view alone.
  j["pixel_counts"] = "summed over frames";
  for (const std::string& png : r.pngs)
    if (!png.empty()) j["png_frame"] = 0;
  j["setups"] = nlohmann::json::array();
  for (size_t k = 0; k < r.setups.size(); ++k) {
    const SetupAudit& s = r.setups[k];
    nlohmann::json sj = s.pair.fields();
    sj.update({{"frames", s.frames},
               {"pixels", s.pixels},
               {"covered_pixels", s.covered_pixels},
               {"fighting_pixels", s.fighting_pixels},
               {"coplanar_pixels", s.coplanar_pixels},
               {"at_risk_pixels", s.at_risk_pixels},
               {"discarded_pixels", s.discarded_pixels},
               {"undrawn_pixels", s.undrawn_pixels},
               {"seam_pixels", s.seam_pixels},
               {"rasterised_triangles", s.records},
               {"culled_triangles", s.culled},
               {"clipped_triangles", s.clipped},
               {"non_finite_triangles", s.non_finite},
               {"pairs", nlohmann::json::array()},
               {"coplanar_pairs", nlohmann::json::array()}});
    if (!s.reduced_precision.empty())
      sj[s.reduced_precision + "_only_pixels"] = s.precision_only_pixels;
    for (const FightPair& p : s.pairs) sj["pairs"].push_back(pair_json(*r.geometry, p));
    for (const FightPair& p : s.coplanar_pairs) {
      nlohmann::json c = {{"winner", surface_json(*r.geometry, p.winner_draw, p.winner_triangle)},
                          {"front", surface_json(*r.geometry, p.front_draw, p.front_triangle)},
                          {"coplanar_pixels_lost", p.pixels},
                          {"eye_depth_median", json_number(p.depth_median)}};
      sj["coplanar_pairs"].push_back(c);
    }
    if (k < r.pngs.size() && !r.pngs[k].empty()) {
      sj["png"] = r.pngs[k];
      sj["margin_png"] = r.margin_pngs[k];
    }
    if (r.rendered.is_array() && k < r.rendered.size()) sj["rendered"] = r.rendered[k];
    if (timing) {
      sj["setup_seconds"] = json_number(s.setup_seconds);
      sj["pixel_seconds"] = json_number(s.pixel_seconds);
      sj["fix_seconds"] = json_number(s.fix_seconds);
    }
    j["setups"].push_back(sj);
  }
  return j;
}

namespace {

// The tables' rows: the fighting pairs (and in CSV the coplanar ones, by kind), and for text the
// coplanar pairs apart.
struct AuditTables {
  std::vector<Column> cols;
  Cells cells, coplanar;
};

AuditTables audit_tables(const AuditReport& r, const std::string& format) {
  const SceneGeometry& g = *r.geometry;
  const auto num = [&format](double v) { return number_cell(v, format); };
  // a value the set-up has not (no pair, no fix): "-" in text, an empty CSV field
  const std::string none = format == "csv" ? "" : "-";
  const auto opt = [&](double v) { return std::isnan(v) ? none : num(v); };
  // A surface's name in a text table: cut to kNameWidth, or one long node name widens the
  // leading columns past the terminal and the table splits into a block per column. CSV and
  // Markdown (whose readers scroll) keep it whole, as JSON does.
  const auto name = [&](int draw) {
    return format == "text" ? shortened(short_name(g, draw), kNameWidth) : short_name(g, draw);
  };
  const bool csv = format == "csv";
  // technique, format, depth_range, winner and front lead, so a table too wide for the terminal
  // repeats them in each block (host/output/text_table.h grid). CSV holds the coplanar pairs in
  // the same table, told apart by `kind`; text shows them in a table of their own below.
  AuditTables t;
  std::vector<Column>& cols = t.cols;
  cols = {{"technique", true},
          {"format", true},
          {"depth_range", true},
          {"winner", true},
          {"front", true},
          {"fighting_pixels"},
          {"at_risk_pixels"},
          {"coplanar_pixels"},
          {"covered_pixels"},
          {"pair_pixels"},
          {"eye_depth"},
          {"min_separation"},
          {"mts"},
          {"offset_needed"},
          {"near_that_resolves"},
          {"bias_units"},
          {"setups_that_resolve", true}};
  if (csv) cols.insert(cols.begin() + 3, {"kind", true});
  Cells &cells = t.cells, &coplanar = t.coplanar;
  for (const SetupAudit& s : r.setups) {
    const std::vector<std::string> head = {info(s.pair.technique).name, s.pair.format,
                                           to_string(s.pair.depth_range)};
    const auto lead = [&](const char* kind) {
      std::vector<std::string> row = head;
      if (csv) row.push_back(kind);
      return row;
    };
    const std::vector<std::string> counts = {
        std::to_string(s.fighting_pixels), std::to_string(s.at_risk_pixels),
        std::to_string(s.coplanar_pixels), std::to_string(s.covered_pixels)};
    if (s.pairs.empty() && (!csv || s.coplanar_pairs.empty())) {
      std::vector<std::string> row = lead("none");
      row.insert(row.end(), {none, none});
      row.insert(row.end(), counts.begin(), counts.end());
      row.insert(row.end(), {"0", none, none, none, none, none, none, none});
      cells.push_back(row);
    }
    for (const FightPair& p : s.pairs) {
      std::vector<std::string> row = lead("fight");
      std::string resolving;
      // one word, so the text never folds a row inside it
      for (const auto& l : p.resolving) resolving += (resolving.empty() ? "" : ",") + l;
      row.insert(row.end(), {name(p.winner_draw), name(p.front_draw)});
      row.insert(row.end(), counts.begin(), counts.end());
      row.insert(row.end(),
                 {std::to_string(p.pixels), num(p.depth_median), num(p.separation_min), opt(p.mts),
                  opt(p.offset), p.near_plane ? num(*p.near_plane) : none,
                  p.bias_units ? std::to_string(static_cast<int64_t>(*p.bias_units)) : none,
                  resolving.empty() ? none : resolving});
      cells.push_back(row);
    }
    for (const FightPair& p : s.coplanar_pairs) {
      if (!csv) {
        coplanar.push_back(head);
        coplanar.back().insert(coplanar.back().end(),
                               {name(p.winner_draw), name(p.front_draw), std::to_string(p.pixels),
                                num(p.depth_median)});
        continue;
      }
      // winner: the surface drawn first, kept; front: the one drawn later in its plane, lost
      std::vector<std::string> row = lead("coplanar");
      row.insert(row.end(), {name(p.winner_draw), name(p.front_draw)});
      row.insert(row.end(), counts.begin(), counts.end());
      row.insert(row.end(), {std::to_string(p.pixels), num(p.depth_median), none, none, none, none,
                             none, none});
      cells.push_back(row);
    }
  }
  return t;
}

// The main table's caption: the scene, the views, the planes and where they came from, and what
// every column means.
std::string audit_caption(const AuditReport& r) {
  const SceneGeometry& g = *r.geometry;
  const nlohmann::json& h = r.header;
  const int views = h.value("frames", 1);
  bool pngs = false;
  for (const std::string& png : r.pngs) pngs = pngs || !png.empty();
  const bool rendered = r.rendered.is_array();
  const std::string images = pngs && rendered ? "; the PNGs and the rendering are view 1's"
                             : pngs           ? "; the PNGs are view 1's"
                             : rendered       ? "; the rendering is view 1's"
                                              : "";
  const std::string over =
      views > 1
          ? fmt::format(" over {} views (pixel counts are sums over the views{})", views, images)
          : "";
  // Where near and far come from when the command line does not give them: a file camera's, or
  // the scene's default (with --eye, a file camera's znear is not used: near 1 then surprises).
  const auto source = [](const std::string& from, const char* field) -> std::string {
    if (from == "camera") return fmt::format(" (the file camera's {})", field);
    if (from == "scene") return " (the scene's default)";
    return "";
  };
  std::string caption = fmt::format(
      "Z-fighting in {} ({} triangles in {} {}), {} at {}x{}{}, near {}{}, far {}{}: per set-up "
      "the "
      "pixels where the depth test kept a surface behind the exact front one (fighting_pixels), "
      "those the front surface wins by less than another conformant implementation may store "
      "(at_risk_pixels), those where two surfaces share a plane (coplanar_pixels), and per "
      "fighting pair (winner "
      "drawn over front) its pixels, the front's median eye depth, the smallest separation along "
      "the ray, the set-up's MTS there, the offset the guaranteed MTS (mts_bound in JSON) asks "
      "for beyond that separation, and the fixes checked on "
      "the pair's pixels, each also within the guaranteed MTS: the nearest near plane, a "
      "constant depth bias on the front surface (API units, moving it by at least offset_needed; "
      "`bias` leads with the sampled answer instead), other set-ups",
      h.value("file", ""), g.triangles, g.draws.size(), g.draws.size() == 1 ? "draw" : "draws",
      h.value("camera", ""), h.value("width", 0), h.value("height", 0), over,
      human(h.value("near", 0.0)), source(h.value("near_source", ""), "znear"),
      human(h.value("far", 0.0)), source(h.value("far_source", ""), "zfar"));
  return caption;
}

// What the tables do not show, said in words.
std::string audit_notes(const AuditReport& r, bool timing) {
  const SceneGeometry& g = *r.geometry;
  const nlohmann::json& h = r.header;
  std::string notes;
  for (const std::string& n : g.notes) notes += n + "\n";  // how the file was read
  if (h.contains("interrupted"))
    notes += fmt::format(
        "Interrupted after {} of {} set-ups: the tables hold the finished ones, the others were "
        "not audited.\n",
        h["interrupted"].value("finished_setups", 0), h["interrupted"].value("setups", 0));
  for (const SetupAudit& s : r.setups) {
    const std::string label = s.pair.label();
    if (s.covered_pixels == 0)
      notes += label +
               ": no pixel is covered: the camera sees nothing between the near and far "
               "planes\n";
    if (s.undrawn_pixels)
      notes += fmt::format(
          "{}: {} covered pixels draw nothing: every fragment stores the cleared "
          "buffer's code (far plane too near, or the format too coarse there)\n",
          label, s.undrawn_pixels);
    if (s.non_finite)
      notes +=
          fmt::format("{}: {} triangles dropped: a vertex is not finite{}\n", label, s.non_finite,
                      s.reduced_precision == "mediump"
                          ? " (mediump shaders hold magnitudes up to 65504; binary16 overflows "
                            "beyond)"
                          : "");
    if (!s.reduced_precision.empty())
      notes += fmt::format(
          "{}: {} of the {} fighting pixels fight only because the shaders run in {}: the "
          "same views with highp shaders do not fight there ({}_only_pixels)\n",
          label, s.precision_only_pixels, s.fighting_pixels, s.reduced_precision,
          s.reduced_precision);
  }
  for (const SetupAudit& s : r.setups)
    for (const FightPair& p : s.pairs)
      if (p.winner_draw == p.front_draw)
        notes += fmt::format(
            "{}: {} fights itself ({} pixels): two parts of one draw that share no corner, as in "
            "a mesh merged from several objects (gltfpack merges meshes unless -kn keeps named "
            "nodes apart) or one passing through itself, or its own back faces behind its front "
            "ones (the audit culls no back face: a renderer culls them for a material that is not "
            "doubleSided); the JSON names a triangle of each\n",
            s.pair.label(), short_name(g, p.winner_draw), p.pixels);
  for (size_t k = 0; k < r.pngs.size(); ++k)
    if (!r.pngs[k].empty())
      notes += fmt::format("{}: {} (fights red, at risk orange, coplanar blue), margin {}\n",
                           r.setups[k].pair.label(), r.pngs[k], r.margin_pngs[k]);
  if (r.rendered.is_array())
    for (size_t k = 0; k < r.rendered.size(); ++k)
      notes += fmt::format(
          "{}: rendered on {}: fighting pixels equal to the emulation's on {} of "
          "{} pixels, winners on {}\n",
          r.setups[k].pair.label(), r.rendered[k].value("renderer", ""),
          r.rendered[k].value("fight_agree", 0), r.rendered[k].value("pixels", 0),
          r.rendered[k].value("winner_agree", 0));
  if (h.value("frames", 1) == 1)
    notes +=
        "One view: a camera moved by a fraction of a code's depth can fight where this one "
        "does not; --frames N adds N - 1 views moved by up to --jitter.\n";
  if (timing)
    for (const SetupAudit& s : r.setups)
      notes += fmt::format("{}: set-up {:.3f} s, pixels {:.3f} s, fixes {:.3f} s\n", s.pair.label(),
                           s.setup_seconds, s.pixel_seconds, s.fix_seconds);
  return notes;
}

}  // namespace

std::string audit_text(const AuditReport& r, const std::string& format, bool timing) {
  const AuditTables t = audit_tables(r, format);
  if (format == "csv") return render_cells(t.cols, t.cells, format);
  std::string text = captioned(audit_caption(r), t.cols, t.cells, format);
  if (!t.coplanar.empty())
    text += "\n" + captioned(
                       "Coplanar pairs: surfaces in one plane, which no depth buffer orders: the "
                       "one drawn first (kept) stays, the one drawn after it (lost) does not "
                       "show; its pixels and median eye depth. The draw order and the compare "
                       "decide them, not the depth: an offset or a depth bias on the one that "
                       "should show orders them",
                       {{"technique", true},
                        {"format", true},
                        {"depth_range", true},
                        {"kept", true},
                        {"lost", true},
                        {"pixels"},
                        {"eye_depth"}},
                       t.coplanar, format);
  // a blank line first, so Markdown ends the table
  const std::string notes = audit_notes(r, timing);
  if (!notes.empty()) text += "\n" + notes;
  return for_terminal(text, format);
}

}  // namespace depthprec
