// The MtsEvaluator's test-only kernels (kernels/mts_test.cl): both planes' codes of one frame,
// and the audit of the coverage shortcut (Kernels::with_tests).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <limits>

#include "host/base/errors.h"
#include "host/mts/mts_evaluator.h"
#include "host/mts/mts_evaluator_parts.h"
#include "interface/mts_layout.h"

namespace depthprec {

using namespace mts_parts;

const cl::Program& MtsEvaluator::test_program() const {
  if (!test_program_())
    throw Error(ExitCode::internal,
                "the test kernels need an MtsEvaluator built with Kernels::with_tests");
  return test_program_;
}

CoverageAudit MtsEvaluator::audit_coverage(const std::vector<Probe>& probes) {
  reserve_plane_a(probes);
  CoverageAudit total;
  for (const std::vector<size_t>& group : cache_groups(probes)) {
    std::vector<Probe> held;
    for (const size_t i : group) held.push_back(probes[i]);
    total += audit_cached(held);
  }
  return total;
}

CoverageAudit MtsEvaluator::audit_cached(const std::vector<Probe>& probes) {
  std::vector<size_t> all(probes.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  double ksecs = 0;
  std::vector<int> cache_launches;
  const std::vector<cl_uint> slots = cache_plane_a(probes, all, ksecs, cache_launches);
  const int frames = scene_.frames;
  cl::Buffer probe_buf, slot_buf, tris, vflags;
  setup_plane_b(probes, all, slots, std::vector<int>(probes.size(), 0), 0, frames, probe_buf,
                slot_buf, tris, vflags);
  const auto kw = static_cast<cl_uint>(scene_.kernel_w), kh = static_cast<cl_uint>(scene_.kernel_h);
  const size_t items = probes.size() * frames * kh;
  cl::Buffer out(rt_.context(), CL_MEM_WRITE_ONLY, sizeof(uint32_t) * items);
  cl::Kernel k(test_program(), "mts_coverage_audit");
  set_args(k, tris, vflags, a_.tris, a_.vflags, a_.rows, slot_buf, cl_uint{0},
           static_cast<cl_uint>(frames), kw, kh, origin_x(), origin_y(),
           static_cast<cl_uint>(frames), kBandRows, out, static_cast<cl_uint>(items));
  rt_.queue().enqueueNDRangeKernel(k, cl::NullRange, padded(items), cl::NDRange(kLocal));
  std::vector<uint32_t> words(items);
  rt_.queue().enqueueReadBuffer(out, CL_TRUE, 0, sizeof(uint32_t) * items, words.data());
  CoverageAudit a;
  for (const uint32_t w : words) {
    a.rows += (w >> 3) & 1;
    a.b_differs += w & 1;
    a.certified += (w >> 1) & 1;
    a.certified_but_differs += (w >> 2) & 1;
    a.a_differs += (w >> 4) & 1;
    a.from_reference += (w >> 5) & 1;
  }
  return a;
}

FrameCodes MtsEvaluator::codes(const Probe& probe, int frame) {
  const ProbeConstants pc = probe_constants(scene_, pair_, probe.z, orientations_);
  // plane A's constants, then plane B's (they differ in an envelope's adversary alone)
  std::vector<float> both;
  for (const int plane : {+1, -1}) {
    const auto packed = pc.packed(plane);
    both.insert(both.end(), packed.begin(), packed.end());
  }
  const cl::Buffer probe_buf = buffer_of(rt_.context(), both);
  std::vector<float> mats;
  for (const double d : {probe.z, probe.z + probe.s})
    append_plane_words(mats, scene_, pc, d, frame);
  cl::Buffer tris(rt_.context(), CL_MEM_READ_WRITE, sizeof(float) * 2 * plane_floats_);
  cl::Buffer vflags(rt_.context(), CL_MEM_READ_WRITE, sizeof(uint32_t) * 2);
  setup(probe_buf, mats, 1, 0, tris, vflags);
  const auto kw = static_cast<cl_uint>(scene_.kernel_w), kh = static_cast<cl_uint>(scene_.kernel_h);
  const size_t pixels = static_cast<size_t>(kw) * kh;
  cl::Buffer out(rt_.context(), CL_MEM_WRITE_ONLY, sizeof(uint32_t) * 4 * pixels);
  cl::Kernel codes(test_program(), "mts_codes");
  set_args(codes, probe_buf, tris, kw, origin_x(), origin_y(), out, kh);
  rt_.queue().enqueueNDRangeKernel(codes, cl::NullRange, padded(kh), cl::NDRange(kLocal));
  std::vector<uint32_t> raw(4 * pixels);
  rt_.queue().enqueueReadBuffer(out, CL_TRUE, 0, sizeof(uint32_t) * raw.size(), raw.data());
  uint32_t vf[2] = {0, 0};
  rt_.queue().enqueueReadBuffer(vflags, CL_TRUE, 0, sizeof vf, vf);
  FrameCodes fc;
  fc.width = static_cast<int>(kw);
  fc.height = static_cast<int>(kh);
  for (size_t i = 0; i < pixels; ++i) {
    fc.code_a.push_back(raw[4 * i]);
    fc.code_b.push_back(raw[4 * i + 1]);
    fc.status_a.push_back((vf[0] & kVertexNonFinite) ? 2 : static_cast<uint8_t>(raw[4 * i + 2]));
    fc.status_b.push_back((vf[1] & kVertexNonFinite) ? 2 : static_cast<uint8_t>(raw[4 * i + 3]));
  }
  return fc;
}

}  // namespace depthprec
