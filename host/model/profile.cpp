#include "host/model/profile.h"

#include <fmt/format.h>

#include "host/base/errors.h"

namespace depthprec {

const std::vector<Profile>& profiles() {
  static const std::vector<Profile> table = {
      {"ideal",
       "the documented pipeline of docs/spec.md 2: planes anchored at a vertex, separate "
       "multiply and add",
       {"pipeline.plane=vertex", "pipeline.viewport=separate", "pipeline.vertex=separate",
        "pipeline.log=library", "pipeline.clip=none", "pipeline.conversion=exact",
        "pipeline.snap=none", "pipeline.shader_precision=highp", "pipeline.envelope=none"},
       "step"},
      // Mesa 22.3 as Debian 12 ships it (docs/validation.md): its vertex shader's fused products,
      // its depth-plane set-up and evaluation, its FMA viewport transform and its unorm
      // conversions, its log, its clip stage. Not modelled (yet): its fixed-point coverage.
      {"llvmpipe",
       "Mesa's llvmpipe (22.3): fused vertex-stage products, depth planes referred to the "
       "framebuffer origin and evaluated with FMA, FMA viewport transform, binary32 unorm "
       "conversions, its approximate log, its clip stage; bias r of unorm buffers 2/(2^n - 1)",
       {"pipeline.plane=origin_fma", "pipeline.viewport=fma", "pipeline.vertex=fma",
        "pipeline.log=llvmpipe", "pipeline.clip=llvmpipe", "pipeline.conversion=llvmpipe",
        "pipeline.snap=none", "pipeline.shader_precision=highp", "pipeline.envelope=none"},
       "double_step"},
      // Mesa 22.3's softpipe (docs/validation.md, "softpipe"): llvmpipe's draw module (its vertex
      // stage, viewport and clip stage), its own plane set-up stepped across 2x2 quads, truncated
      // unorm codes. Not modelled: its float edge-walking coverage, its shaders' log (the log
      // techniques differ), its depth bias (r = 1e-7 or 2e-5, no rule of --r-unorm).
      {"softpipe",
       "Mesa's softpipe (22.3): llvmpipe's vertex stage, viewport and clip stage, depth planes "
       "from the lowest vertex stepped across 2x2 quads, truncated unorm conversions; not its "
       "coverage, its shaders' log or its depth bias",
       {"pipeline.plane=origin_quads", "pipeline.viewport=fma", "pipeline.vertex=fma",
        "pipeline.log=llvmpipe", "pipeline.clip=llvmpipe", "pipeline.conversion=softpipe",
        "pipeline.snap=none", "pipeline.shader_precision=highp", "pipeline.envelope=none"},
       nullptr},
      // A mobile GPU running a vertex shader declared mediump (GLSL ES: relative precision 2^-10,
      // range 2^14; binary16 on the devices of the engines' reports, docs/spec.md 2): the ideal
      // pipeline otherwise.
      {"gles_mediump",
       "the ideal pipeline with a GLSL ES mediump vertex shader: binary16 uniforms, products and "
       "sums (interface/binary16.h)",
       {"pipeline.plane=vertex", "pipeline.viewport=separate", "pipeline.vertex=separate",
        "pipeline.log=library", "pipeline.clip=none", "pipeline.conversion=exact",
        "pipeline.snap=none", "pipeline.shader_precision=mediump", "pipeline.envelope=none"},
       "step"},
      // A device that offers the GLSL ES 1.00 highp minimum alone (relative precision 2^-16,
      // range 2^62; docs/spec.md 2): the ideal pipeline otherwise.
      {"gles2_highp",
       "the ideal pipeline with shaders at the GLSL ES 1.00 highp minimum: 17-bit uniforms, "
       "products and sums (interface/binary16.h)",
       {"pipeline.plane=vertex", "pipeline.viewport=separate", "pipeline.vertex=separate",
        "pipeline.log=library", "pipeline.clip=none", "pipeline.conversion=exact",
        "pipeline.snap=none", "pipeline.shader_precision=es2_highp", "pipeline.envelope=none"},
       "step"},
      // The API envelopes' adversaries (interface/adversary.h, docs/spec.md 2 "Envelopes"): the
      // ideal pipeline's forms, snapped to the sub-pixel bits the API requires at least, with the
      // adversarial choice at each freedom its specification leaves (host/model/bound_model.cpp);
      // each row bounded under the envelope's own model (the scene's bound_model follows
      // pipeline.envelope unless it is given).
      {"d3d11",
       "Direct3D 11.3's envelope, adversarially: the ideal pipeline snapped to 8 sub-pixel bits, "
       "each reciprocal of w the faithful rounding within 1 ulp that helps the farther plane, "
       "unorm "
       "codes within 0.6 of exact on its side",
       {"pipeline.plane=vertex", "pipeline.viewport=separate", "pipeline.vertex=separate",
        "pipeline.log=library", "pipeline.clip=none", "pipeline.conversion=exact",
        "pipeline.snap=8", "pipeline.shader_precision=highp", "pipeline.envelope=d3d11"},
       nullptr},
      {"vulkan_min",
       "the least Vulkan requires, adversarially: the ideal pipeline snapped to 4 sub-pixel bits, "
       "each triangle's depth moved by 1 part in 10^5 and each unorm code the one of the two "
       "nearest on the side that helps the farther plane",
       {"pipeline.plane=vertex", "pipeline.viewport=separate", "pipeline.vertex=separate",
        "pipeline.log=library", "pipeline.clip=none", "pipeline.conversion=exact",
        "pipeline.snap=4", "pipeline.shader_precision=highp", "pipeline.envelope=vulkan_min"},
       nullptr},
  };
  return table;
}

std::pair<std::string, nlohmann::json> pipeline_setting(const std::string& set) {
  const std::string prefix = "pipeline.";
  const auto eq = set.find('=');
  const std::string value = set.substr(eq + 1);
  const bool whole = !value.empty() && value.find_first_not_of("0123456789") == std::string::npos;
  return {set.substr(prefix.size(), eq - prefix.size()),
          whole ? nlohmann::json(std::stoi(value)) : nlohmann::json(value)};
}

const Profile& profile(const std::string& name) {
  for (const Profile& p : profiles())
    if (name == p.name) return p;
  throw InputError(fmt::format("unknown profile '{}' (allowed: {})", name, profile_names()));
}

std::string profile_names() {
  std::string out;
  for (const Profile& p : profiles()) out += (out.empty() ? "" : ", ") + std::string(p.name);
  return out;
}

}  // namespace depthprec
