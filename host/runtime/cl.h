// The one place that includes the Khronos C++ bindings, with the version macros they require.
#pragma once

#define CL_HPP_TARGET_OPENCL_VERSION 120
#define CL_HPP_MINIMUM_OPENCL_VERSION 120
#define CL_HPP_ENABLE_EXCEPTIONS
#include <CL/opencl.hpp>
#include <vector>

namespace depthprec {

// Sets a kernel's arguments 0, 1, 2, ... in the order given, as the kernel declares them.
template <class... Args>
void set_args(cl::Kernel& kernel, const Args&... args) {
  cl_uint index = 0;
  (kernel.setArg(index++, args), ...);
}

// A read-only device copy of a host array.
template <class T>
cl::Buffer buffer_of(const cl::Context& context, const std::vector<T>& v) {
  return cl::Buffer(context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(T) * v.size(),
                    const_cast<T*>(v.data()));
}

// The device time of a finished command (its queue profiles).
inline double device_seconds(const cl::Event& e) {
  return 1e-9 * static_cast<double>(e.getProfilingInfo<CL_PROFILING_COMMAND_END>() -
                                    e.getProfilingInfo<CL_PROFILING_COMMAND_START>());
}

}  // namespace depthprec
