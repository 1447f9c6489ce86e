// Subcommands of the depthprec executable. Each add_* registers its CLI11 subcommand and the
// callback that runs it; errors propagate as depthprec::Error to main's single handler.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace depthprec::cli {

struct GlobalOptions {
  std::string device;  // --device, else $DEPTHPREC_DEVICE
  bool verbose = false;
  bool quiet = false;  // no progress line
};

void add_devices_command(CLI::App& app, GlobalOptions& global);
void add_formats_command(CLI::App& app, GlobalOptions& global);
// mts, table and merge.
void add_mts_commands(CLI::App& app, GlobalOptions& global);
// lj, select, lj-table, resolve.
void add_lj_commands(CLI::App& app, GlobalOptions& global);
void add_tradeoff_command(CLI::App& app, GlobalOptions& global);
void add_cost_command(CLI::App& app, GlobalOptions& global);
void add_plot_command(CLI::App& app);

}  // namespace depthprec::cli
