// lj, select and lj-table: the Lapidous-Jiao metric.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

#include "host/analysis/lj_tables.h"
#include "host/base/errors.h"
#include "host/base/json_number.h"
#include "host/base/version.h"
#include "host/cli/commands.h"
#include "host/cli/record_batch.h"
#include "host/cli/scene_options.h"
#include "host/lj/lj_metric.h"
#include "host/lj/lj_pipeline.h"
#include "host/model/resolve.h"
#include "host/model/storage_format.h"
#include "host/output/gnuplot.h"
#include "host/output/json_header.h"
#include "host/output/plots.h"
#include "host/output/report.h"
#include "host/output/text_table.h"

namespace depthprec::cli {

namespace {

struct LjOptions {
  std::string buffer = "z", format = "unorm16", sampling = "uniform", rounding = "nearest_even";
  double near = 1, far = 100;
  long long samples = 1000000;
  int bits = 16;
  OutputOptions out;
  std::string plot;
  BatchOptions batch;

  LjConfig config() const {
    LjConfig c;
    c.buffer = parse_lj_buffer(buffer);
    c.near = near;
    c.far = far;
    c.samples = samples;
    c.sampling = parse_lj_sampling(sampling);
    validate(c);
    return c;
  }
};

void add_lj_common(CLI::App* cmd, LjOptions& o, bool with_buffer) {
  if (with_buffer)
    cmd->add_option("--buffer", o.buffer, "z, w, inverse_w or complementary_z")
        ->capture_default_str();
  cmd->add_option("--near", o.near, "Near plane distance d")->capture_default_str();
  cmd->add_option("--far", o.far, "Far plane distance f")->capture_default_str();
  cmd->add_option("--samples", o.samples, "N sampled distances from d to f, both ends included")
      ->capture_default_str();
  cmd->add_option("--sampling", o.sampling, "uniform, or increasing (weight Ze - d)")
      ->capture_default_str();
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void run_lj(const LjOptions& o, const GlobalOptions& g) {
  const LjConfig c = o.config();
  const StorageFormat f = StorageFormat::parse(o.format, parse_rounding(o.rounding));
  check_writable(o.out.output);
  auto t0 = std::chrono::steady_clock::now();
  const LjResult host = lj_average_error(c, f);
  const double host_ms = ms_since(t0);
  OpenClRuntime rt(g.device);
  lj_average_error_device(rt, c, f);  // builds the program: compile time is not compute time
  t0 = std::chrono::steady_clock::now();
  const LjResult dev = lj_average_error_device(rt, c, f);
  const double dev_ms = ms_since(t0);
  Pipeline pipeline;
  pipeline.depth_range = DepthRange::zero_to_one;
  pipeline.rounding = f.rounding();
  t0 = std::chrono::steady_clock::now();
  const LjPipelineResult pipe = lj_pipeline_error(c, f, pipeline);
  const double pipe_ms = ms_since(t0);
  const bool timing = !o.out.no_timing;
  std::string text;
  if (o.out.format_out == "json") {
    nlohmann::json j = output_header("lj", rt.description());
    j.update({{"buffer", o.buffer},
              {"format", f.name()},
              {"near", c.near},
              {"far", c.far},
              {"samples", c.samples},
              {"sampling", o.sampling},
              {"rounding", o.rounding},
              {"ae_host", json_number(host.ae)},
              {"ae_device", json_number(dev.ae)},
              {"ae_pipeline", json_number(pipe.ae)},
              {"vertex_limited_fraction", host.vertex_limited},
              {"infinite_samples", host.infinite_samples},
              {"pipeline_clipped_samples", pipe.clipped},
              {"pipeline_off_code_samples", pipe.off_code}});
    if (timing) j["ms"] = {{"host", host_ms}, {"device", dev_ms}, {"pipeline", pipe_ms}};
    text = j.dump(2) + "\n";
  } else {
    const std::string& fmt_out = o.out.format_out;
    const auto num = [&fmt_out](double v) { return number_cell(v, fmt_out); };
    const auto ms = [&fmt_out](double v) { return number_cell(v, fmt_out, "{:.1f}"); };
    std::vector<Column> cols = {{"metric", true}, {"ae"}};
    if (timing) cols.push_back({"ms"});
    cols.push_back({"notes", true});
    Cells cells = {
        {"analytic, host binary64", num(host.ae), ms(host_ms),
         fmt::format("per-vertex term limits {:.1f} % of samples{}", 100 * host.vertex_limited,
                     host.infinite_samples
                         ? fmt::format("; {} samples past the Z pole", host.infinite_samples)
                         : "")},
        {"analytic, device binary64", num(dev.ae), ms(dev_ms), rt.info().device_name},
        {"pipeline-measured", num(pipe.ae), ms(pipe_ms),
         fmt::format("{} samples stored off the exact code, {} clipped", pipe.off_code,
                     pipe.clipped)}};
    if (!timing)
      for (auto& row : cells) row.erase(row.begin() + 2);
    text =
        captioned(fmt::format("Lapidous-Jiao average error: {} buffer, {} ({} storage rounding), "
                              "near {}, far {} (f/d {}), N = {}, {} sampling",
                              o.buffer, f.name(), o.rounding, human(c.near), human(c.far),
                              human(c.far / c.near), c.samples, o.sampling),
                  cols, cells, fmt_out);
  }
  write_output(o.out.output, for_terminal(text, o.out.format_out));
}

void run_select(const LjOptions& o, const GlobalOptions& g) {
  const LjConfig c = o.config();
  if (o.bits < 2 || o.bits > 32)
    throw InputError(fmt::format("--bits must be 2..32, not {}", o.bits));
  check_writable(o.out.output);
  OpenClRuntime rt(g.device);
  auto ranked = sweep(rt, c, o.bits);
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const Ranked& a, const Ranked& b) { return a.ae < b.ae; });
  std::string text;
  const double best = ranked.front().ae;
  // x best where no format has a finite error is none: inf / inf is no ratio
  const bool ranked_by_error = std::isfinite(best);
  if (o.out.format_out == "json") {
    nlohmann::json j = output_header("select", rt.description());
    j.update({{"buffer", o.buffer},
              {"bits", o.bits},
              {"near", c.near},
              {"far", c.far},
              {"samples", c.samples},
              {"sampling", o.sampling},
              {"ranking", nlohmann::json::array()}});
    int rank = 1;
    for (const auto& r : ranked)
      j["ranking"].push_back(
          {{"rank", rank++},
           {"format", r.format},
           {"E", r.e},
           {"M", o.bits - r.e},
           {"ae", json_number(r.ae)},
           {"x_best", ranked_by_error ? json_number(r.ae / best) : nlohmann::json()}});
    text = j.dump(2) + "\n";
  } else {
    Cells cells;
    int rank = 1;
    for (const auto& r : ranked)
      cells.push_back({std::to_string(rank++), r.format, std::to_string(r.e),
                       std::to_string(o.bits - r.e), number_cell(r.ae, o.out.format_out),
                       ranked_by_error             ? number_cell(r.ae / best, o.out.format_out)
                       : o.out.format_out == "csv" ? ""
                                                   : "-"});
    text = captioned(
        fmt::format("Best {}-bit storage for the {} buffer, near {}, far {} ({} sampling, N = {}):",
                    o.bits, o.buffer, human(c.near), human(c.far), o.sampling, c.samples),
        {{"rank"}, {"format", true}, {"E"}, {"M"}, {"ae"}, {"x best"}}, cells, o.out.format_out);
    if (!ranked_by_error && o.out.format_out == "text")
      text += fmt::format(
          "No {}-bit format gives the {} buffer a finite average error over [{}, {}]: past its Z "
          "pole the stored code no longer separates distances. Fewer decades (f/d), more bits or "
          "another buffer (depthprec lj says for how many samples).\n",
          o.bits, o.buffer, human(c.near), human(c.far));
  }
  write_output(o.out.output, for_terminal(text, o.out.format_out));
}

// The index of the best exponent width of an ae row, and whether E = 0 and E = 1 tie: LJ99 eq. 2
// makes them one integer format, and unorm's 1/(2^b - 1) spacing differs from e1's 2^-b by 2^-b
// relative.
struct BestE {
  size_t e = 0;
  bool integer_tie = false;
};
BestE best_exponent(const std::vector<double>& ae, int bits) {
  BestE b;
  for (size_t k = 0; k < ae.size(); ++k)
    if (ae[k] < ae[b.e]) b.e = k;
  b.integer_tie = b.e <= 1 && std::abs(ae[0] - ae[1]) <= std::ldexp(2.0, -bits) * ae[1];
  return b;
}

std::vector<double> ae_of(const std::map<std::string, nlohmann::json>& records,
                          const std::string& key) {
  std::vector<double> v;
  for (const auto& x : records.at(key).at("ae")) v.push_back(number_from_json(x, key + " ae"));
  return v;
}

// CSV: one line per (table, sampling, buffer, f/d, format), exact values, so the tables that text
// and Markdown print side by side are one relation a reader can filter.
std::string lj_table_csv(const std::map<std::string, nlohmann::json>& records) {
  Cells cells;
  for (const char* sampling : kLjSamplings)
    for (int bits : kLjBits)
      for (const LjBuffer b : kLjBuffers)
        for (double r : kLjRatios) {
          const std::string key = split_key(sampling, bits, b, r);
          if (!records.count(key)) continue;
          const auto ae = ae_of(records, key);
          const BestE best = best_exponent(ae, bits);
          for (size_t e = 0; e < ae.size(); ++e) {
            const bool is_best =
                !std::isinf(ae[best.e]) && (e == best.e || (best.integer_tie && e <= 1));
            cells.push_back({"exponent_sweep", sampling, to_string(b), exact(r),
                             e == 0 ? fmt::format("unorm{}", bits)
                                    : fmt::format("e{}m{}", e, bits - static_cast<int>(e)),
                             std::to_string(bits), std::to_string(e), exact(ae[e]),
                             is_best ? "yes" : ""});
          }
        }
  for (double r : kLjRatios) {
    if (!records.count(picks_key(r))) continue;
    const auto ae = ae_of(records, picks_key(r));
    for (size_t k = 0; k < ae.size(); ++k) {
      const StorageFormat f = StorageFormat::parse(kLjPicks[k].format);
      cells.push_back({"32bit_comparison", "uniform", to_string(kLjPicks[k].buffer), exact(r),
                       f.name(), std::to_string(f.bits()), "", exact(ae[k]), ""});
    }
  }
  return csv({{"table"},
              {"sampling"},
              {"buffer"},
              {"f/d"},
              {"format"},
              {"bits"},
              {"E"},
              {"ae"},
              {"best_E"}},
             cells);
}

// The tables from whatever records there are (a shard or an interrupted run has some rows).
std::string render_lj_table(const std::map<std::string, nlohmann::json>& records, long long samples,
                            const std::string& format) {
  if (format == "csv") return lj_table_csv(records);
  const bool md = format == "markdown";
  std::string text = md ? "# Lapidous-Jiao average depth error: the paper's experiments\n\n" : "";
  text += fmt::format(
      "ae per exponent width E (E = 0: integer unorm<bits>; E >= 1: LJ e<E>m<bits-E>), near 1, "
      "N = {} samples. inf: a sample passes the Z buffer's pole. best E 0/1: the integer "
      "format (LJ99 eq. 2 makes E = 0 and E = 1 the same; unorm's codes are 2^-bits relatively "
      "wider apart).\n",
      samples);
  for (const char* sampling : kLjSamplings) {
    for (int bits : kLjBits) {
      for (const LjBuffer b : kLjBuffers) {
        std::vector<Column> cols = {{"f/d"}};
        for (int e = 0; e <= 8; ++e) cols.push_back({fmt::format("E={}", e)});
        cols.push_back({"best E"});
        Cells cells;
        for (double r : kLjRatios) {
          const std::string key = split_key(sampling, bits, b, r);
          if (!records.count(key)) continue;
          const auto ae = ae_of(records, key);
          std::vector<std::string> row = {human(r)};
          for (double v : ae) row.push_back(human(v));
          const BestE best = best_exponent(ae, bits);
          row.push_back(std::isinf(ae[best.e]) ? "-"
                        : best.integer_tie     ? "0/1"
                                               : std::to_string(best.e));
          cells.push_back(row);
        }
        if (cells.empty()) continue;
        text += fmt::format("\n{}{}-bit {} buffer, {} sampling\n\n", md ? "## " : "", bits,
                            to_string(b), sampling);
        text += render_cells(cols, cells, format);
      }
    }
  }
  std::vector<Column> cols = {{"f/d"}};
  for (const auto& p : kLjPicks)
    cols.push_back({fmt::format("{} {}", to_string(p.buffer), p.format)});
  Cells cells;
  for (double r : kLjRatios) {
    if (!records.count(picks_key(r))) continue;
    std::vector<std::string> row = {human(r)};
    for (double ae : ae_of(records, picks_key(r))) row.push_back(human(ae));
    cells.push_back(row);
  }
  if (!cells.empty()) {
    text += fmt::format(
        "\n{}32-bit comparisons (LJ99 fig. 11), uniform sampling; e4m24 is the paper's 28-bit "
        "\"24.4\" format\n\n",
        md ? "## " : "");
    text += render_cells(cols, cells, format);
  }
  return text;
}

}  // namespace

