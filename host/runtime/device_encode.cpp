#include "host/runtime/device_encode.h"

#include <cstring>

namespace depthprec {

namespace {

cl::Kernel encode_kernel(OpenClRuntime& rt, const StorageFormat& f) {
  const auto program =
      rt.program("kernels/encode.cl",
                 base_build_options(f.denormals() == Denormals::flush) + " " + f.defines());
  return cl::Kernel(program, "encode_range");
}

}  // namespace

uint64_t device_encode_range(OpenClRuntime& rt, const StorageFormat& f, uint32_t first_bits,
                             uint32_t count, std::vector<uint32_t>& out) {
  out.resize(count);
  if (count == 0) return 0;
  auto kernel = encode_kernel(rt, f);
  const size_t local = 16;
  const size_t items = ((count + 15u) / 16u + local - 1) / local * local;
  cl::Buffer codes(rt.context(), CL_MEM_WRITE_ONLY | CL_MEM_USE_HOST_PTR, sizeof(uint32_t) * count,
                   out.data());
  std::vector<uint32_t> differ(items);
  cl::Buffer differ_buf(rt.context(), CL_MEM_WRITE_ONLY | CL_MEM_USE_HOST_PTR,
                        sizeof(uint32_t) * items, differ.data());
  kernel.setArg(0, first_bits);
  kernel.setArg(1, count);
  kernel.setArg(2, codes);
  kernel.setArg(3, differ_buf);
  rt.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(items), cl::NDRange(local));
  // Mapping a USE_HOST_PTR buffer on a CPU device returns the host memory itself: no copy.
  void* p = rt.queue().enqueueMapBuffer(codes, CL_TRUE, CL_MAP_READ, 0, sizeof(uint32_t) * count);
  if (p != out.data()) std::memcpy(out.data(), p, sizeof(uint32_t) * count);
  rt.queue().enqueueUnmapMemObject(codes, p);
  void* q =
      rt.queue().enqueueMapBuffer(differ_buf, CL_TRUE, CL_MAP_READ, 0, sizeof(uint32_t) * items);
  if (q != differ.data()) std::memcpy(differ.data(), q, sizeof(uint32_t) * items);
  rt.queue().enqueueUnmapMemObject(differ_buf, q);
  rt.queue().finish();
  uint64_t total = 0;
  for (uint32_t d : differ) total += d;
  return total;
}

std::vector<uint32_t> device_encode(OpenClRuntime& rt, const StorageFormat& f,
                                    const std::vector<float>& values) {
  std::vector<uint32_t> codes;
  codes.reserve(values.size());
  std::vector<uint32_t> one;
  for (float v : values) {
    uint32_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    device_encode_range(rt, f, bits, 1, one);
    codes.push_back(one.front());
  }
  return codes;
}

}  // namespace depthprec
