#include "host/mts/mts_exact.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <glm/gtc/constants.hpp>

#include "host/model/frame_setup.h"
#include "host/runtime/kernel_variant.h"

namespace depthprec {

namespace {

// The work-items of every mts_exact launch: 64 frames of a 200-row kernel.
constexpr size_t kExactLaunchWidth = 64 * 200;
static_assert(kExactLaunchWidth % kWorkGroup == 0, "whole work-groups");

}  // namespace

ExactEvaluator::ExactEvaluator(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                               const Orientations& orientations, bool shortcuts)
    : rt_(rt), scene_(scene), pair_(pair), orientations_(orientations) {
  const Technique t = depth_path(scene, pair.technique);
  const TechniqueInfo& ti = info(t);
  const std::string options =
      fmt::format("{} -DROW_ENDS={} -DDEPTH_MAP={} -DCLIP_W={} -DCOMPARE_GREATER={} {}",
                  base_build_options(false), shortcuts ? 1 : 0, static_cast<int>(info(t).map),
                  ti.from == DepthFrom::fragment ? 1 : 0, ti.greater ? 1 : 0,
                  scene.storage_format(pair).defines());
  kernel_ = cl::Kernel(rt_.program("kernels/mts_exact.cl", options), "mts_exact");
}

std::vector<ProbeResult> ExactEvaluator::run(const std::vector<Probe>& probes) {
  std::vector<ProbeResult> results(probes.size());
  std::vector<bool> decided(probes.size(), false);
  const auto kw = static_cast<cl_uint>(scene_.kernel_w), kh = static_cast<cl_uint>(scene_.kernel_h);
  const double tan_half = std::tan(scene_.fov_y_deg * glm::pi<double>() / 360.0);
  const double aspect = static_cast<double>(scene_.viewport_w) / scene_.viewport_h;
  int done = 0;
  while (done < scene_.frames) {
    const std::vector<size_t> active = undecided(decided);
    if (active.empty()) break;
    const int frames = batch_frames(done, scene_.frames);
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<double> planes(active.size() * frames * 2 * 16);
    for (size_t i = 0; i < active.size(); ++i) {
      const Probe& pr = probes[active[i]];
      // the mapping's near and far ride in the spare centre.w slots: plane A's layer for
      // layered, so every probe of a launch keeps its own
      const ProbeConstants pc = probe_constants(scene_, pair_, pr.z, orientations_);
      for (int f = 0; f < frames; ++f)
        for (int p = 0; p < 2; ++p) {
          const auto M = model_matrix_f64(scene_, pc, p == 0 ? pr.z : pr.z + pr.s, done + f);
          double* dst = planes.data() + ((i * frames + f) * 2 + p) * 16;
          for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 3; ++r)
              dst[c * 4 + r] = M[r * 4 + c];  // columns a, b, normal, centre
          dst[15] = p == 0 ? pc.layer_near : pc.layer_far;
        }
    }
    cl::Buffer plane_buf(rt_.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                         sizeof(double) * planes.size(), planes.data());
    const size_t items = active.size() * frames * kh;
    cl::Buffer out(rt_.context(), CL_MEM_WRITE_ONLY, sizeof(uint32_t) * items);
    set_args(kernel_, plane_buf, kw, kh,
             static_cast<double>((scene_.viewport_w - scene_.kernel_w) / 2),
             static_cast<double>((scene_.viewport_h - scene_.kernel_h) / 2),
             static_cast<double>(scene_.viewport_w), static_cast<double>(scene_.viewport_h),
             aspect * tan_half, tan_half, scene_.params.log_k, out, static_cast<cl_uint>(items));
    // Every launch is kExactLaunchWidth work-items wide, offset along the items: evaluators of
    // one program running side by side (attribution's jobs) then never launch it wider than an
    // earlier launch did, which PoCL 3.1 cannot take while others are in flight
    // (MtsEvaluator::prime_launches says how it aborts).
    for (size_t first = 0; first < items; first += kExactLaunchWidth)
      rt_.queue().enqueueNDRangeKernel(kernel_, cl::NDRange(first), cl::NDRange(kExactLaunchWidth),
                                       cl::NDRange(kWorkGroup));
    std::vector<uint32_t> rows(items);
    rt_.queue().enqueueReadBuffer(out, CL_TRUE, 0, sizeof(uint32_t) * items, rows.data());
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (const uint32_t w : rows) rows_from_ends_ += (w & MTS_R_BOUNDS) != 0;
    uint64_t after_decision = 0;  // work the -v breakdown counts for the emulated pipeline only
    fold_launch(rows, active, done, frames, kh, results, decided, after_decision);
    for (const size_t i : active)
      if (decided[i]) results[i].deciding_frame = results[i].frames - 1;  // frames in order
    for (const size_t i : active) {
      results[i].seconds += secs / static_cast<double>(active.size());
      results[i].launches += 1;
    }
    done += frames;
  }
  finish_outcomes(results, decided);
  return results;
}

}  // namespace depthprec
