// What the guaranteed MTS (host/mts/mts_bound.h) knows of a plane of the measurement over the whole
// rotation cube: ranges of eye distance at its vertices and at the kernel's pixel centres, and the
// exact depth maps and gaps the error bounds are held against (docs/bound.md).
#pragma once

#include <vector>

#include "host/base/binary32_error.h"
#include "host/model/bound_model.h"
#include "host/model/frame_setup.h"
#include "host/model/scene.h"
#include "host/model/storage_format.h"
#include "host/model/technique.h"
#include "host/model/vertex_stage.h"

namespace depthprec::bound {

// Everything about a row that does not depend on the separation.
struct RowModel {
  const Scene* scene = nullptr;
  EvalPair pair;
  ProbeConstants pc;  // plane A's constants: P in the matrix precision, the shaders' constants
  TechniqueInfo ti;   // the depth path's (layered: its layer mapping's)
  StorageFormat format;
  binary32_error::Rounding rounding;         // the fixed-function stages: binary32
  binary32_error::Rounding shader_rounding;  // the shaders: the model's precision
  const BoundModel* model = nullptr;         // the scene's bound_model
  // The shaders' largest magnitude: the model's, or GLSL ES mediump's 2^14 where the pipeline's
  // shader precision is mediump (as shader_rounding's bits are then at most 11).
  double shader_range = INFINITY;
  double a = 0, b = 0;  // the third row of the P the depths follow: z_clip = a e_z + b
  double scale = 1;     // window depth = scale z_ndc + (1 - scale): 0.5 under gl, else 1
  double P00 = 0, P11 = 0;
  double sin_tilt = 0, tan_tilt = 0;              // bounds over the cube (widened, docs/mts.md)
  double xn_max = 0, yn_max = 0;                  // |x_ndc|, |y_ndc| of the kernel's pixel centres
  double sign = 1;                                // +1 where plane B must store the larger depth
  VertexPath path = VertexPath::model_then_view;  // which matrices the GPU gets (vertex_stage.h)
  bool premultiplied = false, fragment = false, vertex_log = false;
  // Fragment-stage depth written by a mediump shader (interface/mediump_fragment.h): its varying
  // q and its uniforms in binary16 too; the largest uniform it holds (the range check's).
  bool fragment_mediump = false;
  double fragment_uniform_max = 0;
  // The orthographic projection: w = 1 exactly, z_ndc = a e_z + b = -a w + b with w the eye
  // distance (the perspective techniques' z_ndc is (-a w + b) / w).
  bool ortho = false;
};

// The row's model; throws InputError where the bound model has none (its message says why).
RowModel row_model(const Scene& scene, const EvalPair& pair, double z);

// The uniforms a fragment shader that writes depth reads (interface/mediump_fragment.h): near and
// range (linear), far (w_buffer), k and L (log), FC (three.js), near and 1/log2 (Cesium).
std::vector<double> fragment_uniforms(const RowModel& m);

// A plane at eye distance D over the cube.
struct PlaneGeometry {
  double D = 0, side = 0;
  double wv_lo = 0, wv_hi = 0;  // w at any vertex (and any point of the plane's square)
  double wp_lo = 0, wp_hi = 0;  // w at any pixel centre of the kernel
  double lateral = 0;           // |e_x|, |e_y| at any vertex
};
PlaneGeometry plane_geometry(const RowModel& m, double D);

// The distance a plane requested at D is drawn at: fl32(D) at the world origin (the GPU's
// model-view holds its translation in binary32 under either matrix precision), D itself away from
// it (its translation's rounding is a vertex error there).
double geometry_distance(const RowModel& m, double D);

// The exact window depth of eye distance w as the row's pipeline means it (with its binary32
// constants: P's entries, the shaders' L, FC, ...), and its largest slope |dF/dw| over [lo, hi].
double exact_depth(const RowModel& m, double w);
double depth_slope(const RowModel& m, double lo, double hi);

// The exact gap sign (F(lambda w) - F(w)) between plane B (lambda = D_B / D_A) and plane A at a
// pixel where A's distance is w, in forms that keep its digits when lambda is close to 1.
double exact_gap(const RowModel& m, double lambda_minus_one, double w);

}  // namespace depthprec::bound