std::string render_lj_table_output(const nlohmann::json& header,
                                   const std::vector<nlohmann::json>& records,
                                   const OutputOptions& out) {
  if (out.format_out == "json") return records_json(header, records, !out.no_timing);
  return render_lj_table(by_key(records), header.at("samples").get<long long>(), out.format_out);
}

namespace {

// One unit per table row, so an interrupted run keeps every finished row.
std::vector<BatchUnit> lj_table_units(OpenClRuntime& rt, long long samples) {
  std::vector<BatchUnit> units;
  auto aes = [](const std::vector<double>& v) {
    nlohmann::json a = nlohmann::json::array();
    for (double x : v) a.push_back(json_number(x));
    return nlohmann::json{{"ae", a}};
  };
  for (const char* sampling : kLjSamplings)
    for (int bits : kLjBits)
      for (const LjBuffer b : kLjBuffers)
        for (double r : kLjRatios)
          units.push_back(
              {split_key(sampling, bits, b, r), [&rt, samples, sampling, bits, b, r, aes] {
                 std::vector<double> v;
                 for (const auto& x :
                      sweep(rt, table_config(b, r, samples, parse_lj_sampling(sampling)), bits))
                   v.push_back(x.ae);
                 return aes(v);
               }});
  for (double r : kLjRatios)
    units.push_back({picks_key(r), [&rt, samples, r, aes] {
                       std::vector<double> v;
                       for (const auto& p : kLjPicks)
                         v.push_back(lj_average_error_device(
                                         rt,
                                         table_config(p.buffer, r, samples, LjSampling::uniform),
                                         StorageFormat::parse(p.format))
                                         .ae);
                       return aes(v);
                     }});
  return units;
}

void run_lj_table(const LjOptions& o, const GlobalOptions& g) {
  check_writable(o.out.output);
  check_plot_output(o.plot);
  const auto records = run_record_batch(
      "lj-table", o.out, o.batch, g,
      [&o](OpenClRuntime& rt, nlohmann::json& header) {
        header["samples"] = o.samples;
        return lj_table_units(rt, o.samples);
      },
      render_lj_table_output);
  if (!o.plot.empty()) plot_lj_table(by_key(records), o.plot);
}

}  // namespace

