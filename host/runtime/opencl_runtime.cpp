#include "host/runtime/opencl_runtime.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>

#include "host/base/embedded_sources.h"
#include "host/base/errors.h"
#include "host/base/fatal_signal.h"
#include "host/base/text.h"
#include "host/runtime/driver_cache.h"

namespace depthprec {

namespace {

constexpr const char* kNoPlatform =
    "no OpenCL platform found: install the PoCL CPU driver (apt-get install pocl-opencl-icd, or "
    "run scripts/setup.sh)";

std::vector<cl::Platform> platforms_or_throw() {
  open_driver_cache();  // PoCL reads POCL_CACHE_DIR when the platform is first touched
  std::vector<cl::Platform> platforms;
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error&) {
    platforms.clear();
  }
  if (platforms.empty()) throw RuntimeError(kNoPlatform);
  return platforms;
}

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == '\0' || std::isspace(static_cast<unsigned char>(s.back()))))
    s.pop_back();
  return s;
}

DeviceInfo describe(const cl::Platform& p, const cl::Device& d, int pi, int di) {
  DeviceInfo info;
  info.platform_index = pi;
  info.device_index = di;
  info.platform_name = trim(p.getInfo<CL_PLATFORM_NAME>());
  info.platform_version = trim(p.getInfo<CL_PLATFORM_VERSION>());
  info.device_name = trim(d.getInfo<CL_DEVICE_NAME>());
  const auto type = d.getInfo<CL_DEVICE_TYPE>();
  info.device_type = (type & CL_DEVICE_TYPE_CPU)   ? "CPU"
                     : (type & CL_DEVICE_TYPE_GPU) ? "GPU"
                                                   : "other";
  info.opencl_c_version = trim(d.getInfo<CL_DEVICE_OPENCL_C_VERSION>());
  info.compute_units = d.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
  info.fp64 = d.getInfo<CL_DEVICE_DOUBLE_FP_CONFIG>() != 0;
  info.fp32_denormals = (d.getInfo<CL_DEVICE_SINGLE_FP_CONFIG>() & CL_FP_DENORM) != 0;
  info.global_mem_bytes = d.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
  return info;
}

struct Candidate {
  cl::Platform platform;
  cl::Device device;
  DeviceInfo info;
};

// Every device of every platform, numbered as `depthprec devices` lists them (a platform whose
// device query fails has none: clinfo lists those, depthprec does not).
std::vector<Candidate> enumerate_devices() {
  const auto platforms = platforms_or_throw();
  std::vector<Candidate> all;
  for (size_t pi = 0; pi < platforms.size(); ++pi) {
    std::vector<cl::Device> devices;
    try {
      platforms[pi].getDevices(CL_DEVICE_TYPE_ALL, &devices);
    } catch (const cl::Error&) {
      continue;
    }
    for (size_t di = 0; di < devices.size(); ++di)
      all.push_back(
          {platforms[pi], devices[di],
           describe(platforms[pi], devices[di], static_cast<int>(pi), static_cast<int>(di))});
  }
  install_fatal_signal_report();  // over the handlers PoCL's LLVM installed meanwhile
  return all;
}

}  // namespace

std::vector<DeviceInfo> list_devices() {
  std::vector<DeviceInfo> out;
  for (const auto& c : enumerate_devices()) out.push_back(c.info);
  return out;
}

OpenClRuntime::OpenClRuntime(const std::string& selector_arg)
    : binaries_(ProgramBinaryCache::from_environment()) {
  std::string selector = selector_arg;
  if (selector.empty()) {
    if (const char* env = std::getenv(kDeviceEnvVar)) selector = env;
  }
  const std::vector<Candidate> all = enumerate_devices();
  if (all.empty()) throw RuntimeError(kNoPlatform);

  const Candidate* chosen = nullptr;
  if (selector.empty()) {
    for (const auto& c : all)
      if (!chosen && c.info.device_type == "CPU" &&
          to_lower(c.info.platform_name).find("portable computing language") != std::string::npos)
        chosen = &c;
    for (const auto& c : all)
      if (!chosen && c.info.device_type == "CPU") chosen = &c;
    if (!chosen) chosen = &all.front();
  } else {
    int pi = -1, di = -1;
    char tail = 0;
    if (std::sscanf(selector.c_str(), "%d:%d%c", &pi, &di, &tail) == 2) {
      for (const auto& c : all)
        if (c.info.platform_index == pi && c.info.device_index == di) chosen = &c;
    } else {
      for (const auto& c : all)
        if (!chosen &&
            (to_lower(c.info.device_name).find(to_lower(selector)) != std::string::npos ||
             to_lower(c.info.platform_name).find(to_lower(selector)) != std::string::npos))
          chosen = &c;
    }
    if (!chosen) {
      std::string known;
      for (const auto& c : all)
        known += fmt::format("\n  {}:{}  {} / {}", c.info.platform_index, c.info.device_index,
                             c.info.platform_name, c.info.device_name);
      throw RuntimeError(fmt::format(
          "no OpenCL device matches '{}' (from --device or ${}); expected P:D or part of a name "
          "among:{}",
          selector, kDeviceEnvVar, known));
    }
  }
  info_ = chosen->info;
  device_ = chosen->device;
  try {
    context_ = cl::Context(device_);
    (void)queue();  // the constructing thread's queue: a device that cannot make one fails here
  } catch (const cl::Error& e) {
    throw RuntimeError(
        fmt::format("cannot open OpenCL device {}: {} ({})", description(), e.what(), e.err()));
  }
}

