// The bound models of the guaranteed MTS (docs/bound.md): what an
// implementation's arithmetic may do, as the error bounds of host/mts/bound_plane.cpp read it. The
// default, binary32, holds every choice the emulated profiles make at once; a profile's own model
// holds its choices alone; an API's envelope holds what its specification allows (the section it
// comes from in `source`). A scene names one (`bound_model`); every per-model fact is here.
#pragma once

#include <cmath>
#include <string>
#include <vector>

namespace depthprec {

struct BoundModel {
  const char* name;
  const char* what;    // one line for docs and --help
  const char* source;  // where its tolerances come from
  bool clip_stage;     // vertices made by a clip stage (llvmpipe's: out + t (in - out))
  // Roundings of the plane's evaluation at the value's magnitude and at the slopes' reach: the
  // vertex-anchored form 2 and 2, llvmpipe's origin form with fma 3 and 3, softpipe's quads 5
  // and 5.
  int value_roundings, reach_roundings;
  double reciprocal_half_ulps;  // 1: correctly rounded; 2: within 1 ulp (D3D 11.3 3.1.3)
  // A unorm conversion's width in codes (code - d N within an interval this wide), for 16, 24
  // and 32 bits.
  double unorm_width[3];
  // The widest run of binary32 depths that store one code, in codes, under any conversion the
  // model allows, for 16, 24 and 32 bits: where each is a monotone function of the depth (the
  // profiles' are), two depths that store one code lie at most this far apart, which is all the
  // bound asks of the conversion (mts_bound.cpp collision_width). At most the width above, and
  // narrower where a binary32 product rounds before the conversion: a code's run spans that
  // rounding once, not the range of code - d N twice. 0: the width above (an API's envelope
  // lets neighbouring depths take either of two codes, in no order; softpipe's 16-bit fast path
  // steps codes without converting each depth; unorm32, where llvmpipe's runs of 2 codes are what
  // it renders, kept at the width's margin).
  double unorm_collision[3];
  double log_half_ulps;  // the shaders' log and log2
  int snap_bits;         // window positions snapped to 2^-bits; 0: as pipeline.snap says
  // Depth interpolation not otherwise specified: an error up to this fraction of the value.
  double interpolation_relative;
  // The shaders' precision (the vertex stage, and the fragment stage where it writes depth):
  // significand bits (24: binary32; 11: GLSL ES mediump, relative precision 2^-10) and the
  // largest magnitude they hold (mediump: 2^14).
  int shader_bits = 24;
  double shader_range = INFINITY;
  // An envelope's adversarial unorm conversion (pipeline.envelope, interface/adversary.h): a code
  // within this many codes of d (2^b - 1) on the side that helps the farther plane (D3D 0.6;
  // Vulkan's "either of the two nearest" 1); 0: the pipeline's own conversion. The envelope's
  // other freedoms are the fields above: the reciprocal (reciprocal_half_ulps 2: within 1 ulp),
  // the interpolation error, the snapping (its profile sets pipeline.snap to snap_bits).
  double adversary_conversion = 0;
  bool has_adversary() const { return adversary_conversion > 0; }
  // The depth formats the API has, "unorm16, unorm24, float32"; null: any. A row of another
  // format has no bound under the model: its conversion rules say nothing of it.
  const char* api_formats = nullptr;
  // softpipe's 16-bit fast path (Mesa's sp_quad_depth_test_tmp.h, for depth from the rasterizer):
  // a run of quads takes its first quad's codes and steps them by trunc(dz/dx N) per pixel, up to
  // this many pixels (flush_spans hands on quads of one 16-pixel chunk: 14), so a code drifts
  // from its conversion by up to that many times min(1, |dz/dx| N) and a hair
  // (mts_bound.cpp, stepped_code_drift). 0: none.
  int unorm16_step_pixels = 0;
};

// The entry of BoundModel's per-unorm arrays (unorm_width, unorm_collision) a unorm of `bits`
// takes: up to 16 bits the first, up to 24 the second, more the third.
inline int unorm_entry(unsigned bits) {
  return bits <= 16 ? 0 : bits <= 24 ? 1 : 2;
}

const std::vector<BoundModel>& bound_models();
const BoundModel& bound_model(const std::string& name);  // throws InputError naming the models
// pipeline.envelope's value: "none" (nullptr) or a model with an adversary; throws InputError
// naming them.
const BoundModel* envelope_model(const std::string& name);
// The model whose shaders' bits and range a pipeline.shader_precision below binary32 takes
// (interface/binary16.h's numbers: 1 mediump, gles_mediump; 2 es2_highp, gles2_highp); null for
// binary32.
const BoundModel* shader_precision_model(int precision);
// The slack of its adversarial unorm conversion (interface/adversary.h dp_adv_unorm_code): 1 - t
// for a tolerance of t codes, with a hair (2^-20) more below 1 so binary64 cannot carry a code
// past t; 0 for either of the two nearest codes (t = 1).
double adversary_code_slack(const BoundModel& envelope);
std::string bound_model_names();  // "binary32, ideal, ..."

}  // namespace depthprec
