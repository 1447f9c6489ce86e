// The technique table (docs/spec.md 3), the one place that says how each technique turns eye
// distance w into window depth d: where depth is computed, the compare function, the third row of
// P, and the exact mapping D(w) the metrics invert.
#pragma once

#include <cmath>
#include <string>
#include <vector>

namespace depthprec {

enum class DepthRange { gl, zero_to_one };
const char* to_string(DepthRange r);
DepthRange parse_depth_range(const std::string& s);  // throws InputError

// Where d comes from, which decides the kernel's code path; the values are kernels/mts.cl's
// DEPTH_FROM and FRAG_DEPTH.
enum class DepthFrom {
  projection = 0,  // d = z_ndc of P (window transform per depth range)
  vertex_log = 1,  // z_clip rewritten per vertex (Gilg eq. 5, or three.js's), then as projection
  fragment = 2,    // d written by the fragment stage from the perspective-correct w
};
// The fragment stage's depth: Gilg's ln(k w + 1) / L (log), three.js's log2(1 + w) * FC * 0.5
// (threejs_log), Cesium's log2((w - n) + 1) / log2(f - n + 1) with its discard (cesium_log).
enum class FragmentDepth {
  none = 0,
  linear = 1,
  w_buffer = 2,
  log = 3,
  threejs_log = 4,
  cesium_log = 5
};
const char* to_string(DepthFrom f);  // "projection", "vertex_log", "fragment"
// "", "linear", "w_buffer", "log", "threejs_log", "cesium_log"
const char* to_string(FragmentDepth f);

// The exact mapping D(w) (docs/spec.md 3), one per family of techniques; the values are
// kernels/mts_exact.cl's DEPTH_MAP.
enum class DepthMap {
  standard = 0,
  infinite = 1,
  reversed = 2,
  n_over_w = 3,
  log = 4,  // ln(k w + 1) / ln(k f + 1)
  linear = 5,
  w_over_f = 6,
  log2_one_plus_w = 7,  // log2(1 + w) / log2(1 + f): three.js (near unused)
  log2_from_near = 8,   // log2(w - n + 1) / log2(f - n + 1): Cesium
};

enum class Technique {
  standard,
  infinite,
  reversed,
  reversed_infinite,
  log_vertex,
  log_fragment,
  log_threejs,
  log_threejs_vertex,
  log_cesium,
  linear,
  w_buffer,
  inverse_w,
  layered,
  orthographic,
};

struct TechniqueInfo {
  Technique id;
  const char* name;
  DepthFrom from;
  FragmentDepth fragment;
  bool greater;  // reversed mapping: nearer is larger, compare GEQUAL
  // The depth range the technique is meant for, used when a scene or command names none:
  // the reversed mappings need zero_to_one (in gl, 0.5*z_ndc + 0.5 adds 0.5 to a depth near 0
  // and throws away the floating-point precision they exist for).
  DepthRange range;
  // Whether a plane nearer than the near plane is clipped. log_vertex and log_threejs_vertex
  // rewrite z_clip so that every w in [0, far] maps into [0, 1]: they have no near clipping.
  bool clips_near;
  DepthMap map;           // the exact D(w) (layered: its layer mapping's, per layer)
  const char* lj_buffer;  // the Lapidous-Jiao buffer type it is (docs/spec.md 6), or nullptr
  const char* gpu_cost;   // what a real GPU pays for it beyond its arithmetic (`cost`)
};

const std::vector<TechniqueInfo>& technique_table();
const TechniqueInfo& info(Technique t);
// Whether the technique's depth goes through a shader's log (its exact map is a log): the kernel
// then matches the reference within a code, not bit for bit (the library log's error).
bool takes_shader_log(const TechniqueInfo& ti);
// The formula of vertex-stage log depth (DepthFrom::vertex_log), by the technique's map: Gilg's
// ln(k w + 1) / L (log_vertex) or three.js's log2(max(1e-6, w + 1)) * FC (log_threejs_vertex).
// The values are interface/mts_layout.h's MTS_VERTEX_LOG_* (the probe constant MTS_C_VERTEX_LOG).
enum class VertexLog { gilg = 0, threejs = 1 };
VertexLog vertex_log(const TechniqueInfo& ti);
Technique parse_technique(const std::string& s);  // throws InputError listing the names
std::string technique_names();                    // "standard, infinite, ..." for help texts
// Whether the technique clips at the far plane (the fragment-depth ones clip with the standard
// projection's volume) and so needs a finite far; infinite, reversed_infinite and inverse_w have
// none.
bool has_far_plane(Technique t);
// The techniques that need a finite far plane, for error messages: "standard, reversed, ...".
std::string finite_far_technique_names();

// Third row of P, (P[2][2], P[2][3]), computed term by term (orthographic's w row is (0, 0, 0, 1),
// the perspective techniques' (0, 0, -1, 0): host/model/frame_setup.cpp projection) in the
// arithmetic of T as an application writes it (T = float for matrix_precision float, double for
// double). The techniques whose depth is not the projection's (log_vertex rewrites z_clip, the
// fragment-depth ones ignore it) get the standard row for their geometry. far = +inf gives NaN
// entries for standard and reversed: a result the evaluator reports as non_finite.
template <class T>
struct Row3 {
  T a, b;
};

template <class T>
Row3<T> projection_row3(Technique t, DepthRange r, T n, T f) {
  const bool gl = r == DepthRange::gl;
  switch (t) {
    case Technique::infinite:
      return {T(-1), gl ? T(-2) * n : -n};
    case Technique::reversed:
      return {gl ? (f + n) / (f - n) : n / (f - n), gl ? T(2) * f * n / (f - n) : f * n / (f - n)};
    case Technique::reversed_infinite:
    case Technique::inverse_w:  // d = n/w: the same matrix as reversed_infinite
      return {gl ? T(1) : T(0), gl ? T(2) * n : n};
    case Technique::orthographic:  // z_ndc of the eye z itself, w = 1 (glOrtho, D3D's OrthoRH)
      return {gl ? T(-2) / (f - n) : T(-1) / (f - n), gl ? -(f + n) / (f - n) : -n / (f - n)};
    default:
      return {gl ? -(f + n) / (f - n) : -f / (f - n),
              gl ? T(-2) * f * n / (f - n) : -f * n / (f - n)};
  }
}

// Parameters of the techniques that have them.
struct TechniqueParams {
  double log_k = 1.0;
  int layers = 3;
  Technique layer_mapping = Technique::standard;
  double layer_overlap = 0.01;
};

// Window depth in [0,1] of eye distance w, the exact mapping in binary64 (for the metrics and
// the code/distance queries, never for the emulated pipeline). The same in both depth ranges.
double depth_of_distance(Technique t, double near, double far, const TechniqueParams& p, double w);

// Eye distance of window depth D: the inverse of depth_of_distance, in forms that keep full
// accuracy near D = 0 and D = 1 (no 1 - D·c with D·c close to 1), in the arithmetic of T (double,
// or __float128 where a difference of two distances must keep its digits; the log techniques
// evaluate in binary64, having no binary128 libm here). Throws InputError for `layered`, which has
// one mapping per layer.
[[noreturn]] void throw_layered_has_no_single_mapping();

template <class T>
T distance_of_depth(Technique t, T n, T f, const TechniqueParams& p, T D) {
  if (t == Technique::layered) throw_layered_has_no_single_mapping();
  switch (info(t).map) {
    case DepthMap::standard:  // D = f(Ze - n)/((f - n)Ze); 1 - D is exact for D >= 0.5
      return n * f / (f * (T(1) - D) + n * D);
    case DepthMap::infinite:
      return n / (T(1) - D);
    case DepthMap::reversed:  // D = n(f - Ze)/((f - n)Ze)
      return n * f / (n + D * (f - n));
    case DepthMap::n_over_w:
      return n / D;
    case DepthMap::linear:
      return n + D * (f - n);
    case DepthMap::w_over_f:
      return D * f;
    case DepthMap::log:
      return T(std::expm1(double(D) * std::log1p(p.log_k * double(f))) / p.log_k);
    case DepthMap::log2_one_plus_w:  // (f + 1)^D - 1
      return T(std::expm1(double(D) * std::log1p(double(f))));
    case DepthMap::log2_from_near:  // (f - n + 1)^D - 1 + n
      return n + T(std::expm1(double(D) * std::log1p(double(f - n))));
  }
  throw_layered_has_no_single_mapping();
}

// Layer i = 0..L-1 of `layered`: geometric bounds between near and far, each layer's far bound
// pushed out by the overlap (the last ends at far). layer_of() is the layer holding distance z.
struct Layer {
  double near, far;
};
Layer layer_bounds(int i, double near, double far, const TechniqueParams& p);
int layer_of(double z, double near, double far, const TechniqueParams& p);

}  // namespace depthprec