std::string OpenClRuntime::description() const {
  return fmt::format("{} / {} ({})", info_.platform_name, info_.device_name,
                     info_.opencl_c_version);
}

cl::CommandQueue& OpenClRuntime::queue() {
  std::lock_guard<std::mutex> lock(queues_mutex_);
  auto it = queues_.find(std::this_thread::get_id());
  // Profiling on: kernel time per launch is reported next to wall time.
  if (it == queues_.end())
    it = queues_
             .emplace(std::this_thread::get_id(),
                      cl::CommandQueue(context_, device_, CL_QUEUE_PROFILING_ENABLE))
             .first;
  return it->second;
}

std::string compiler_options(const std::string& options) {
  const char* warnings = std::getenv(kKernelWarningsEnvVar);
  if (warnings && std::string(warnings) == "on") return options;
  return options + " -w";
}

cl::Program compile_program(cl::Context& context, const cl::Device& device,
                            const std::string& source, const std::string& options,
                            const std::string& what) {
  const std::string built_with = compiler_options(options);
  cl::Program program(context, source);
  try {
    program.build({device}, built_with.c_str());
  } catch (const cl::Error& e) {
    std::string log;
    try {
      log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device);
    } catch (const cl::Error&) {
      log = "(no build log)";
    }
    throw RuntimeError(
        fmt::format("building OpenCL program {} failed ({})\n  options: {}\n  build log:\n{}", what,
                    e.err(), built_with, log));
  }
  if (built_with == options) {  // $DEPTHPREC_KERNEL_WARNINGS=on: the log asked for
    const std::string log = trim(program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device));
    if (!log.empty())
      fmt::print(stderr, "depthprec: build log of {} ({}):\n{}\n", what, built_with, log);
  }
  return program;
}

std::string base_build_options(bool flush_denormals) {
  std::string o = "-cl-std=CL1.2 -cl-fp32-correctly-rounded-divide-sqrt";
  if (flush_denormals) o += " -cl-denorms-are-zero";
  return o;
}

cl::Program OpenClRuntime::program(const std::string& path, const std::string& options) {
  std::lock_guard<std::mutex> lock(programs_mutex_);
  const auto key = std::make_pair(path, options);
  const auto it = cache_.find(key);
  if (it != cache_.end()) return it->second.program;
  const std::string source = expand_embedded(path);
  BuiltProgram built;
  // Everything a binary depends on: a driver upgrade or an edited kernel is another key.
  const std::string built_with = compiler_options(options);
  built.key = fmt::format("{}\n{}\n{}\n{}\n{}\n{}\n{}", info_.platform_name, info_.platform_version,
                          info_.device_name, device_.getInfo<CL_DRIVER_VERSION>(), path, built_with,
                          source);
  if (const auto binary = binaries_.load(built.key)) {
    try {
      cl::Program from_binary(context_, {device_}, cl::Program::Binaries{*binary});
      from_binary.build({device_}, built_with.c_str());
      built.program = from_binary;
      built.loaded_bytes = binary->size();
    } catch (const cl::Error&) {
      binaries_.forget(built.key);  // not loadable here after all: compiled again below
    }
  }
  if (built.loaded_bytes == 0)
    built.program = compile_program(context_, device_, source, options,
                                    fmt::format("{} on {}", path, description()));
  cache_.emplace(key, built);
  return built.program;
}

OpenClRuntime::~OpenClRuntime() {
  // Programs whose binary grew here (compiled from source, or new work-group functions) are
  // kept for the next run; nothing a cache write does may fail the run that is ending.
  if (binaries_.writable()) {  // exporting a binary compiles: only when it is kept
    for (const auto& [name, built] : cache_) {
      try {
        const auto binaries = built.program.getInfo<CL_PROGRAM_BINARIES>();
        if (!binaries.empty() && binaries.front().size() != built.loaded_bytes)
          binaries_.store(built.key, binaries.front());
      } catch (...) {
      }
    }
  }
  record_driver_cache();  // what PoCL compiled for this run, checked at the next one
}

}  // namespace depthprec
