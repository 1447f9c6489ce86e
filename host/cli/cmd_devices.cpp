#include <fmt/format.h>

#include <memory>
#include <nlohmann/json.hpp>

#include "host/cli/commands.h"
#include "host/output/json_header.h"
#include "host/output/report.h"
#include "host/output/text_table.h"
#include "host/render/gl_context.h"
#include "host/runtime/opencl_runtime.h"

namespace depthprec::cli {

namespace {

void run_devices(const GlobalOptions& global, const OutputOptions& out) {
  check_writable(out.output);
  const auto devices = list_devices();
  std::string chosen, not_chosen;
  try {
    chosen = OpenClRuntime(global.device).description();
  } catch (const std::exception& e) {
    not_chosen = e.what();  // the list is still printed, then the selector's error
  }
  const bool csv_out = out.format_out == "csv";
  nlohmann::json j = output_header("devices", chosen);
  j["opencl_devices"] = nlohmann::json::array();
  Cells cells;
  for (const auto& d : devices) {
    const std::string desc =
        fmt::format("{} / {} ({})", d.platform_name, d.device_name, d.opencl_c_version);
    const double gib = static_cast<double>(d.global_mem_bytes) / (1024.0 * 1024.0 * 1024.0);
    const std::string pd = fmt::format("{}:{}", d.platform_index, d.device_index);
    cells.push_back({csv_out ? pd : (desc == chosen ? "*" : " ") + pd, d.device_type, d.device_name,
                     d.opencl_c_version, std::to_string(d.compute_units), d.fp64 ? "yes" : "no",
                     d.fp32_denormals ? "yes" : "no",
                     csv_out ? exact(gib) : fmt::format("{:.1f}", gib), d.platform_name,
                     d.platform_version, desc == chosen ? "yes" : ""});
    j["opencl_devices"].push_back({{"device", pd},
                                   {"type", d.device_type},
                                   {"name", d.device_name},
                                   {"opencl_c", d.opencl_c_version},
                                   {"compute_units", d.compute_units},
                                   {"fp64", d.fp64},
                                   {"fp32_denormals", d.fp32_denormals},
                                   {"global_mem_bytes", d.global_mem_bytes},
                                   {"platform", d.platform_name},
                                   {"platform_version", d.platform_version},
                                   {"chosen", desc == chosen}});
  }
  const std::vector<Column> cols = {{"P:D", true},
                                    {"type", true},
                                    {"device", true},
                                    {"OpenCL C", true},
                                    {"CUs"},
                                    {"fp64", true},
                                    {"denormals", true},
                                    {"mem GiB"},
                                    {"platform", true},
                                    {"platform version", true},
                                    {"chosen", true}};
  // The displays `render` and `compare` can use (--gl-device), with what each renders on.
  const auto displays = list_gl_displays();
  j["gl_displays"] = nlohmann::json::array();
  Cells gl;
  for (const auto& d : displays) {
    gl.push_back({d.choice, d.usable ? "yes" : "no", d.what});
    j["gl_displays"].push_back({{"choice", d.choice}, {"usable", d.usable}, {"what", d.what}});
  }
  std::string text;
  if (out.format_out == "json")
    text = j.dump(2) + "\n";
  else if (csv_out)
    text = csv(cols, cells);  // the OpenCL devices; the displays are in the JSON
  else {
    // The terminal gets the columns that tell devices apart; CSV and JSON have them all.
    const size_t shown = 9;
    for (auto& row : cells) row.resize(shown);
    text = captioned("OpenCL devices (* = the one depthprec uses: --device, $DEPTHPREC_DEVICE)",
                     {cols.begin(), cols.begin() + shown}, cells, out.format_out) +
           "\n" +
           captioned(
               "OpenGL through EGL, for render and compare (--gl-device; auto takes the "
               "first usable)",
               {{"--gl-device", true}, {"usable", true}, {"renders on", true}}, gl, out.format_out);
  }
  write_output(out.output, for_terminal(text, out.format_out));
  // A selector that matches nothing is what the user came to check: the list shows what there
  // is, and the exit code says the choice failed.
  if (!not_chosen.empty()) throw Error(ExitCode::runtime, not_chosen);
}

}  // namespace

void add_devices_command(CLI::App& app, GlobalOptions& global) {
  auto out = std::make_shared<OutputOptions>();
  auto* cmd = app.add_subcommand(
      "devices",
      "List OpenCL platforms and devices (the one depthprec would use is marked *), and the\n"
      "OpenGL displays render and compare can use (--gl-device).\n"
      "Example: depthprec devices");
  out->add_to(*cmd);
  cmd->callback([&global, out]() { run_devices(global, *out); });
}

}  // namespace depthprec::cli
