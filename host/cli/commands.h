// Subcommands of the depthprec executable. Each add_* registers its CLI11 subcommand and the
// callback that runs it; errors propagate as depthprec::Error to main's single handler.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host/cli/scene_options.h"

namespace depthprec::cli {

struct GlobalOptions {
  std::string device;  // --device, else $DEPTHPREC_DEVICE
  bool verbose = false;
  bool quiet = false;        // no progress line
  std::string command_line;  // as typed, for outputs that say how they were made
};

void add_devices_command(CLI::App& app, GlobalOptions& global);
void add_formats_command(CLI::App& app, GlobalOptions& global);
// mts and table.
void add_mts_commands(CLI::App& app, GlobalOptions& global);
// --gl-device, for the commands that render (render, compare).
void add_gl_device_option(CLI::App* cmd, std::string& choice);
void add_merge_command(CLI::App& app);
// lj, select, lj-table.
void add_lj_commands(CLI::App& app, GlobalOptions& global);
void add_resolve_command(CLI::App& app);
void add_readback_command(CLI::App& app);
void add_tradeoff_command(CLI::App& app, GlobalOptions& global);
void add_cost_command(CLI::App& app, GlobalOptions& global);
void add_plot_command(CLI::App& app);
void add_compare_command(CLI::App& app, GlobalOptions& global);
void add_pipelines_command(CLI::App& app, GlobalOptions& global);
void add_report_command(CLI::App& app, GlobalOptions& global);
void add_advise_command(CLI::App& app, GlobalOptions& global);
void add_world_command(CLI::App& app, GlobalOptions& global);
void add_audit_command(CLI::App& app, GlobalOptions& global);
void add_bias_command(CLI::App& app, GlobalOptions& global);
void add_shadow_command(CLI::App& app, GlobalOptions& global);
// cache show, cache clear.
void add_cache_command(CLI::App& app);

// The record batches (lj-table, tradeoff, cost, pipelines) render their output from a header (what
// their JSON output carries besides the records) and the records, so `merge` renders joined shards
// exactly as one run would.
std::string render_lj_table_output(const nlohmann::json& header,
                                   const std::vector<nlohmann::json>& records,
                                   const OutputOptions& out);
std::string render_tradeoff_output(const nlohmann::json& header,
                                   const std::vector<nlohmann::json>& records,
                                   const OutputOptions& out);
std::string render_pipelines_output(const nlohmann::json& header,
                                    const std::vector<nlohmann::json>& records,
                                    const OutputOptions& out);
std::string render_compare_output(const nlohmann::json& header,
                                  const std::vector<nlohmann::json>& records,
                                  const OutputOptions& out);
std::string render_cost_output(const nlohmann::json& header,
                               const std::vector<nlohmann::json>& records,
                               const OutputOptions& out);
std::string render_advise_output(const nlohmann::json& header,
                                 const std::vector<nlohmann::json>& records,
                                 const OutputOptions& out);
std::string render_world_output(const nlohmann::json& header,
                                const std::vector<nlohmann::json>& records,
                                const OutputOptions& out);
std::string render_bias_output(const nlohmann::json& header,
                               const std::vector<nlohmann::json>& records,
                               const OutputOptions& out);
std::string render_profiles_output(const nlohmann::json& header,
                                   const std::vector<nlohmann::json>& records,
                                   const OutputOptions& out);

}  // namespace depthprec::cli
