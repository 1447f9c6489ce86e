#include "host/audit/audit_device.h"

#include <algorithm>

#include "host/runtime/kernel_args.h"
#include "host/runtime/kernel_variant.h"
#include "host/runtime/opencl_runtime.h"

namespace depthprec {

namespace {

// A read-only buffer holding v, copied by the driver (OpenCL has no empty buffers: one zero
// element for an empty v).
template <class T>
cl::Buffer input(cl::Context& ctx, const std::vector<T>& v) {
  static const T zero{};
  return cl::Buffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                    sizeof(T) * std::max<size_t>(v.size(), 1),
                    const_cast<T*>(v.empty() ? &zero : v.data()));
}

}  // namespace

AuditPixels audit_device(OpenClRuntime& rt, const Scene& scene, const AuditSetup& a) {
  const KernelVariant variant = mts_variant(scene, a.pair);
  cl::Program program = rt.program("kernels/audit.cl", variant.options);
  cl::Kernel kernel(program, "audit_pixels");
  cl::Context& ctx = rt.context();
  const auto packed = a.pc.packed(0);
  const std::vector<float> probe(packed.begin(), packed.end());
  std::vector<double> planes;
  planes.reserve(a.planes.size() * AUDIT_PLANE_WORDS);
  for (const auto& p : a.planes) planes.insert(planes.end(), p.begin(), p.end());
  const std::vector<double> ray(a.ray.begin(), a.ray.end());
  const cl::Buffer b_probe = input(ctx, probe), b_records = input(ctx, packed_records(a)),
                   b_source = input(ctx, a.source), b_tolerance = input(ctx, a.tolerance),
                   b_ray = input(ctx, ray), b_planes = input(ctx, planes),
                   b_bins = input(ctx, a.bins), b_bin_records = input(ctx, a.bin_records);
  const size_t n = static_cast<size_t>(a.width) * a.height;
  cl::Buffer b_winner(ctx, CL_MEM_WRITE_ONLY, sizeof(uint32_t) * n),
      b_front(ctx, CL_MEM_WRITE_ONLY, sizeof(uint32_t) * n),
      b_margin(ctx, CL_MEM_WRITE_ONLY, sizeof(int32_t) * n),
      b_flags(ctx, CL_MEM_WRITE_ONLY, sizeof(uint32_t) * n);
  AuditPixelsBuffers b;
  b.probe = &b_probe;
  b.records = &b_records;
  b.source = &b_source;
  b.tolerance = &b_tolerance;
  b.ray = &b_ray;
  b.planes = &b_planes;
  b.bins = &b_bins;
  b.bin_records = &b_bin_records;
  b.winner = &b_winner;
  b.front = &b_front;
  b.margin = &b_margin;
  b.flags = &b_flags;
  AuditPixelsArgs args{};
  args.width = static_cast<uint32_t>(a.width);
  args.height = static_cast<uint32_t>(a.height);
  args.tiles_x = static_cast<uint32_t>(a.tiles_x);
  args.tiles_y = static_cast<uint32_t>(a.tiles_y);
  args.clear_code = a.clear_code;
  bind(kernel, b, args);
  cl::CommandQueue& q = rt.queue();
  const size_t items = static_cast<size_t>(a.tiles_x) * a.tiles_y * AUDIT_TILE;
  q.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(padded_size(items)),
                         cl::NDRange(kWorkGroup));
  AuditPixels out;
  out.resize(a.width, a.height);
  q.enqueueReadBuffer(b_winner, CL_FALSE, 0, sizeof(uint32_t) * n, out.winner.data());
  q.enqueueReadBuffer(b_front, CL_FALSE, 0, sizeof(uint32_t) * n, out.front.data());
  q.enqueueReadBuffer(b_margin, CL_FALSE, 0, sizeof(int32_t) * n, out.margin.data());
  q.enqueueReadBuffer(b_flags, CL_TRUE, 0, sizeof(uint32_t) * n, out.flags.data());
  return out;
}

}  // namespace depthprec
