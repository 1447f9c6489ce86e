// resolve: code <-> eye distance queries on the exact mappings (host/model/resolve.h).
#include <fmt/format.h>

#include <cmath>
#include <cstdio>

#include "host/base/errors.h"
#include "host/base/json_number.h"
#include "host/cli/commands.h"
#include "host/model/resolve.h"
#include "host/model/storage_format.h"
#include "host/model/technique.h"
#include "host/output/json_header.h"
#include "host/output/report.h"
#include "host/output/text_table.h"

namespace depthprec::cli {

namespace {

struct ResolveOptions {
  std::string technique = "standard", format = "unorm24", rounding = "nearest_even";
  double near = 1, far = 100, log_k = 1;
  long long code = 0;
  double distance = 0;
  bool code_given = false, distance_given = false;  // by the option's count: any value is typed
  bool far_given = false;
  bool curve = false;
  int points = 50;
  OutputOptions out;
};

void run_resolve(const ResolveOptions& o) {
  ResolveSetup s;
  s.technique = parse_technique(o.technique);
  s.near = o.near;
  s.far = o.far;
  s.params.log_k = o.log_k;
  const StorageFormat f = StorageFormat::parse(o.format, parse_rounding(o.rounding));
  const int modes = (o.code_given ? 1 : 0) + (o.distance_given ? 1 : 0) + (o.curve ? 1 : 0);
  if (modes != 1)
    throw Error(ExitCode::usage, "resolve: give exactly one of --code N, --distance w or --curve");
  if (o.code_given && (o.code < 0 || o.code > static_cast<long long>(f.max_code())))
    throw InputError(fmt::format("--code {}: {}'s codes are the whole numbers 0 to {}", o.code,
                                 f.name(), f.max_code()));
  // A technique without a far plane maps depths without one: --far only ends --curve's range.
  const bool far_used = has_far_plane(s.technique) || o.curve;
  if (o.far_given && !far_used)
    std::fprintf(stderr,
                 "depthprec: note: --far %s: %s has no far plane, so its mapping ignores it\n",
                 human(o.far).c_str(), o.technique.c_str());
  check_writable(o.out.output);
  std::string text;
  const auto digits = [&o](double v) { return number_cell(v, o.out.format_out, "{:.10g}"); };
  // A code's missing neighbour (the first or last code): '-' and JSON null, not a gap of 0.
  const auto gap = [&o](double v) {
    if (std::isnan(v)) return std::string(o.out.format_out == "csv" ? "" : "-");
    return number_cell(v, o.out.format_out);
  };
  const auto gap_json = [](double v) { return std::isnan(v) ? nlohmann::json() : json_number(v); };
  // JSON: the set-up and the rows with every value a JSON number (json_number).
  nlohmann::json j = output_header("resolve", "");
  j.update({{"technique", o.technique},
            {"format", f.name()},
            {"rounding", o.rounding},
            {"near", json_number(s.near)},
            {"far", json_number(s.far)},
            {"rows", nlohmann::json::array()}});
  j.erase("device");  // exact mappings on the host: no device
  if (!far_used) j.erase("far");
  if (o.code_given) {
    const CodeInterval ci = resolve_code(s, f, static_cast<uint32_t>(o.code));
    j["rows"].push_back({{"code", ci.code},
                         {"depth", json_number(ci.depth)},
                         {"distance", json_number(ci.distance)},
                         {"distance_lo", json_number(ci.distance_lo)},
                         {"distance_hi", json_number(ci.distance_hi)},
                         {"width", json_number(ci.distance_hi - ci.distance_lo)}});
    text = render_cells(
        {{"code"}, {"depth"}, {"distance"}, {"distance_lo"}, {"distance_hi"}, {"width"}},
        {{std::to_string(ci.code), digits(ci.depth), digits(ci.distance), digits(ci.distance_lo),
          digits(ci.distance_hi), gap(ci.distance_hi - ci.distance_lo)}},
        o.out.format_out);
  } else {
    std::vector<DistanceResolution> rows;
    if (o.curve)
      rows = resolution_curve(s, f, o.points);
    else
      rows.push_back(resolve_distance(s, f, o.distance));
    Cells cells;
    for (const auto& r : rows)
      j["rows"].push_back({{"distance", json_number(r.distance)},
                           {"depth", json_number(r.depth)},
                           {"code", r.code},
                           {"gap_below", gap_json(r.gap_below)},
                           {"gap_above", gap_json(r.gap_above)},
                           {"resolution", json_number(r.resolution)}});
    for (const auto& r : rows)
      cells.push_back({digits(r.distance), digits(r.depth), std::to_string(r.code),
                       gap(r.gap_below), gap(r.gap_above), gap(r.resolution)});
    text = render_cells(
        {{"distance"}, {"depth"}, {"code"}, {"gap_below"}, {"gap_above"}, {"resolution"}}, cells,
        o.out.format_out);
  }
  if (o.out.format_out == "json") text = j.dump(2) + "\n";
  if (o.out.format_out == "text")
    text = fmt::format("{} in {} ({}), near {}, {}:\n", o.technique, f.name(), o.rounding,
                       human(s.near),
                       has_far_plane(s.technique) ? "far " + human(s.far)
                       : o.curve                  ? "no far plane, the curve up to " + human(s.far)
                                                  : "no far plane") +
           text;
  write_output(o.out.output, text);
}

}  // namespace

void add_resolve_command(CLI::App& app) {
  auto res = std::make_shared<ResolveOptions>();
  auto* rcmd = app.add_subcommand(
      "resolve",
      "Code <-> eye distance: which distances a stored code stands for (--code), which code a\n"
      "distance gets and the gap to its neighbours (--distance), or the resolution across the\n"
      "range (--curve). Exact mappings; no emulated arithmetic.\n"
      "Examples:\n"
      "  depthprec resolve --technique standard --format unorm16 --near 0.01 --far 1000 --code 1\n"
      "  depthprec resolve --technique reversed --format float32 --near 0.1 --far 1e4 --distance "
      "5000\n"
      "  depthprec resolve --technique reversed_infinite --format float32 --near 0.1 --far 1e4 "
      "--curve");
  rcmd->add_option("-t,--technique", res->technique, "Technique: " + technique_names())
      ->capture_default_str();
  rcmd->add_option("-f,--format", res->format, "Storage format")->capture_default_str();
  rcmd->add_option("--near", res->near, "Near plane")->capture_default_str();
  CLI::Option* far =
      rcmd->add_option("--far", res->far,
                       "Far plane (for infinite, reversed_infinite and inverse_w, which have none: "
                       "the end of --curve's range)")
          ->capture_default_str();
  rcmd->add_option("--log-k", res->log_k, "k of the log techniques")->capture_default_str();
  rcmd->add_option("--rounding", res->rounding, "nearest_even or truncate")->capture_default_str();
  CLI::Option* code =
      rcmd->add_option("--code", res->code, "A stored code: 0 to the format's largest");
  CLI::Option* distance = rcmd->add_option("--distance", res->distance, "An eye distance");
  rcmd->add_flag("--curve", res->curve,
                 "Resolution at --points distances, geometric from near to far");
  rcmd->add_option("--points", res->points, "Points of --curve")->capture_default_str();
  res->out.add_to(*rcmd);
  rcmd->callback([res, code, distance, far]() {
    res->far_given = far->count() > 0;
    res->code_given = code->count() > 0;
    res->distance_given = distance->count() > 0;
    run_resolve(*res);
  });
}

}  // namespace depthprec::cli
