#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <vector>

#include "host/base/errors.h"
#include "host/base/json_number.h"
#include "host/cli/commands.h"
#include "host/model/storage_format.h"
#include "host/output/json_header.h"
#include "host/output/report.h"
#include "host/output/text_table.h"
#include "host/runtime/device_encode.h"
#include "host/runtime/opencl_runtime.h"

namespace depthprec::cli {

namespace {

struct FormatsOptions {
  std::vector<std::string> names{"unorm16", "unorm24", "unorm32", "float16",
                                 "float24", "float32", "e4m12",   "e3m13"};
  std::string rounding = "nearest_even";
  std::string denormals = "keep";
  std::vector<double> values;
  bool on_device = false;
  OutputOptions out;
};

std::vector<StorageFormat> parse_formats(const FormatsOptions& o) {
  const Rounding rounding = parse_rounding(o.rounding);
  const Denormals denormals = parse_denormals(o.denormals);
  std::vector<StorageFormat> formats;
  for (const auto& n : o.names) formats.push_back(StorageFormat::parse(n, rounding, denormals));
  return formats;
}

// A depth buffer holds window depths in [0, 1] (the pipeline clamps or clips the rest), so a
// value outside is not a depth: refused rather than stored as the nearest end.
void check_depth_values(const std::vector<double>& values) {
  for (double v : values)
    if (!(v >= 0.0 && v <= 1.0))
      throw InputError(fmt::format("--value {}: depth values are in [0, 1]", v));
}

Cells describe_formats(const std::vector<StorageFormat>& formats, const std::string& out,
                       nlohmann::json& j) {
  const auto g7 = [&out](double v) { return number_cell(v, out, "{:.7g}"); };
  Cells fcells;
  for (const auto& f : formats) {
    const unsigned long long codes = static_cast<unsigned long long>(f.max_code()) + 1;
    fcells.push_back({f.name(), std::to_string(f.bits()), g7(f.smallest_positive()),
                      number_cell(f.largest(), out, "{:.10g}"), g7(f.spacing_at(0.5)),
                      std::to_string(codes)});
    j["formats"].push_back({{"format", f.name()},
                            {"bits", f.bits()},
                            {"smallest_positive", json_number(f.smallest_positive())},
                            {"largest", json_number(f.largest())},
                            {"spacing_at_half", json_number(f.spacing_at(0.5))},
                            {"codes", codes}});
  }
  return fcells;
}

std::vector<std::string> round_trip(const StorageFormat& f, double v, bool underflow,
                                    OpenClRuntime* rt, const std::string& out, nlohmann::json* t) {
  const float d = static_cast<float>(v);
  const uint32_t code = f.encode(d);
  const double stored = f.decode(code);
  const double rel = underflow   ? (stored - v) / v
                     : d != 0.0f ? (stored - static_cast<double>(d)) / static_cast<double>(d)
                                 : 0.0;
  std::vector<std::string> row = {f.name(),
                                  number_cell(v, out, "{:.17g}"),
                                  fmt::format("{:.17g}", d),
                                  std::to_string(code),
                                  fmt::format("{:#x}", code),
                                  fmt::format("{:.17g}", stored),
                                  number_cell(rel, out, "{:.3e}")};
  *t = {{"format", f.name()}, {"value", json_number(v)},       {"depth", json_number(d)},
        {"code", code},       {"stored", json_number(stored)}, {"rel_error", json_number(rel)}};
  if (rt) {
    const uint32_t dev = device_encode(*rt, f, std::vector<float>{d}).front();
    if (dev != code)
      throw Error(ExitCode::internal,
                  fmt::format("{} encodes {} as {} on the host but {} on the device", f.name(), d,
                              code, dev));
    row.push_back("agrees");
    (*t)["device_code"] = dev;
  }
  return row;
}

struct RoundTrips {
  Cells cells;
  std::vector<std::string> notes;
};

RoundTrips round_trips(const std::vector<StorageFormat>& formats, const std::vector<double>& values,
                       OpenClRuntime* rt, const std::string& out, nlohmann::json& j) {
  RoundTrips trips;
  for (double v : values) {
    // A value below binary32's smallest positive is 0 as a depth before any format stores it:
    // all of it is lost (relative error -1), which an error relative to d = 0 would hide as 0.
    const bool underflow = static_cast<float>(v) == 0.0f && v != 0.0;
    if (underflow)
      trips.notes.push_back(fmt::format(
          "--value {}: below binary32's smallest positive value ({:g}), it is 0 as a depth before "
          "any format stores it: relative error -1",
          v, static_cast<double>(std::numeric_limits<float>::denorm_min())));
    for (const auto& f : formats) {
      nlohmann::json t;
      trips.cells.push_back(round_trip(f, v, underflow, rt, out, &t));
      j["round_trips"].push_back(t);
    }
  }
  return trips;
}

std::string formats_text(const FormatsOptions& o, const nlohmann::json& j, const Cells& fcells,
                         const RoundTrips& trips, bool on_device) {
  const std::string& out = o.out.format_out;
  const std::vector<Column> fcols = {{"format", true}, {"bits"},        {"smallest>0"},
                                     {"largest"},      {"spacing@0.5"}, {"codes"}};
  std::vector<Column> rcols = {{"format", true}, {"value"},  {"d (binary32)"}, {"code"},
                               {"code (hex)"},   {"stored"}, {"rel. error"}};
  if (on_device) rcols.push_back({"device", true});
  if (out == "json") return j.dump(2) + "\n";
  // One table per CSV: the round trips when values are given, else the formats.
  if (out == "csv") return trips.cells.empty() ? csv(fcols, fcells) : csv(rcols, trips.cells);
  std::string text =
      captioned(fmt::format("storage formats (rounding {}, denormals {})", o.rounding, o.denormals),
                fcols, fcells, out);
  if (!trips.cells.empty())
    text +=
        "\n" + captioned(fmt::format("round trip: value -> binary32 depth d -> code -> stored "
                                     "value{}",
                                     on_device ? " (code also computed by the OpenCL kernel)" : ""),
                         rcols, trips.cells, out);
  for (const auto& note : trips.notes) text += (out == "markdown" ? "\n" : "") + note + "\n";
  return text;
}

void run_formats(const FormatsOptions& o, const GlobalOptions& global) {
  const std::vector<StorageFormat> formats = parse_formats(o);
  check_depth_values(o.values);
  check_writable(o.out.output);
  nlohmann::json j = output_header("formats", "");
  j.erase("device");  // described on the host; --on-device adds the device below
  j.update({{"rounding", o.rounding}, {"denormals", o.denormals}});
  const Cells fcells = describe_formats(formats, o.out.format_out, j);
  std::unique_ptr<OpenClRuntime> rt;
  if (o.on_device && !o.values.empty()) {
    rt = std::make_unique<OpenClRuntime>(global.device);
    j["device"] = rt->description();
  }
  const RoundTrips trips = round_trips(formats, o.values, rt.get(), o.out.format_out, j);
  const std::string text = formats_text(o, j, fcells, trips, rt != nullptr);
  write_output(o.out.output, for_terminal(text, o.out.format_out));
}

}  // namespace

void add_formats_command(CLI::App& app, GlobalOptions& global) {
  auto opts = std::make_shared<FormatsOptions>();
  auto* cmd = app.add_subcommand(
      "formats",
      "Describe storage formats and round-trip values through them.\n"
      "Formats: unorm<b> (b = 1..32), float16, float24, float32 (IEEE-style), e<E>m<M>\n"
      "(Lapidous-Jiao eq. 2: no sign, bias 2^E, values in [0,1)).\n"
      "Examples:\n"
      "  depthprec formats\n"
      "  depthprec formats unorm24 float32 --value 0.999 --on-device\n"
      "  depthprec formats e4m12 --value 1e-3 --rounding truncate");
  cmd->add_option("names", opts->names, "Formats to describe (default: a representative set)");
  cmd->add_option("--value", opts->values, "Depth value(s) in [0,1] to round-trip");
  cmd->add_option("--rounding", opts->rounding, "nearest_even (default) or truncate");
  cmd->add_option("--denormals", opts->denormals, "keep (default) or flush");
  cmd->add_flag("--on-device", opts->on_device,
                "Also encode on the OpenCL device and check it agrees with the host");
  opts->out.add_to(*cmd);
  cmd->callback([opts, &global]() { run_formats(*opts, global); });
}

}  // namespace depthprec::cli
