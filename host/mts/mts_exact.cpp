#include "host/mts/mts_exact.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <glm/gtc/constants.hpp>

#include "host/model/frame_setup.h"
#include "host/runtime/kernel_variant.h"

namespace depthprec {

namespace {

// The work-items of every mts_exact and mts_exact_a launch: 64 frames of a 200-row kernel.
constexpr size_t kExactLaunchWidth = 64 * 200;
static_assert(kExactLaunchWidth % kWorkGroup == 0, "whole work-groups");

// Plane A's cache of one evaluator (attribution runs one per job): 5 bytes a pixel, so the
// default scene's paper frames (100 x 200 x 200) hold 3 distances, 20 MB each.
constexpr size_t kCacheBudget = 64u << 20;

// Sets the arguments mts_exact and mts_exact_a open with (kernels/mts_exact.cl): the planes, the
// kernel and viewport, the projection's slopes, log k and the items; then `more`, each kernel's
// own.
template <class... More>
void bind_exact(cl::Kernel& k, const Scene& s, const cl::Buffer& planes, size_t items,
                const More&... more) {
  const double tan_half = std::tan(s.fov_y_deg * glm::pi<double>() / 360.0);
  const double aspect = static_cast<double>(s.viewport_w) / s.viewport_h;
  set_args(k, planes, static_cast<cl_uint>(s.kernel_w), static_cast<cl_uint>(s.kernel_h),
           static_cast<double>((s.viewport_w - s.kernel_w) / 2),
           static_cast<double>((s.viewport_h - s.kernel_h) / 2), static_cast<double>(s.viewport_w),
           static_cast<double>(s.viewport_h), aspect * tan_half, tan_half, s.params.log_k,
           static_cast<cl_uint>(items), more...);
}

}  // namespace

ExactEvaluator::ExactEvaluator(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                               const Orientations& orientations, bool shortcuts)
    : rt_(rt), scene_(scene), pair_(pair), orientations_(orientations) {
  const Technique t = depth_path(scene, pair.technique);
  const TechniqueInfo& ti = info(t);
  options_ = fmt::format(
      "{} -DROW_ENDS={} -DDEPTH_MAP={} -DCLIP_W={} -DPARALLEL_RAYS={} -DCOMPARE_GREATER={} {}",
      base_build_options(false), shortcuts ? 1 : 0, static_cast<int>(info(t).map),
      ti.from == DepthFrom::fragment ? 1 : 0, t == Technique::orthographic ? 1 : 0,
      ti.greater ? 1 : 0, scene.storage_format(pair).defines());
  kernel_ =
      cl::Kernel(rt_.program("kernels/mts_exact.cl", options_ + " -DA_CACHED=0"), "mts_exact");
  kw_pad_ = (static_cast<size_t>(scene.kernel_w) + 7) / 8 * 8;
  const size_t per_distance = static_cast<size_t>(scene.frames) *
                              static_cast<size_t>(scene.kernel_h) * kw_pad_ *
                              (sizeof(uint32_t) + 1);
  slots_ = shortcuts ? kCacheBudget / std::max<size_t>(1, per_distance) : 0;
}

std::vector<double> ExactEvaluator::plane_records(const std::vector<Probe>& probes,
                                                  const std::vector<size_t>& which, int first,
                                                  int count) const {
  std::vector<double> planes(which.size() * static_cast<size_t>(count) * 2 * 16);
  for (size_t i = 0; i < which.size(); ++i) {
    const Probe& pr = probes[which[i]];
    // the mapping's near and far ride in the spare centre.w slots: plane A's layer for
    // layered, so every probe of a launch keeps its own
    const ProbeConstants pc = probe_constants(scene_, pair_, pr.z, orientations_);
    for (int f = 0; f < count; ++f)
      for (int p = 0; p < 2; ++p) {
        const auto M = model_matrix_f64(scene_, pc, p == 0 ? pr.z : pr.z + pr.s, first + f);
        double* dst = planes.data() + ((i * static_cast<size_t>(count) + f) * 2 + p) * 16;
        for (int c = 0; c < 4; ++c)
          for (int r = 0; r < 3; ++r)
            dst[c * 4 + r] = M[r * 4 + c];  // columns a, b, normal, centre
        dst[15] = p == 0 ? pc.layer_near : pc.layer_far;
        // an orthographic view's half-extents scale with plane A's distance (frame_setup's P)
        dst[3] = pair_.technique == Technique::orthographic ? pr.z : 0.0;
      }
  }
  return planes;
}

// Every launch is kExactLaunchWidth work-items wide, offset along the items: evaluators of one
// program running side by side (attribution's jobs) then never launch it wider than an earlier
// launch did, which PoCL 3.1 cannot take while others are in flight (MtsEvaluator::prime_launches
// says how it aborts).
void ExactEvaluator::launch(cl::Kernel& k, size_t items) {
  for (size_t first = 0; first < items; first += kExactLaunchWidth)
    rt_.queue().enqueueNDRangeKernel(k, cl::NDRange(first), cl::NDRange(kExactLaunchWidth),
                                     cl::NDRange(kWorkGroup));
}

// A distance's first run computes plane A in every probe (a fighting probe stops after a few
// frames, which a fill of every frame would not); from its second on the probes read the cache,
// once every distance of the run has a slot (search_pair's windows hold distances_at_once()).
std::vector<size_t> ExactEvaluator::cache_slots(const std::vector<Probe>& probes) {
  bool use = slots_ > 0;
  std::vector<double> zs;
  for (const Probe& p : probes) {
    use &= runs_at_[p.z]++ >= 1;
    if (std::find(zs.begin(), zs.end(), p.z) == zs.end()) zs.push_back(p.z);
  }
  if (!use || zs.size() > slots_) return {};
  const auto kh = static_cast<size_t>(scene_.kernel_h), frames = static_cast<size_t>(scene_.frames);
  if (slot_z_.empty()) {
    const size_t cells = slots_ * frames * kh * kw_pad_;
    a_code_ = cl::Buffer(rt_.context(), CL_MEM_READ_WRITE, sizeof(uint32_t) * cells);
    a_bits_ = cl::Buffer(rt_.context(), CL_MEM_READ_WRITE, cells);
    slot_z_.assign(slots_, NAN);
    const cl::Program program = rt_.program("kernels/mts_exact.cl", options_ + " -DA_CACHED=1");
    cached_ = cl::Kernel(program, "mts_exact");
    fill_ = cl::Kernel(program, "mts_exact_a");
  }
  for (const double z : zs) {
    if (std::find(slot_z_.begin(), slot_z_.end(), z) != slot_z_.end()) continue;
    // a free slot, or one whose distance this run does not probe
    size_t slot = 0;
    while (!std::isnan(slot_z_[slot]) && std::find(zs.begin(), zs.end(), slot_z_[slot]) != zs.end())
      ++slot;
    slot_z_[slot] = z;
    const std::vector<double> planes =
        plane_records({Probe{z, 0.0}}, {0}, 0, static_cast<int>(frames));
    const cl::Buffer plane_buf = buffer_of(rt_.context(), planes);
    const size_t items = frames * kh;
    bind_exact(fill_, scene_, plane_buf, items, static_cast<cl_uint>(kw_pad_),
               static_cast<cl_uint>(slot * frames), a_code_, a_bits_);
    launch(fill_, items);
    ++cache_fills_;
  }
  std::vector<size_t> out;
  for (const Probe& p : probes)
    out.push_back(
        static_cast<size_t>(std::find(slot_z_.begin(), slot_z_.end(), p.z) - slot_z_.begin()));
  return out;
}

std::vector<double> ExactEvaluator::chord_audit(const std::vector<Probe>& probes) {
  cl::Kernel k(rt_.program("kernels/mts_exact.cl", options_ + " -DA_CACHED=1 -DCHORD_AUDIT=1"),
               "mts_exact_chord_audit");
  std::vector<size_t> all(probes.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  const cl::Buffer plane_buf =
      buffer_of(rt_.context(), plane_records(probes, all, 0, scene_.frames));
  const size_t per_probe =
      static_cast<size_t>(scene_.frames) * static_cast<size_t>(scene_.kernel_h);
  const size_t items = probes.size() * per_probe;
  cl::Buffer out(rt_.context(), CL_MEM_WRITE_ONLY, sizeof(double) * items);
  bind_exact(k, scene_, plane_buf, items, out);
  launch(k, items);
  std::vector<double> rows(items);
  rt_.queue().enqueueReadBuffer(out, CL_TRUE, 0, sizeof(double) * items, rows.data());
  std::vector<double> worst(probes.size(), -1.0);
  for (size_t i = 0; i < items; ++i) worst[i / per_probe] = std::max(worst[i / per_probe], rows[i]);
  return worst;
}

std::vector<ProbeResult> ExactEvaluator::run(const std::vector<Probe>& probes) {
  std::vector<ProbeResult> results(probes.size());
  std::vector<bool> decided(probes.size(), false);
  const std::vector<size_t> slots = cache_slots(probes);
  const auto kh = static_cast<size_t>(scene_.kernel_h);
  int done = 0;
  while (done < scene_.frames) {
    const std::vector<size_t> active = undecided(decided);
    if (active.empty()) break;
    const int frames = batch_frames(done, scene_.frames);
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<double> planes = plane_records(probes, active, done, frames);
    const cl::Buffer plane_buf = buffer_of(rt_.context(), planes);
    const size_t items = active.size() * frames * kh;
    cl::Buffer out(rt_.context(), CL_MEM_WRITE_ONLY, sizeof(uint32_t) * items);
    cl::Kernel& k = slots.empty() ? kernel_ : cached_;
    cl::Buffer a_frame;  // alive until the launch has run
    if (slots.empty()) {
      bind_exact(k, scene_, plane_buf, items, out);
    } else {
      // each (probe, frame) of the launch: its frame of the cache
      std::vector<uint32_t> frame_of(active.size() * static_cast<size_t>(frames));
      for (size_t i = 0; i < active.size(); ++i)
        for (int f = 0; f < frames; ++f)
          frame_of[i * static_cast<size_t>(frames) + static_cast<size_t>(f)] =
              static_cast<uint32_t>(slots[active[i]] * static_cast<size_t>(scene_.frames) +
                                    static_cast<size_t>(done + f));
      a_frame = buffer_of(rt_.context(), frame_of);
      bind_exact(k, scene_, plane_buf, items, out, static_cast<cl_uint>(kw_pad_), a_frame, a_code_,
                 a_bits_);
    }
    launch(k, items);
    std::vector<uint32_t> rows(items);
    rt_.queue().enqueueReadBuffer(out, CL_TRUE, 0, sizeof(uint32_t) * items, rows.data());
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (const uint32_t w : rows) {
      rows_from_ends_ += (w & MTS_R_BOUNDS) != 0;
      rows_from_chords_ += (w & MTS_R_CHORDS) != 0;
    }
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
