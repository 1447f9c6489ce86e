#include "host/runtime/device_encode.h"

#include <cstring>

namespace depthprec {

namespace {

cl::Program encode_program(OpenClRuntime& rt, const StorageFormat& f) {
  return rt.program("kernels/encode.cl",
                    base_build_options(f.denormals() == Denormals::flush) + " " + f.defines());
}

// Maps a USE_HOST_PTR buffer for reading (on a CPU device the host memory itself: no copy).
void read_back(OpenClRuntime& rt, const cl::Buffer& buffer, void* host, size_t bytes) {
  void* p = rt.queue().enqueueMapBuffer(buffer, CL_TRUE, CL_MAP_READ, 0, bytes);
  if (p != host) std::memcpy(host, p, bytes);
  rt.queue().enqueueUnmapMemObject(buffer, p);
}

}  // namespace

uint64_t device_encode_range(OpenClRuntime& rt, const StorageFormat& f, uint32_t first_bits,
                             uint32_t count, std::vector<uint32_t>& out) {
  out.resize(count);
  if (count == 0) return 0;
  const auto program = encode_program(rt, f);
  const size_t local = 64;
  const auto round_up = [&](size_t n) { return (n + local - 1) / local * local; };
  cl::Buffer codes(rt.context(), CL_MEM_READ_WRITE | CL_MEM_USE_HOST_PTR, sizeof(uint32_t) * count,
                   out.data());
  cl::Kernel encode(program, "encode_range");
  encode.setArg(0, first_bits);
  encode.setArg(1, count);
  encode.setArg(2, codes);
  rt.queue().enqueueNDRangeKernel(encode, cl::NullRange, cl::NDRange(round_up(count)),
                                  cl::NDRange(local));
  std::vector<uint32_t> differ;
  if (!df_encode16_is_scalar(f.spec())) {
    differ.resize(round_up((count + 15u) / 16u));
    cl::Buffer differ_buf(rt.context(), CL_MEM_WRITE_ONLY | CL_MEM_USE_HOST_PTR,
                          sizeof(uint32_t) * differ.size(), differ.data());
    cl::Kernel lanes(program, "encode16_differs");
    lanes.setArg(0, first_bits);
    lanes.setArg(1, count);
    lanes.setArg(2, codes);
    lanes.setArg(3, differ_buf);
    rt.queue().enqueueNDRangeKernel(lanes, cl::NullRange, cl::NDRange(differ.size()),
                                    cl::NDRange(local));
    read_back(rt, differ_buf, differ.data(), sizeof(uint32_t) * differ.size());
  }
  read_back(rt, codes, out.data(), sizeof(uint32_t) * count);
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
