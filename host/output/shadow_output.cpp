#include "host/output/shadow_output.h"

#include <fmt/format.h>

#include "host/output/text_table.h"

namespace depthprec {

namespace {

std::string shadow_cell(const nlohmann::json& j, const char* key, const std::string& format) {
  if (!j.contains(key) || j.at(key).is_null()) return format == "csv" ? "" : "-";
  if (j.at(key).is_boolean()) return j.at(key).get<bool>() ? "yes" : "no";
  return number_cell(j.at(key).get<double>(), format);
}

// "97 %": a witnessed value as a share of the bound's.
std::string witnessed_share(const nlohmann::json& rec, const char* witnessed, const char* bound) {
  if (!rec.contains("witnessed")) return "-";
  const nlohmann::json &b = rec["bound"][bound], &w = rec["witnessed"][witnessed];
  if (!b.is_number() || !w.is_number() || !(b.get<double>() > 0)) return "-";
  return fmt::format("{:.0f}%", 100 * w.get<double>() / b.get<double>());
}

std::string camera_cell(const nlohmann::json& rec) {
  if (rec.contains("distance")) return human(rec["distance"].get<double>());
  if (!rec.contains("split")) return "-";
  return human(rec["split"][0].get<double>()) + "-" + human(rec["split"][1].get<double>());
}

std::string caption(const nlohmann::json& h) {
  return fmt::format(
      "Shadow bias, {10} light: {0}x{0} texels per {11}, {1}{2}, filter {3} (reads "
      "texels up to {4} texels away per axis), receivers up to {5} degrees from the light, light "
      "{6} degrees above the horizon, raster bias under {7} (r = {8}{12}). Proven under bound "
      "model {9}: no receiver up to the slope limit shadows itself. constant: a depth bias alone, "
      "in r "
      "and in metres along the light. slope: the slope factor, with the constant the rounding "
      "errors alone need (err r). normal: the receiver's offset along its normal, with that same "
      "constant. gap: the shadow a wall standing on level ground loses at its foot, metres. "
      "witnessed: the smallest clean value the emulation found, as a share of the proven one "
      "(constant/slope/normal)",
      h.value("resolution", 0), h.value("format", std::string("?")),
      h.value("reversed", false) ? " reversed" : "", h.value("filter", std::string("?")),
      human(h.value("reach_texels", 0.0)), human(h.value("slope_max_deg", 0.0)),
      human(h.value("light_elevation_deg", 0.0)), h.value("api", std::string("?")),
      h.contains("r") ? human(h.value("r", 0.0)) : std::string("each row's depth's, in the JSON"),
      h.value("bound_model", std::string("?")), h.value("light", std::string("directional")),
      h.value("light", std::string()) == "spot"
          ? fmt::format("map ({} degree cone; a row per receiver distance d, its texel there)",
                        human(h.value("spot_angle_deg", 0.0)))
          : std::string("cascade"),
      // A float buffer's r is 2^(e - 23), e the exponent of a caster's largest depth: the
      // directional light's is taken where it is largest (shadow_r).
      h.contains("r") && h.value("format", std::string()).rfind("unorm", 0) != 0
          ? ", a float buffer's r at depths in [1/2, 1), where it is largest: a caster at depths "
            "in [2^-k-1, 2^-k) needs 2^k times the units; constant m holds at any depth"
          : "");
}

// The two columns that name a row: a cascade and its camera split, or (a spot light's one map) a
// row per receiver distance d along its axis.
std::vector<Column> named_by_light(std::vector<Column> cols, const nlohmann::json& header) {
  if (header.value("light", std::string()) == "spot") {
    cols[0] = {"row", true};
    cols[1] = {"receiver d m", true};
  }
  return cols;
}

const std::vector<Column>& cascade_columns() {
  static const std::vector<Column> cols = {
      {"cascade", true}, {"camera m", true}, {"texel m"},      {"range m"},  {"constant r"},
      {"constant m"},    {"constant gap m"}, {"slope"},        {"err r"},    {"slope gap m"},
      {"normal texels"}, {"normal m"},       {"normal gap m"}, {"witnessed"}};
  return cols;
}

std::vector<std::string> cascade_cells(const nlohmann::json& rec, const std::string& f) {
  const nlohmann::json& b = rec["bound"];
  std::string witnessed = "-";
  if (rec.contains("witnessed"))
    witnessed = rec["witnessed"].value("bound_clean", true)
                    ? witnessed_share(rec, "constant_units", "constant_units") + "/" +
                          witnessed_share(rec, "slope_factor", "slope_factor") + "/" +
                          witnessed_share(rec, "normal_metres", "normal_metres")
                    : "BOUND FAILED";
  return {std::to_string(rec.value("cascade", 0)),
          camera_cell(rec),
          shadow_cell(rec, "texel", f),
          shadow_cell(rec, "depth_range", f),
          shadow_cell(b, "constant_units", f),
          shadow_cell(b, "constant_metres", f),
          shadow_cell(b, "gap_constant", f),
          shadow_cell(b, "slope_factor", f),
          shadow_cell(b, "error_units", f),
          shadow_cell(b, "gap_slope", f),
          shadow_cell(b, "normal_texels", f),
          shadow_cell(b, "normal_metres", f),
          shadow_cell(b, "gap_normal", f),
          witnessed};
}

const std::vector<Column>& engine_columns() {
  static const std::vector<Column> cols = {
      {"cascade", true},         {"engine", true},    {"depth bias alone"},
      {"normal bias"},           {"with depth bias"}, {"depth bias at default normal"},
      {"defaults suffice", true}};
  return cols;
}

std::vector<std::string> engine_cells(const nlohmann::json& rec, const nlohmann::json& e,
                                      const std::string& f) {
  return {std::to_string(rec.value("cascade", 0)),   e.value("engine", std::string("?")),
          shadow_cell(e, "depth_alone", f),          shadow_cell(e, "normal_min", f),
          shadow_cell(e, "depth_for_normal_min", f), shadow_cell(e, "depth_with_default_normal", f),
          shadow_cell(e, "default_suffices", f)};
}

std::string engine_caption(const nlohmann::json& h) {
  std::string units;
  for (const auto& e : h["engines"]) {
    const std::string name = e.value("engine", std::string("?"));
    if (!e.value("public_formula", true)) {
      units += fmt::format(" {}: {}.", name, "no conversion, its formula is not public");
      continue;
    }
    units +=
        fmt::format(" {}: depth bias in {}; normal bias in {}; defaults {} and {}.", name,
                    e.value("depth_unit", std::string()), e.value("normal_unit", std::string()),
                    human(e.value("default_depth", 0.0)), human(e.value("default_normal", 0.0)));
  }
  return "The same in each engine's settings (docs/shadow.md \"Engines\"), each with the raster "
         "bias it always applies: the depth bias alone; the smallest normal bias and the depth "
         "bias that goes with it ('-': its normal bias cannot cover shallow slopes alone); the "
         "depth bias its default normal bias needs; whether its default pair suffices." +
         units;
}

const std::vector<Column>& rendered_columns() {
  static const std::vector<Column> cols = {
      {"cascade", true},       {"camera m", true},    {"points"},
      {"acne at bound c/s/n"}, {"acne at 90% c/s/n"}, {"clean at bound", true},
      {"gap formula m"},       {"gap ray cast m"},    {"gap rendered m"}};
  return cols;
}

// "0/0/0": acne counts of the three recipes at one level ('-': a recipe not rendered).
std::string acne_counts(const nlohmann::json& r, const char* level) {
  std::string out;
  for (const char* recipe : {"constant", "slope", "normal"}) {
    if (!out.empty()) out += "/";
    const bool has = r.contains(recipe) && r[recipe].contains(level);
    out += has ? std::to_string(r[recipe][level].get<uint64_t>()) : "-";
  }
  return out;
}

std::vector<std::string> rendered_cells(const nlohmann::json& rec, const std::string& f) {
  const nlohmann::json& r = rec["rendered"];
  const nlohmann::json gap = r.value("gap", nlohmann::json::object());
  return {std::to_string(rec.value("cascade", 0)),
          camera_cell(rec),
          std::to_string(r.value("points", uint64_t{0})),
          acne_counts(r, "acne_at_bound"),
          acne_counts(r, "acne_at_90_percent"),
          r.value("clean_at_bound", false) ? "yes" : "NO",
          shadow_cell(gap, "formula", f),
          shadow_cell(gap, "raycast", f),
          shadow_cell(gap, "rendered", f)};
}

std::string rendered_caption(const nlohmann::json& h) {
  return fmt::format(
      "Rendered on {}: receiver points looked up through a shadow pass drawn with each proven "
      "bias (constant/slope/normal; '-': the normal offset carries lookups beyond the window "
      "drawn), acne at it and at 90 % of it (the bias is tight where acne appears there), and the "
      "gap a wall's shadow loses at its foot: the formula's, a ray cast's, the rendered edge's "
      "(directional light only)",
      h.value("renderer", std::string("the system's OpenGL")));
}

}  // namespace

std::string render_shadow_output(const nlohmann::json& header,
                                 const std::vector<nlohmann::json>& records,
                                 const std::string& format) {
  if (format == "json") {
    nlohmann::json out = header;
    out["cascades"] = records;
    return out.dump(2) + "\n";
  }
  if (format == "csv") {
    std::vector<Column> cols = named_by_light(cascade_columns(), header);
    bool rendered = false;
    for (const auto& rec : records) rendered |= rec.contains("rendered");
    const std::vector<Column>& rc = rendered_columns();
    if (rendered) cols.insert(cols.end(), rc.begin() + 2, rc.end());
    const std::vector<Column>& ec = engine_columns();
    cols.insert(cols.end(), ec.begin() + 1, ec.end());
    Cells cells;
    for (const auto& rec : records) {
      std::vector<std::string> c = cascade_cells(rec, format);
      if (rendered) {
        std::vector<std::string> r(rc.size() - 2, "");
        if (rec.contains("rendered")) {
          const std::vector<std::string> all = rendered_cells(rec, format);
          r.assign(all.begin() + 2, all.end());
        }
        c.insert(c.end(), r.begin(), r.end());
      }
      if (rec["engines"].empty()) {
        std::vector<std::string> row = c;
        row.resize(cols.size(), "");
        cells.push_back(row);
      }
      for (const auto& e : rec["engines"]) {
        std::vector<std::string> row = c;
        const std::vector<std::string> ecells = engine_cells(rec, e, format);
        row.insert(row.end(), ecells.begin() + 1, ecells.end());
        cells.push_back(row);
      }
    }
    return csv(cols, cells);
  }
  const ShadowTables t = shadow_tables(header, records, format);
  std::string out = captioned(t.caption, t.cascade_cols, t.cascades, format);
  if (!t.rendered.empty())
    out += "\n" + captioned(t.rendered_caption, t.rendered_cols, t.rendered, format);
  if (!t.engines.empty())  // a spot light has no engine conversions
    out += "\n" + captioned(t.engine_caption, t.engine_cols, t.engines, format);
  return out;
}

ShadowTables shadow_tables(const nlohmann::json& header, const std::vector<nlohmann::json>& records,
                           const std::string& format) {
  ShadowTables t;
  t.caption = caption(header);
  t.engine_caption = engine_caption(header);
  t.cascade_cols = named_by_light(cascade_columns(), header);
  t.engine_cols = engine_columns();
  t.rendered_caption = rendered_caption(header);
  t.rendered_cols = named_by_light(rendered_columns(), header);
  for (const auto& rec : records) {
    t.cascades.push_back(cascade_cells(rec, format));
    if (rec.contains("rendered")) t.rendered.push_back(rendered_cells(rec, format));
    for (const auto& e : rec["engines"]) t.engines.push_back(engine_cells(rec, e, format));
  }
  return t;
}

}  // namespace depthprec
