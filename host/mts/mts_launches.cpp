// The MtsEvaluator's launches: priming PoCL's work-group functions before jobs run side by
// side, and every launch checked against what was primed (mts_evaluator.h, prime_launches).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <limits>

#include "host/base/errors.h"
#include "host/mts/mts_evaluator.h"
#include "host/mts/mts_evaluator_parts.h"
#include "host/runtime/kernel_args.h"
#include "interface/mts_layout.h"

namespace depthprec {

using namespace mts_parts;

void LaunchPrimer::once(const std::string& kernel, const std::function<void()>& prime) {
  std::once_flag* flag = nullptr;
  {
    std::lock_guard<std::mutex> lock(m_);
    flag = &flags_[kernel];  // a map's elements stay where they are
  }
  std::call_once(*flag, prime);
}

MtsEvaluator::LaunchWidths& MtsEvaluator::LaunchWidths::operator|=(const LaunchWidths& o) {
  setup = std::max(setup, o.setup);
  a_rows = std::max(a_rows, o.a_rows);
  a_bands = std::max(a_bands, o.a_bands);
  bounds = std::max(bounds, o.bounds);
  raster = std::max(raster, o.raster);
  return *this;
}

MtsEvaluator::LaunchWidths MtsEvaluator::widest_launches(const Scene& scene,
                                                         const KernelVariant& variant,
                                                         int evaluators) {
  const size_t f = static_cast<size_t>(scene.frames), bands = band_count(scene);
  // A launch of run() takes the probes of at most distances_at_once() distances (search_pair's
  // window), one bisection probe or the stiffness probes of each, over at most kMaxBatchFrames
  // frames; the plane-A cache's launches take every frame of one distance.
  const size_t probes = plane_a_slots(scene, variant.cache_a_codes, evaluators) *
                        static_cast<size_t>(std::max(1, 2 * scene.stiffness_probes));
  const size_t frames = std::min<size_t>(f, kMaxBatchFrames), planes = probes * frames;
  LaunchWidths w;
  w.setup = padded_size(std::max(f, planes));
  w.a_rows = padded_size(f * a_row_groups(scene));
  w.a_bands = padded_size(f * bands);
  w.bounds = padded_size(planes * bands);
  w.raster = std::max({padded_size(bands), frames, probes});  // (bands, frames, probes)
  return w;
}

void MtsEvaluator::prime_launches(const LaunchWidths& widths, LaunchPrimer& primer) {
  const cl::Buffer none(rt_.context(), CL_MEM_READ_WRITE, 64);
  MtsKernelArea none_area = area();
  none_area.bands = 0;
  // Once per kernel of a program build (its source, options and name): placeholder buffers and
  // the kernel's area with no bands and no items, so every work-item returns at once.
  const auto prime = [&](cl::Kernel& k, auto args, const std::string& program, size_t width,
                         int dimensions) {
    primer.once(program + " " + k.getInfo<CL_KERNEL_FUNCTION_NAME>(), [&] {
      args.area = none_area;
      bind_placeholders(k, none, args);
      const size_t w = padded_size(width);
      rt_.queue().enqueueNDRangeKernel(
          k, cl::NullRange, dimensions == 3 ? cl::NDRange(w, 1, 1) : cl::NDRange(w),
          dimensions == 3 ? cl::NDRange(kLocal, 1, 1) : cl::NDRange(kLocal));
      rt_.queue().finish();
    });
  };
  const std::string program = variant_.program + " " + variant_.options;
  MtsSetupArgs setup_args{};
  setup_args.per_probe = 1;
  prime(setup_, setup_args, variant_.setup_program + " " + variant_.setup_options, widths.setup, 1);
  prime(a_rows_, MtsARowsArgs{}, program, widths.a_rows, 1);
  prime(a_bands_, MtsABandsArgs{}, program, widths.a_bands, 1);
  prime(bounds_, MtsFrameBoundsArgs{}, program, widths.bounds, 1);
  prime(raster_, MtsRasterArgs{}, program, widths.raster, 3);
  primed_ = widths;
}

void MtsEvaluator::launch(cl::Kernel& k, size_t primed, const cl::NDRange& global,
                          const cl::NDRange& local, cl::Event* done) {
  for (size_t d = 0; primed && d < global.dimensions(); ++d)
    if (global.get()[d] > primed)
      throw Error(ExitCode::internal,
                  fmt::format("{}: a grid {} work-items wide, wider than the {} it was primed for "
                              "(MtsEvaluator::widest_launches)",
                              k.getInfo<CL_KERNEL_FUNCTION_NAME>(), global.get()[d], primed));
  rt_.queue().enqueueNDRangeKernel(k, cl::NullRange, global, local, nullptr, done);
  ++launches_;
}

}  // namespace depthprec
