// OpenCL platform and device selection, one context, an in-order queue per host thread, and an
// in-process cache of built programs keyed by (source, build options, device).
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "host/runtime/cl.h"
#include "host/runtime/program_cache.h"

namespace depthprec {

struct DeviceInfo {
  int platform_index = 0;
  int device_index = 0;
  std::string platform_name;
  std::string platform_version;
  std::string device_name;
  std::string device_type;
  std::string opencl_c_version;
  unsigned compute_units = 0;
  bool fp64 = false;
  bool fp32_denormals = false;
  unsigned long long global_mem_bytes = 0;
};

// Every device of every platform. Throws RuntimeError naming the package to install when the
// ICD loader finds no platform.
std::vector<DeviceInfo> list_devices();

// The environment variable that selects a device when --device is not given.
constexpr const char* kDeviceEnvVar = "DEPTHPREC_DEVICE";

class OpenClRuntime {
 public:
  // selector: "" (then $DEPTHPREC_DEVICE, then the first PoCL CPU device, then the first CPU
  // device), "P:D" (platform and device index as `depthprec devices` lists them), or a
  // case-insensitive part of the platform or device name.
  explicit OpenClRuntime(const std::string& selector = "");

  const DeviceInfo& info() const { return info_; }
  std::string description() const;
  cl::Context& context() { return context_; }
  // The calling thread's in-order queue (profiling on), made on first use: host threads driving
  // separate evaluations (run_scene's jobs) each wait only for their own commands, and the device
  // runs both threads' work-groups side by side.
  cl::CommandQueue& queue();
  cl::Device& device() { return device_; }

  // The program built from an embedded source (path relative to the project root) with the
  // given options; built once per (path, options) and kept. Throws RuntimeError with the build
  // log and the options on failure.
  // A program compiled by an earlier run is loaded from the program binary cache
  // (host/runtime/program_cache.h) instead; programs built here are stored there when the
  // runtime closes, with the work-group functions their kernels' launches compiled.
  cl::Program program(const std::string& path, const std::string& options);
  ~OpenClRuntime();
  OpenClRuntime(const OpenClRuntime&) = delete;
  OpenClRuntime& operator=(const OpenClRuntime&) = delete;

 private:
  DeviceInfo info_;
  cl::Device device_;
  cl::Context context_;
  std::mutex queues_mutex_;
  std::map<std::thread::id, cl::CommandQueue> queues_;
  std::mutex programs_mutex_;
  struct BuiltProgram {
    cl::Program program;
    std::string key;          // its program binary cache key
    size_t loaded_bytes = 0;  // the binary it was loaded from (0: compiled from source)
  };
  std::map<std::pair<std::string, std::string>, BuiltProgram> cache_;
  ProgramBinaryCache binaries_;
};

// Work-group size of every 1-D launch: fixed, because PoCL compiles a kernel once per local size,
// and letting it choose per launch (a new size for every batch shape) recompiles again and again.
constexpr size_t kWorkGroup = 16;
// n rounded up to a whole number of work-groups.
inline size_t padded_size(size_t n) {
  return (n + kWorkGroup - 1) / kWorkGroup * kWorkGroup;
}

// Options every depthprec program is built with: OpenCL C 1.2, IEEE division (docs/spec.md's GPU
// divides correctly rounded), denormals kept unless flush is asked for.
std::string base_build_options(bool flush_denormals);

// The environment variable that keeps the compiler's warnings ("on"): for kernel developers.
constexpr const char* kKernelWarningsEnvVar = "DEPTHPREC_KERNEL_WARNINGS";

// options as the driver gets them: with the compiler's warnings off (OpenCL's -w). PoCL compiles
// with an embedded clang, which ends a compile that warned with a line such as "151 warnings
// generated." written straight to stderr, past -q and past any PoCL setting (POCL_DEBUG governs
// PoCL's own messages, which stay off). Errors are not affected: a failing build's log is in the
// error thrown. With $DEPTHPREC_KERNEL_WARNINGS=on the options are left as they are (other cache
// entries, so compiled cold) and compile_program prints each compiled program's log.
std::string compiler_options(const std::string& options);

// Compiles source for device as every depthprec program is compiled (compiler_options). Throws
// RuntimeError with the options and the build log on failure; what names the program there.
cl::Program compile_program(cl::Context& context, const cl::Device& device,
                            const std::string& source, const std::string& options,
                            const std::string& what);

}  // namespace depthprec
