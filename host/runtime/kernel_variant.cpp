#include "host/runtime/kernel_variant.h"

#include <fmt/format.h>

#include "host/model/bound_model.h"
#include "host/model/vertex_stage.h"
#include "host/runtime/opencl_runtime.h"

namespace depthprec {

Technique depth_path(const Scene& scene, Technique t) {
  return t == Technique::layered ? scene.params.layer_mapping : t;
}

KernelVariant mts_variant(const Scene& scene, const EvalPair& pair) {
  const TechniqueInfo& ti = info(depth_path(scene, pair.technique));
  const StorageFormat f = scene.storage_format(pair);
  const int depth_from = static_cast<int>(ti.from), frag = static_cast<int>(ti.fragment);
  const Pipeline& p = scene.pipeline;
  // Log depth through the library log (or log2) is monotone only up to its error, <= 3 ulp in
  // OpenCL 1.2 (sec. 7.4); with the division or product after it, d is within 4 ulp of a monotone
  // function of w (three.js's further * 0.5 is exact). In codes that is at most s = ceil(4 ulp /
  // code spacing) + 1 on each side, and a piece decided from its ends needs B's and A's end codes
  // 4 s apart (both planes, both ends).
  // A fragment shader below binary32 (FRAG_MEDIUMP: mediump's binary16, the GLSL ES 1.00 highp
  // minimum) rounds the log's result to its precision, so its error can reach one step of d
  // there, 2^(24 - bits) binary32 ulps.
  const BoundModel* reduced = ti.from == DepthFrom::fragment
                                  ? shader_precision_model(static_cast<int>(p.shader_precision))
                                  : nullptr;
  long long log_slack = 0;
  if (ti.from == DepthFrom::fragment && takes_shader_log(ti)) {
    const df_format& fs = f.spec();
    const int fine = (fs.kind == DF_KIND_UNORM ? static_cast<int>(fs.bits) + 2 : fs.man_bits) +
                     (reduced ? 24 - reduced->shader_bits : 0);
    const long long s = (fine > 21 ? (1LL << (fine - 21)) : 1LL) + 1;
    log_slack = 4 * s;
  }
  KernelVariant v;
  v.program = "kernels/mts.cl";
  v.cache_a_codes = depth_from == 2 && !p.contraction;
  const int plane_form = p.plane == PlaneForm::origin_fma     ? 1
                         : p.plane == PlaneForm::origin_quads ? 2
                                                              : 0;
  const int llvmpipe_log = p.log == LogForm::llvmpipe ? 1 : 0;
  const int rte = vertex_path(p) == VertexPath::relative_to_eye ? 1 : 0;
  const std::string base = base_build_options(p.denormals == Denormals::flush);
  // An envelope's adversarial unorm conversion (interface/adversary.h dp_adv_unorm_code).
  const BoundModel* envelope = p.envelope.empty() ? nullptr : &bound_model(p.envelope);
  const bool adversary_codes = envelope && f.spec().kind == DF_KIND_UNORM;
  const double slack = adversary_codes ? adversary_code_slack(*envelope) : 0.0;
  v.options = fmt::format(
      "{} -DGRID={} -DDEPTH_FROM={} -DFRAG_DEPTH={} -DCOMPARE_GREATER={} -DCONTRACT={} "
      "-DLOG_CODE_SLACK={}UL -DCACHE_A_CODES={} -DPLANE_FORM={} -DLLVMPIPE_LOG={} "
      "-DCLIP_SLOTS={} -DRELATIVE_TO_EYE={} -DADVERSARY_CODES={} -DADVERSARY_CODE_SLACK={:a} "
      "-DFRAG_MEDIUMP={} {}",
      base, scene.plane_subdivisions, depth_from, frag, ti.greater ? 1 : 0, p.contraction ? 1 : 0,
      log_slack, v.cache_a_codes ? 1 : 0, plane_form, llvmpipe_log, p.clip_slots(), rte,
      adversary_codes ? 1 : 0, slack, reduced ? static_cast<int>(p.shader_precision) : 0,
      f.defines());
  // The set-up takes a log only for vertex-stage log depth, so elsewhere the log's form is left
  // out of its key.
  v.setup_program = "kernels/mts_setup.cl";
  v.setup_options = fmt::format(
      "{} -DGRID={} -DDEPTH_FROM={} -DCONTRACT={} -DPLANE_FORM={} -DLLVMPIPE_LOG={} "
      "-DCLIP_SLOTS={} -DRELATIVE_TO_EYE={}",
      base, scene.plane_subdivisions, depth_from, p.contraction ? 1 : 0, plane_form,
      depth_from == 1 ? llvmpipe_log : 0, p.clip_slots(), rte);
  // A variant with a driver's forms names the profile they are (or "custom-forms").
  const bool driver_forms = p.plane != PlaneForm::vertex || p.viewport == ViewportForm::fma ||
                            p.vertex == VertexForm::fma || p.log == LogForm::llvmpipe ||
                            p.clip == ClipForm::llvmpipe || p.conversion != Conversion::exact;
  const std::string profile = scene.json.contains("pipeline")
                                  ? scene.json["pipeline"].value("profile", "custom")
                                  : "custom";
  v.label = fmt::format("{}{}{}/{}/{}/{}{}{}", to_string(ti.from), frag ? ":" : "",
                        to_string(ti.fragment), ti.greater ? "GEQUAL" : "LEQUAL",
                        to_string(pair.depth_range), f.name(),
                        driver_forms ? "/" + (profile == "custom" ? "custom-forms" : profile) : "",
                        p.snap_bits ? fmt::format("/snap{}", p.snap_bits) : "") +
            (rte ? "/relative_to_eye" : "") + (envelope ? std::string("/") + envelope->name : "");
  return v;
}

}  // namespace depthprec
