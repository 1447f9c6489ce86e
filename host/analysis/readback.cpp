#include "host/analysis/readback.h"

#include <cmath>

#include "host/model/frame_setup.h"
#include "host/model/resolve.h"

namespace depthprec {

namespace {

using quad = __float128;

// three.js's packing chunk, perspectiveDepthToViewZ (docs/spec.md 8), with the camera's near and
// far as binary32 uniforms: the standard branch, and the USE_REVERSED_DEPTH_BUFFER one (r185),
// which takes the reversed depth as stored. w = -viewZ.
float threejs_read(float n, float f, float d, bool reversed) {
  const float view_z = reversed ? (n * f) / ((n - f) * d - n) : (n * f) / ((f - n) * d - f);
  return -view_z;
}

// Godot's inverse projection (advanced_postprocessing.rst): ndc = (uv, depth) in the Vulkan range,
// (uv, depth) * 2 - 1 in OpenGL's; view = INV_PROJECTION_MATRIX * vec4(ndc, 1); view.xyz /= view.w;
// -view.z. At the centre of the screen (ndc x = y = 0) only the inverse's z and w rows take part:
// P's (0, 0, A, B) and (0, 0, -1, 0) invert to (0, 0, 0, -1) and (0, 0, 1/B, A/B), computed in
// binary64 from P's binary32 entries and uploaded as binary32 (Godot inverts in real_t, binary32
// by default: its entries may differ from these by a rounding).
float godot_read(const ProbeConstants& pc, bool gl, float d) {
  const double a = pc.P[10], b = pc.P[11];
  Mat4f inv{};
  inv[2 * 4 + 3] = -1.0f;
  inv[3 * 4 + 2] = static_cast<float>(1.0 / b);
  inv[3 * 4 + 3] = static_cast<float>(a / b);
  const float ndc[4] = {0.0f, 0.0f, gl ? d * 2.0f - 1.0f : d, 1.0f};
  const float view_z = mat_row_dot(inv, 2, ndc), view_w = mat_row_dot(inv, 3, ndc);
  return -(view_z / view_w);
}

// The binary32 inverse, each operation rounded, with the uniforms an engine uploads: near and far
// (and k) as binary32, Cesium's log2(f - n + 1) computed in binary64 as its UniformState does.
float shader_read(Inverse inv, const ProbeConstants& pc, const EvalPair& pair,
                  const ResolveSetup& m, float d) {
  const float n = pc.near, f = pc.far;
  switch (inv) {
    case Inverse::threejs:
      return threejs_read(n, f, d, info(m.technique).map == DepthMap::reversed);
    case Inverse::godot:
      return godot_read(pc, pair.depth_range == DepthRange::gl, d);
    case Inverse::linear:
      return n + d * (f - n);
    case Inverse::w_buffer:
      return d * f;
    case Inverse::exp2: {
      // three.js's curve is Gilg's with k = 1, whatever the scene's log_k
      const float k = info(m.technique).map == DepthMap::log ? pc.log_k : 1.0f;
      return (std::exp2(d * std::log2(k * f + 1.0f)) - 1.0f) / k;
    }
    case Inverse::cesium: {
      const float log2_far = static_cast<float>(std::log2(m.far - m.near + 1.0));
      return (std::exp2(d * log2_far) - 1.0f) + n;
    }
  }
  return NAN;
}

}  // namespace

const char* to_string(Inverse i) {
  switch (i) {
    case Inverse::threejs:
      return "threejs";
    case Inverse::godot:
      return "godot";
    case Inverse::linear:
      return "linear";
    case Inverse::w_buffer:
      return "w_buffer";
    case Inverse::exp2:
      return "exp2";
    case Inverse::cesium:
      return "cesium";
  }
  return "?";
}

std::vector<Inverse> inverses_of(Technique t) {
  switch (info(t).map) {
    case DepthMap::standard:
    case DepthMap::reversed:
      return {Inverse::threejs, Inverse::godot};
    case DepthMap::infinite:
    case DepthMap::n_over_w:
      return {Inverse::godot};
    case DepthMap::linear:
      return {Inverse::linear};
    case DepthMap::w_over_f:
      return {Inverse::w_buffer};
    case DepthMap::log:
    case DepthMap::log2_one_plus_w:
      return {Inverse::exp2};
    case DepthMap::log2_from_near:
      return {Inverse::cesium};
  }
  return {};
}

double ReadbackRow::relative_error() const {
  return std::fabs(error()) / distance;
}

const char* ReadbackRow::dominant() const {
  return std::fabs(arithmetic_error()) > std::fabs(storage_error()) ? "arithmetic" : "storage";
}

std::vector<ReadbackRow> readback(const Scene& scene, const EvalPair& pair, double w) {
  const ResolveSetup m = mapping_at(pair.technique, scene.near, scene.far, scene.params, w);
  validate(m);
  check_stored_distance(m, w, "--distances");
  const StorageFormat f = scene.storage_format(pair);
  const ProbeConstants pc = probe_constants(scene, pair, w);  // for layered, w's layer
  const DistanceResolution r = resolve_distance(m, f, w);
  const double value = f.decode(r.code);
  const quad exact =
      distance_of_depth<quad>(m.technique, m.near, m.far, m.params, static_cast<quad>(value));
  std::vector<ReadbackRow> rows;
  for (const Inverse inv : inverses_of(m.technique)) {
    ReadbackRow row;
    row.pair = pair;
    row.inverse = inv;
    row.distance = w;
    row.code = r.code;
    row.depth = static_cast<float>(value);
    row.read = shader_read(inv, pc, pair, m, row.depth);
    row.exact = static_cast<double>(exact);
    row.code_gap = r.resolution;
    rows.push_back(row);
  }
  return rows;
}

}  // namespace depthprec
