#include <fmt/format.h>

#include "host/cli/commands.h"
#include "host/render/gl_context.h"
#include "host/runtime/opencl_runtime.h"

namespace depthprec::cli {

void add_devices_command(CLI::App& app, GlobalOptions& global) {
  auto* cmd = app.add_subcommand(
      "devices",
      "List OpenCL platforms and devices (the one depthprec would use is marked *), and the\n"
      "OpenGL displays render and compare can use (--gl-device).\n"
      "Example: depthprec devices");
  cmd->callback([&global]() {
    const auto devices = list_devices();
    std::string chosen;
    try {
      chosen = OpenClRuntime(global.device).description();
    } catch (const std::exception&) {
      chosen.clear();  // listing still works when the selector matches nothing
    }
    fmt::print("{:<5} {:<6} {:<42} {:<22} {:>3} {:>5} {:>9} {:>8}\n", "P:D", "type", "device",
               "OpenCL C", "CUs", "fp64", "denormals", "mem GiB");
    for (const auto& d : devices) {
      const std::string desc =
          fmt::format("{} / {} ({})", d.platform_name, d.device_name, d.opencl_c_version);
      fmt::print(
          "{:<5} {:<6} {:<42} {:<22} {:>3} {:>5} {:>9} {:>8.1f}\n",
          fmt::format("{}{}:{}", desc == chosen ? "*" : " ", d.platform_index, d.device_index),
          d.device_type, d.device_name.substr(0, 42), d.opencl_c_version, d.compute_units,
          d.fp64 ? "yes" : "no", d.fp32_denormals ? "yes" : "no",
          static_cast<double>(d.global_mem_bytes) / (1024.0 * 1024.0 * 1024.0));
      fmt::print("      platform: {} ({})\n", d.platform_name, d.platform_version);
    }
    // The displays `render` and `compare` can use (--gl-device), with what each renders on.
    fmt::print(
        "\nOpenGL through EGL, for render and compare (--gl-device; auto takes the first):\n");
    for (const auto& d : list_gl_displays())
      fmt::print("  {:<12} {}{}\n", d.choice, d.usable ? "" : "unavailable: ", d.what);
  });
}

}  // namespace depthprec::cli
