#include "host/kernel_variant.h"

#include <fmt/format.h>

#include "host/opencl_runtime.h"

namespace depthprec {

Technique depth_path(const Scene& scene, Technique t) {
  return t == Technique::layered ? scene.params.layer_mapping : t;
}

KernelVariant mts_variant(const Scene& scene, const EvalPair& pair) {
  const TechniqueInfo& ti = info(depth_path(scene, pair.technique));
  const StorageFormat f = scene.storage_format(pair);
  const int depth_from = ti.from == DepthFrom::projection ? 0 : ti.from == DepthFrom::vertex_log ? 1 : 2;
  const int frag = ti.fragment == FragmentDepth::linear     ? 1
                   : ti.fragment == FragmentDepth::w_buffer ? 2
                   : ti.fragment == FragmentDepth::log      ? 3
                                                            : 0;
  const Pipeline& p = scene.pipeline;
  KernelVariant v;
  v.program = "kernels/mts.cl";
  v.options = fmt::format(
      "{} -DGRID={} -DDEPTH_FROM={} -DFRAG_DEPTH={} -DRANGE_GL={} -DCOMPARE_GREATER={} "
      "-DDIVIDE_EXACT={} -DCOMPOSE_PREMULT={} -DCONTRACT={} {}",
      base_build_options(p.denormals == Denormals::flush), scene.plane_subdivisions, depth_from,
      frag, pair.depth_range == DepthRange::gl ? 1 : 0, ti.greater ? 1 : 0,
      p.divide == Divide::exact ? 1 : 0, p.compose == Compose::premultiplied ? 1 : 0,
      p.contraction ? 1 : 0, f.defines());
  const char* from = depth_from == 0 ? "projection" : depth_from == 1 ? "vertex_log" : "fragment";
  const char* fd = frag == 1 ? "linear" : frag == 2 ? "w_buffer" : frag == 3 ? "log" : "";
  v.label = fmt::format("{}{}{}/{}/{}/{}", from, frag ? ":" : "", fd, ti.greater ? "GEQUAL" : "LEQUAL",
                        to_string(pair.depth_range), f.name());
  return v;
}

}  // namespace depthprec
