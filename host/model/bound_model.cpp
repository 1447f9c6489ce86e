#include "host/model/bound_model.h"

#include <fmt/format.h>

#include "host/base/errors.h"

namespace depthprec {

const std::vector<BoundModel>& bound_models() {
  // The unorm widths: the exact conversion 1 code; llvmpipe's binary32 product then rint
  // 1 + 2^-7, 3/2, 3; softpipe's truncation after a binary32 product 1 + 2^-8, 2, just over 1
  // (kernels/mts/bounds.cl GAP_CODE_WIDTH, tests/base/binary32_error_proof.cpp); D3D's 0.6 ulp
  // either side, 1.2; Vulkan's either of the two nearest codes one more than the binary32
  // product leaves (an exact value maps to one code over an interval 2 codes wide, not 1).
  static const std::vector<BoundModel> models = {
      {"binary32",
       "every binary32 step correctly rounded, in any order, fused or not, with every choice the "
       "ideal, llvmpipe and softpipe profiles make",
       "IEEE 754 binary32; the profiles (docs/spec.md 2)",
       true,
       5,
       5,
       1,
       {1.0078125, 2, 3},
       {0, 1.25, 0},
       8,
       0,
       0,
       24,
       INFINITY,
       0,
       nullptr,
       14},
      {"ideal",
       "the ideal profile's choices alone (docs/spec.md 2)",
       "IEEE 754 binary32; OpenCL 1.2's log (3 ulp)",
       false,
       2,
       2,
       1,
       {1, 1, 1},
       {0, 0, 0},
       6,
       0,
       0},
      {"llvmpipe",
       "the llvmpipe profile's choices alone",
       "Mesa 22.3 llvmpipe (docs/validation.md)",
       true,
       3,
       3,
       1,
       {1.0078125, 1.5, 3},
       {0, 1.25, 0},
       8,
       0,
       0},
      {"softpipe",
       "the softpipe profile's choices alone",
       "Mesa 22.3 softpipe (docs/validation.md)",
       true,
       5,
       5,
       1,
       {1.00390625, 2, 1.000001},
       {0, 1, 0},
       8,
       0,
       0,
       24,
       INFINITY,
       0,
       nullptr,
       14},
      {"d3d11",
       "what Direct3D 11.3 allows: binary32 within 0.5 ulp, reciprocal within 1 ulp, positions "
       "snapped to 8 fractional bits, unorm conversion within 0.6 ulp, any evaluation form",
       "D3D 11.3 functional spec 3.1.3 (arithmetic, x/y as x (1/y)), 3.1.3.2 (denormals flushed), "
       "3.2.3.6 (float to unorm 0.6 ulp), 15.16 (8-bit snapping)",
       true,
       5,
       5,
       2,
       {1.2, 1.2, 1.2},
       {0, 0, 0},
       8,
       8,
       0,
       24,
       INFINITY,
       0.6,
       "unorm16, unorm24, float32"},  // D16_UNORM, D24_UNORM_S8_UINT, D32_FLOAT
      {"vulkan_min",
       "the least a Vulkan implementation must do: 4 sub-pixel bits, depth interpolated to 1 part "
       "in 10^5, a unorm code either of the two nearest, otherwise as binary32",
       "Vulkan: subPixelPrecisionBits minimum 4 (Limits); fixed-function results 'accurate to "
       "about 1 part in 10^5' (Fundamentals, Floating-Point Computation), taken for the "
       "interpolated depth; float to unorm 'one of the two ... closest' integers (Fundamentals, "
       "Conversion From Floating-Point to Normalized Fixed-Point)",
       true,
       5,
       5,
       1,
       {2.0078125, 3, 4},
       {0, 0, 0},
       8,
       4,
       1e-5,
       24,
       INFINITY,
       1,
       "unorm16, unorm24, float32"},  // D16_UNORM, X8_D24_UNORM_PACK32, D32_SFLOAT
      {"gles_mediump",
       "shaders in GLSL ES mediump (relative precision 2^-10, magnitudes to 2^14: binary16's), "
       "the fixed-function stages in binary32, otherwise as binary32",
       "GLSL ES 3.00 4.5.1 (mediump: relative precision 2^-10, range 2^14)",
       true,
       5,
       5,
       1,
       {1.0078125, 2, 3},
       {0, 1.25, 0},
       8,
       0,
       0,
       11,
       0x1.0p14,
       0,
       nullptr,
       14},
      {"gles2_highp",
       "shaders at the GLSL ES 1.00 highp minimum (relative precision 2^-16, magnitudes to 2^62: "
       "17 significant bits), the fixed-function stages in binary32, otherwise as binary32",
       "GLSL ES 1.00 4.5.2 (highp: relative precision 2^-16, range 2^62)",
       true,
       5,
       5,
       1,
       {1.0078125, 2, 3},
       {0, 1.25, 0},
       8,
       0,
       0,
       17,
       0x1.0p62,
       0,
       nullptr,
       14},
  };
  return models;
}

const BoundModel& bound_model(const std::string& name) {
  for (const BoundModel& m : bound_models())
    if (name == m.name) return m;
  throw InputError(fmt::format("unknown bound model '{}': one of {}", name, bound_model_names()));
}

const BoundModel* envelope_model(const std::string& name) {
  if (name == "none") return nullptr;
  std::string names = "none";
  for (const BoundModel& m : bound_models()) {
    if (name == m.name && m.has_adversary()) return &m;
    if (m.has_adversary()) names += std::string(", ") + m.name;
  }
  throw InputError(fmt::format("unknown envelope '{}': one of {}", name, names));
}

const BoundModel* shader_precision_model(int precision) {
  if (precision == 1) return &bound_model("gles_mediump");
  if (precision == 2) return &bound_model("gles2_highp");
  return nullptr;
}

double adversary_code_slack(const BoundModel& envelope) {
  const double t = envelope.adversary_conversion;
  return t >= 1 ? 0.0 : 1.0 - t + 0x1p-20;
}

std::string bound_model_names() {
  std::string out;
  for (const BoundModel& m : bound_models()) out += (out.empty() ? "" : ", ") + std::string(m.name);
  return out;
}

}  // namespace depthprec
