#include "host/bias/bias_evaluator.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "host/base/errors.h"
#include "host/model/frame_setup.h"
#include "host/mts/probe.h"
#include "host/runtime/kernel_args.h"
#include "interface/bias_formula.h"
#include "interface/mts_layout.h"

namespace depthprec {

namespace {

// Planes set up per launch at most (two per probe and frame, MTS_PLANE_STRIDE floats each: about
// 8 KiB at the default grid), so a round of many distances stays within a few tens of MiB.
constexpr size_t kMaxPlanesPerLaunch = 4096;

}  // namespace

KernelVariant bias_variant(const Scene& scene, const EvalPair& pair) {
  // The adversary moves plane A against plane B; depth bias draws one plane over its own overlay.
  if (!scene.pipeline.envelope.empty())
    throw InputError(fmt::format(
        "bias: pipeline.envelope {} is an adversary between two planes of the MTS; depth bias "
        "overlays a plane on itself (measure bias under the ideal pipeline, or give "
        "--set bound_model={} for the guaranteed units)",
        scene.pipeline.envelope, scene.pipeline.envelope));
  KernelVariant v = mts_variant(scene, pair);
  v.program = "kernels/bias.cl";
  v.label = "bias:" + v.label;
  v.cache_a_codes = false;
  return v;
}

BiasEmulator::BiasEmulator(OpenClRuntime& rt, const Scene& scene, const EvalPair& pair,
                           const BiasOptions& options, const Orientations& orientations)
    : rt_(rt),
      scene_(scene),
      pair_(pair),
      orientations_(orientations),
      options_(options),
      rule_(bias_rule(options, scene.storage_format(pair))),
      variant_(bias_variant(scene, pair)) {
  const std::string why = bias_not_applicable(scene, pair);
  if (!why.empty()) throw InputError(fmt::format("{}: no depth bias: {}", pair.label(), why));
  program_ = rt_.program(variant_.program, variant_.options);
  setup_ = cl::Kernel(program_, "bias_setup");
  rows_ = cl::Kernel(program_, "bias_rows");
  plane_floats_ = MTS_PLANE_STRIDE(scene.plane_subdivisions, scene.pipeline.clip_slots());
}

std::vector<ProbeResult> BiasEmulator::run(const std::vector<BiasProbe>& probes) {
  const int total = scene_.frames;
  const size_t kh = static_cast<size_t>(scene_.kernel_h);
  // The whole kernel is one band: the set-up's certificate is per plane here, not per band.
  const MtsKernelArea area{static_cast<cl_uint>(scene_.kernel_w),
                           static_cast<cl_uint>(scene_.kernel_h),
                           static_cast<float>((scene_.viewport_w - scene_.kernel_w) / 2),
                           static_cast<float>((scene_.viewport_h - scene_.kernel_h) / 2),
                           1,
                           static_cast<cl_uint>(scene_.kernel_h)};
  const double tilt = options_.tilt_deg * M_PI / 180.0;
  std::vector<ProbeResult> results(probes.size());
  std::vector<bool> decided(probes.size(), false);
  std::vector<int> first(probes.size(), 0);
  for (size_t i = 0; i < probes.size(); ++i) {
    const auto it = last_fail_frame_.find(probes[i].z);
    if (it != last_fail_frame_.end()) first[i] = it->second;
  }
  // Every probe starts at visit 0 and advances by the same batch, so the undecided ones stay in
  // step: one launch renders the same visits of all of them (as many as fit a launch).
  int done = 0;
  while (done < total) {
    const int frames = batch_frames(done, total);
    const std::vector<size_t> pending = undecided(decided);
    if (pending.empty()) break;
    const size_t per_launch =
        std::max<size_t>(1, kMaxPlanesPerLaunch / (2 * static_cast<size_t>(frames)));
    for (size_t c = 0; c < pending.size(); c += per_launch) {
      const std::vector<size_t> active(
          pending.begin() + static_cast<std::ptrdiff_t>(c),
          pending.begin() + static_cast<std::ptrdiff_t>(std::min(pending.size(), c + per_launch)));
      const auto t0 = std::chrono::steady_clock::now();
      std::vector<float> consts, mats;
      for (const size_t i : active) {
        const BiasProbe& p = probes[i];
        const ProbeConstants pc = probe_constants(scene_, pair_, p.z, orientations_);
        auto packed = pc.packed(0);
        packed[MTS_C_BIAS_UNITS] = rule_.units_term(p.units);
        packed[MTS_C_BIAS_FACTOR] = static_cast<float>(p.factor);
        packed[MTS_C_BIAS_CLAMP] = static_cast<float>(options_.clamp);
        consts.insert(consts.end(), packed.begin(), packed.end());
        for (int v = done; v < done + frames; ++v)
          append_plane_words(mats, scene_, pc, p.z, (first[i] + v) % total, tilt);
      }
      const size_t planes = 2 * active.size() * static_cast<size_t>(frames);
      const cl::Buffer const_buf = buffer_of(rt_.context(), consts);
      const cl::Buffer mat_buf = buffer_of(rt_.context(), mats);
      cl::Buffer tris(rt_.context(), CL_MEM_READ_WRITE, sizeof(float) * planes * plane_floats_);
      cl::Buffer vflags(rt_.context(), CL_MEM_READ_WRITE, sizeof(uint32_t) * planes);
      BiasSetupBuffers setup_in;
      setup_in.probes = &const_buf;
      setup_in.mats = &mat_buf;
      setup_in.tris = &tris;
      setup_in.vflags = &vflags;
      BiasSetupArgs setup_args{};
      setup_args.area = area;
      setup_args.half_w = 0.5f * static_cast<float>(scene_.viewport_w);
      setup_args.half_h = 0.5f * static_cast<float>(scene_.viewport_h);
      setup_args.per_probe = static_cast<cl_uint>(2 * frames);
      setup_args.count = static_cast<cl_uint>(planes);
      setup_args.float_rule = rule_.float_rule ? 1 : 0;
      setup_args.slope_form = options_.slope == SlopeForm::sqrt ? BIAS_SLOPE_SQRT : 0;
      bind(setup_, setup_in, setup_args);
      cl::Event setup_done, rows_done;
      rt_.queue().enqueueNDRangeKernel(setup_, cl::NullRange, cl::NDRange(padded_size(planes)),
                                       cl::NDRange(kWorkGroup), nullptr, &setup_done);
      const size_t items = active.size() * static_cast<size_t>(frames) * kh;
      cl::Buffer result(rt_.context(), CL_MEM_WRITE_ONLY, sizeof(uint32_t) * items);
      BiasRowsBuffers rows_in;
      rows_in.probes = &const_buf;
      rows_in.tris = &tris;
      rows_in.vflags = &vflags;
      rows_in.result = &result;
      BiasRowsArgs rows_args{};
      rows_args.area = area;
      rows_args.frames = static_cast<cl_uint>(frames);
      rows_args.strict = options_.or_equal ? 0 : 1;
      bind(rows_, rows_in, rows_args);
      rt_.queue().enqueueNDRangeKernel(
          rows_, cl::NullRange,
          cl::NDRange(padded_size(kh), static_cast<size_t>(frames), active.size()),
          cl::NDRange(kWorkGroup, 1, 1), nullptr, &rows_done);
      std::vector<uint32_t> rows(items);
      rt_.queue().enqueueReadBuffer(result, CL_TRUE, 0, sizeof(uint32_t) * items, rows.data());
      const double secs =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const double ksecs = device_seconds(setup_done) + device_seconds(rows_done);
      uint64_t after = 0;
      fold_launch(rows, active, done, frames, kh, results, decided, after);
      for (const size_t i : active) {
        results[i].seconds += secs / static_cast<double>(active.size());
        results[i].kernel_seconds += ksecs / static_cast<double>(active.size());
        results[i].launches += 2;
        if (decided[i]) {
          results[i].deciding_frame = (first[i] + results[i].frames - 1) % total;
          last_fail_frame_[probes[i].z] = results[i].deciding_frame;
        }
      }
    }
    done += frames;
  }
  finish_outcomes(results, decided);
  return results;
}

}  // namespace depthprec
