// The Lapidous-Jiao average depth error (LJ99 eqs. 6-7, docs/spec.md 6) on the host and on the
// OpenCL device. The per-sample formulas are interface/lj_formulas.h, shared by both; this file
// parses the user's words, validates, and sums.
#pragma once

#include <optional>
#include <string>

#include "host/model/storage_format.h"
#include "host/model/technique.h"
#include "interface/lj_formulas.h"

namespace depthprec {

class OpenClRuntime;  // host/runtime/opencl_runtime.h

enum class LjBuffer {
  z = LJ_Z,
  w = LJ_W,
  inverse_w = LJ_INVERSE_W,
  complementary_z = LJ_COMPLEMENTARY_Z
};
enum class LjSampling { uniform = LJ_UNIFORM, increasing = LJ_INCREASING };

const char* to_string(LjBuffer b);
LjBuffer parse_lj_buffer(const std::string& s);  // throws InputError
const char* to_string(LjSampling s);
LjSampling parse_lj_sampling(const std::string& s);

// The emulated technique whose mapping is the buffer's, in the zero_to_one depth range (LJ99's D
// in [0, 1]): Z = standard, W = w_buffer, inverse W = inverse_w (d/Ze), complementary Z =
// reversed.
Technique lj_technique(LjBuffer b);

struct LjConfig {
  LjBuffer buffer = LjBuffer::z;
  double near = 1, far = 100;
  long long samples = 1000000;  // N, both ends included
  LjSampling sampling = LjSampling::uniform;
  lj_config shared() const;
};

void validate(const LjConfig& c);  // throws InputError naming the parameter

struct LjResult {
  double ae = 0;              // average normalised error; +inf if any sample passes the pole
  double vertex_limited = 0;  // fraction of samples whose per-vertex term is >= the per-pixel one
  long long infinite_samples = 0;
  long long samples = 0;
};

// From partial sums (in order): the shared finishing step of host and device.
LjResult lj_finish(const LjConfig& c, const lj_partial* partials, size_t count);

// The Lapidous-Jiao set-up a depth technique stands for over [near, far] (uniform sampling, the
// default N): none when the technique is not one of LJ99's buffers, or far is infinite (the
// metric normalises by f - d).
std::optional<LjConfig> lj_config_for(Technique t, double near, double far);

// Binary64 on the host.
LjResult lj_average_error(const LjConfig& c, const StorageFormat& f);
// Binary64 on the OpenCL device (kernels/lj.cl), chunks of samples per work-item.
LjResult lj_average_error_device(OpenClRuntime& rt, const LjConfig& c, const StorageFormat& f);

}  // namespace depthprec
