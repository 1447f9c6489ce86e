#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "host/base/errors.h"
#include "host/cli/commands.h"
#include "host/model/storage_format.h"
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
};

void run_formats(const FormatsOptions& o, const GlobalOptions& global) {
  const Rounding rounding = parse_rounding(o.rounding);
  const Denormals denormals = parse_denormals(o.denormals);
  std::vector<StorageFormat> formats;
  for (const auto& n : o.names) formats.push_back(StorageFormat::parse(n, rounding, denormals));
  // A depth buffer holds window depths in [0, 1] (the pipeline clamps or clips the rest), so a
  // value outside is not a depth: refused rather than stored as the nearest end.
  for (double v : o.values)
    if (!(v >= 0.0 && v <= 1.0))
      throw InputError(fmt::format("--value {}: depth values are in [0, 1]", v));

  fmt::print("storage formats (rounding {}, denormals {})\n", o.rounding, o.denormals);
  fmt::print("{:<9} {:>4} {:>14} {:>14} {:>14} {:>14}\n", "format", "bits", "smallest>0", "largest",
             "spacing@0.5", "codes");
  for (const auto& f : formats)
    fmt::print("{:<9} {:>4} {:>14.7g} {:>14.10g} {:>14.7g} {:>14}\n", f.name(), f.bits(),
               f.smallest_positive(), f.largest(), f.spacing_at(0.5),
               static_cast<unsigned long long>(f.max_code()) + 1);

  if (o.values.empty()) return;
  std::unique_ptr<OpenClRuntime> rt;
  if (o.on_device) rt = std::make_unique<OpenClRuntime>(global.device);
  fmt::print("\nround trip: value -> binary32 depth d -> code -> stored value{}\n",
             o.on_device ? " (code also computed by the OpenCL kernel)" : "");
  fmt::print("{:<9} {:>24} {:>12} {:>12} {:>24} {:>12}{}\n", "format", "d (binary32)", "code",
             "code (hex)", "stored value", "rel. error", o.on_device ? "  device" : "");
  for (double v : o.values) {
    const float d = static_cast<float>(v);
    for (const auto& f : formats) {
      const uint32_t code = f.encode(d);
      const double stored = f.decode(code);
      const double rel =
          d != 0.0f ? (stored - static_cast<double>(d)) / static_cast<double>(d) : 0.0;
      std::string device_col;
      if (rt) {
        const uint32_t dev = device_encode(*rt, f, std::vector<float>{d}).front();
        device_col = dev == code ? "  agrees" : fmt::format("  DIFFERS: {}", dev);
        if (dev != code)
          throw Error(ExitCode::internal,
                      fmt::format("{} encodes {} as {} on the host but {} on the device", f.name(),
                                  d, code, dev));
      }
      fmt::print("{:<9} {:>24.17g} {:>12} {:>#12x} {:>24.17g} {:>12.3e}{}\n", f.name(), d, code,
                 code, stored, rel, device_col);
    }
  }
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
  cmd->callback([opts, &global]() { run_formats(*opts, global); });
}

}  // namespace depthprec::cli
