#include "host/lj/lj_metric.h"

#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "host/base/did_you_mean.h"
#include "host/base/errors.h"
#include "host/runtime/opencl_runtime.h"

namespace depthprec {

std::optional<LjConfig> lj_config_for(Technique t, double near, double far) {
  if (!info(t).lj_buffer || !std::isfinite(far)) return std::nullopt;
  LjConfig c;
  c.buffer = parse_lj_buffer(info(t).lj_buffer);
  c.near = near;
  c.far = far;
  return c;
}

const char* to_string(LjBuffer b) {
  switch (b) {
    case LjBuffer::z:
      return "z";
    case LjBuffer::w:
      return "w";
    case LjBuffer::inverse_w:
      return "inverse_w";
    case LjBuffer::complementary_z:
      return "complementary_z";
  }
  return "?";
}

LjBuffer parse_lj_buffer(const std::string& s) {
  for (const LjBuffer b :
       {LjBuffer::z, LjBuffer::w, LjBuffer::inverse_w, LjBuffer::complementary_z})
    if (s == to_string(b)) return b;
  throw InputError(
      fmt::format("unknown buffer type '{}'{}: expected z, w, inverse_w or complementary_z", s,
                  buffer_suggestion(s)));
}

const char* to_string(LjSampling s) {
  return s == LjSampling::uniform ? "uniform" : "increasing";
}

LjSampling parse_lj_sampling(const std::string& s) {
  if (s == "uniform") return LjSampling::uniform;
  if (s == "increasing") return LjSampling::increasing;
  throw InputError(fmt::format("unknown sampling '{}': expected uniform or increasing", s));
}

Technique lj_technique(LjBuffer b) {
  for (const auto& ti : technique_table())
    if (ti.lj_buffer && to_string(b) == std::string(ti.lj_buffer)) return ti.id;
  throw Error(ExitCode::internal, fmt::format("no technique is the LJ buffer {}", to_string(b)));
}

lj_config LjConfig::shared() const {
  lj_config c;
  c.buffer = static_cast<int>(buffer);
  c.sampling = static_cast<int>(sampling);
  c.d = near;
  c.f = far;
  c.n = samples;
  return c;
}

void validate(const LjConfig& c) {
  if (!(c.near > 0) || !std::isfinite(c.near))
    throw InputError(fmt::format("--near must be a finite distance > 0, not {}", c.near));
  if (!(c.far > c.near) || !std::isfinite(c.far))
    throw InputError(fmt::format("--far must be finite and > near ({}), not {}", c.near, c.far));
  if (c.samples < 2 || c.samples > 4000000000LL)
    throw InputError(
        fmt::format("--samples must be 2..4e9 (both ends are sampled), not {}", c.samples));
}

LjResult lj_finish(const LjConfig& c, const lj_partial* partials, size_t count) {
  lj_partial total{};
  for (size_t k = 0; k < count; ++k) {
    lj_add(&total.num, &total.num_c, partials[k].num);
    lj_add(&total.num, &total.num_c, partials[k].num_c);
    lj_add(&total.den, &total.den_c, partials[k].den);
    lj_add(&total.den, &total.den_c, partials[k].den_c);
    total.infinite += partials[k].infinite;
    total.vertex_limited += partials[k].vertex_limited;
  }
  LjResult r;
  r.samples = c.samples;
  r.infinite_samples = total.infinite;
  r.vertex_limited = static_cast<double>(total.vertex_limited) / static_cast<double>(c.samples);
  r.ae = total.infinite
             ? INFINITY
             : (total.num + total.num_c) / ((c.far - c.near) * (total.den + total.den_c));
  return r;
}

LjResult lj_average_error(const LjConfig& c, const StorageFormat& f) {
  validate(c);
  const lj_partial p = lj_sum_range(c.shared(), f.spec(), 0, c.samples);
  return lj_finish(c, &p, 1);
}

LjResult lj_average_error_device(OpenClRuntime& rt, const LjConfig& c, const StorageFormat& f) {
  validate(c);
  const std::string options = base_build_options(false) + " " + f.defines();
  cl::Kernel kernel(rt.program("kernels/lj.cl", options), "lj_partials");
  const long long chunk = 4096;
  // A fixed work-group size (PoCL compiles once per local size); the padding items see an empty
  // range and write zeros.
  const size_t local = 16;
  const size_t items =
      static_cast<size_t>((c.samples + chunk - 1) / chunk + local - 1) / local * local;
  cl::Buffer sums(rt.context(), CL_MEM_WRITE_ONLY, sizeof(double) * 4 * items);
  cl::Buffer counts(rt.context(), CL_MEM_WRITE_ONLY, sizeof(cl_long) * 2 * items);
  kernel.setArg(0, static_cast<cl_int>(c.buffer));
  kernel.setArg(1, static_cast<cl_int>(c.sampling));
  kernel.setArg(2, c.near);
  kernel.setArg(3, c.far);
  kernel.setArg(4, static_cast<cl_long>(c.samples));
  kernel.setArg(5, static_cast<cl_long>(chunk));
  kernel.setArg(6, sums);
  kernel.setArg(7, counts);
  rt.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(items), cl::NDRange(local));
  std::vector<double> s(4 * items);
  std::vector<cl_long> n(2 * items);
  rt.queue().enqueueReadBuffer(sums, CL_TRUE, 0, sizeof(double) * s.size(), s.data());
  rt.queue().enqueueReadBuffer(counts, CL_TRUE, 0, sizeof(cl_long) * n.size(), n.data());
  std::vector<lj_partial> parts(items);
  for (size_t k = 0; k < items; ++k)
    parts[k] = {s[4 * k], s[4 * k + 1], s[4 * k + 2], s[4 * k + 3], n[2 * k], n[2 * k + 1]};
  return lj_finish(c, parts.data(), parts.size());
}

}  // namespace depthprec