void add_lj_commands(CLI::App& app, GlobalOptions& global) {
  auto lj = std::make_shared<LjOptions>();
  auto* cmd = app.add_subcommand(
      "lj",
      "Lapidous-Jiao average depth error (LJ99 eqs. 6-7, docs/spec.md 6) of a buffer type and "
      "storage\n"
      "format: analytic in binary64 on the host and on the device, and measured on the emulated\n"
      "binary32 pipeline. ae is the average eye-distance error normalised by (f - d).\n"
      "Examples:\n"
      "  depthprec lj --buffer z --format unorm16 --near 1 --far 100\n"
      "  depthprec lj --buffer complementary_z --format e4m12 --far 1000 --sampling increasing\n"
      "  depthprec lj --buffer inverse_w --format float32 --far 1e4 --format-out json");
  add_lj_common(cmd, *lj, true);
  cmd->add_option("-f,--format", lj->format, "Storage format")->capture_default_str();
  cmd->add_option("--rounding", lj->rounding, "nearest_even or truncate")->capture_default_str();
  lj->out.add_to(*cmd);  // the output's options last, as every command lists them
  cmd->callback([lj, &global]() { run_lj(*lj, global); });

  auto sel = std::make_shared<LjOptions>();
  auto* scmd = app.add_subcommand(
      "select",
      "LJ99's driver-side format choice: every split of --bits into exponent E and mantissa\n"
      "(E = 0 is the integer format), ranked by the Lapidous-Jiao average error.\n"
      "Examples:\n"
      "  depthprec select --buffer inverse_w --bits 16 --far 500\n"
      "  depthprec select --buffer complementary_z --bits 24 --far 1e4 --sampling increasing");
  add_lj_common(scmd, *sel, true);
  scmd->add_option("--bits", sel->bits, "Buffer size in bits (2..32)")->capture_default_str();
  sel->out.add_to(*scmd);
  scmd->callback([sel, &global]() { run_select(*sel, global); });

  auto tab = std::make_shared<LjOptions>();
  auto* tcmd = app.add_subcommand(
      "lj-table",
      "The paper's experiments: for 16 and 24 bits, each buffer type and f/d from 2 to 1e6, ae "
      "per\n"
      "exponent width and the best one; and the 32-bit comparisons (LJ99 fig. 11).\n"
      "Example:\n"
      "  depthprec lj-table --format-out markdown -o lj-tables.md");
  tcmd->add_option("--samples", tab->samples, "N samples per evaluation")->capture_default_str();
  tab->out.add_to(*tcmd);
  tcmd->add_option("--plot", tab->plot,
                   "Also plot ae against f/d per format, 16 bits (gnuplot), FILE.png or FILE.svg");
  tab->batch.add_to(*tcmd, "table rows (k in output order)");
  tcmd->callback([tab, &global]() { run_lj_table(*tab, global); });
}

}  // namespace depthprec::cli
