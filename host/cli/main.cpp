#include <fmt/format.h>
#include <fmt/ranges.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <sstream>

#include "host/base/did_you_mean.h"
#include "host/base/errors.h"
#include "host/base/fatal_signal.h"
#include "host/base/version.h"
#include "host/cli/commands.h"
#include "host/output/report.h"
#include "host/runtime/cl.h"

namespace {

// An option takes one value per occurrence (a list is comma-separated, or the option repeated):
// CLI11's lists otherwise take every word after them, so in `mts -t reversed scene.json` the
// scene was read as a technique. Positionals (merge's files) keep taking several.
void one_value_per_option(CLI::App& app) {
  for (CLI::Option* o : app.get_options())
    if (o->nonpositional()) o->allow_extra_args(false);
  for (CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    one_value_per_option(*sub);
}

// Runs the command line; returns the exit code.
int run(int argc, char** argv) {
  using namespace depthprec;
  install_fatal_signal_report();  // a crash (a damaged kernel cache, say) is said in words
  CLI::App app{fmt::format(
      "depthprec {} - how much depth precision a depth-buffer set-up gives.\n"
      "Emulates per fragment what a GPU computes and stores (OpenCL on PoCL) and measures the\n"
      "minimum triangle separation (Gilg et al. 2021) and the Lapidous-Jiao average depth error.\n"
      "Exit codes: 0 ok, 1 internal error, 2 usage, 3 bad input, 4 OpenCL device/runtime (a\n"
      "crash in the driver too: see `depthprec cache`), 5 output not writable, 130 interrupted.",
      kVersion)};
  app.set_version_flag("--version", kVersion);
  app.require_subcommand(1);
  app.fallthrough();  // --device, -v, -q work after the subcommand too
  cli::GlobalOptions global;
  app.add_option("--device", global.device,
                 "OpenCL device: P:D as `depthprec devices` lists, or part of its name "
                 "(default: $DEPTHPREC_DEVICE, else the PoCL CPU device)");
  app.add_flag("-v,--verbose", global.verbose, "Say which kernel variants were built");
  app.add_flag("-q,--quiet", global.quiet,
               "No progress line on stderr (it appears only on a terminal)");
  cli::add_devices_command(app, global);
  cli::add_formats_command(app, global);
  cli::add_mts_commands(app, global);
  cli::add_merge_command(app);
  cli::add_lj_commands(app, global);
  cli::add_resolve_command(app);
  cli::add_readback_command(app);
  cli::add_tradeoff_command(app, global);
  cli::add_cost_command(app, global);
  cli::add_pipelines_command(app, global);
  cli::add_plot_command(app);
  cli::add_compare_command(app, global);
  cli::add_report_command(app, global);
  cli::add_advise_command(app, global);
  cli::add_world_command(app, global);
  cli::add_audit_command(app, global);
  cli::add_bias_command(app, global);
  cli::add_shadow_command(app, global);
  cli::add_cache_command(app);
  one_value_per_option(app);
  global.command_line = "depthprec";
  for (int i = 1; i < argc; ++i) global.command_line += std::string(" ") + argv[i];
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // A mistyped command (or a command's subcommand: cache) would otherwise read "A subcommand is
    // required": name it and the closest.
    const CLI::App* at = &app;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--device") ++i;
      if (a.empty() || a[0] == '-') continue;
      std::vector<std::string> names;
      const CLI::App* next = nullptr;
      for (const CLI::App* sub : at->get_subcommands([](const CLI::App*) { return true; })) {
        names.push_back(sub->get_name());
        if (sub->get_name() == a) next = sub;
      }
      if (names.empty()) break;  // a command's own positionals
      if (next) {
        at = next;
        continue;
      }
      const std::string near = closest_name(a, names);
      const std::string what = at == &app ? "command" : at->get_name() + " subcommand";
      std::fprintf(stderr, "depthprec: unknown %s '%s'%s; the %ss are %s (depthprec %s--help)\n",
                   what.c_str(), a.c_str(),
                   near.empty() ? "" : (" (did you mean " + near + "?)").c_str(), what.c_str(),
                   fmt::format("{}", fmt::join(names, ", ")).c_str(),
                   at == &app ? "" : (at->get_name() + " ").c_str());
      return static_cast<int>(ExitCode::usage);
    }
    // --help and --version through write_output, so a failed write names its reason.
    std::ostringstream out, err;
    const int rc = app.exit(e, out, err);
    // CLI11's message ("--jobs: Value 0 not in range 1 to 64"), said by depthprec as every error is
    if (!err.str().empty()) std::fputs(("depthprec: " + err.str()).c_str(), stderr);
    try {
      write_output("", out.str());
    } catch (const Error& failed) {
      std::fprintf(stderr, "depthprec: %s\n", failed.what());
      return static_cast<int>(failed.code());
    }
    return rc == 0 ? 0 : static_cast<int>(ExitCode::usage);
  } catch (const Error& e) {
    std::fprintf(stderr, "depthprec: %s\n", e.what());
    return static_cast<int>(e.code());
  } catch (const cl::Error& e) {
    std::fprintf(stderr, "depthprec: OpenCL call %s failed with error %d\n", e.what(), e.err());
    return static_cast<int>(ExitCode::runtime);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "depthprec: internal error: %s\n", e.what());
    return static_cast<int>(ExitCode::internal);
  }
  return 0;
}

// Everything written to standard output -- results, --help, --version -- is buffered, and a full
// disk or /dev/full fails only when it is flushed: checked once here, at the end of every run, so
// no command can lose its output and still exit 0.
int finish_standard_output(int rc) {
  std::cout.flush();
  errno = 0;
  const bool flush_failed = std::fflush(stdout) != 0;
  const int err = errno;
  if (!flush_failed && !std::ferror(stdout) && std::cout) return rc;
  std::fprintf(stderr, "depthprec: cannot write standard output: %s\n",
               err != 0 ? std::strerror(err) : "a write failed");
  return rc == 0 ? static_cast<int>(depthprec::ExitCode::output) : rc;
}

}  // namespace

int main(int argc, char** argv) {
  return finish_standard_output(run(argc, argv));
}
