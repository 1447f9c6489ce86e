#include "host/audit/audit_setup.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <initializer_list>

#include "host/audit/depth_tolerance.h"
#include "host/base/errors.h"
#include "host/model/shader_log.h"
#include "host/runtime/kernel_variant.h"
#include "interface/audit_layout.h"
#include "interface/mts_layout.h"

namespace depthprec {

namespace {

// The view of an eye at `eye` with orthonormal axes right, up and back (the eye looks down -back).
Mat4d view_of(const Vec3& eye, const Vec3& right, const Vec3& up, const Vec3& back) {
  Mat4d v = mat_identity();
  const Vec3* axes[3] = {&right, &up, &back};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) v[r * 4 + c] = (*axes[r])[c];
    v[r * 4 + 3] = -dot(*axes[r], eye);
  }
  return v;
}

// x rounded to binary32 upwards (a bound stays a bound).
float rounded_up(double x) {
  const float f = static_cast<float>(x);
  return static_cast<double>(f) >= x ? f : std::nextafter(f, INFINITY);
}

// A draw as the application holds it (host/model/vertex_stage.h): its world matrix and the
// camera's view in binary64 (the glTF's node transforms, the camera), each held in the matrix
// precision, the same under every transform: this application forms no translation apart, so
// camera-relative it hands the GPU their product V M, formed in the matrix precision.
class AuditDraw final : public ApplicationDraw {
 public:
  AuditDraw(MatrixPrecision precision, const Draw& d, const AuditCamera& cam)
      : precision_(precision), d_(d), cam_(cam) {}
  Mat4d model(Transform) const override { return held_in(precision_, d_.world); }
  ViewMatrix view(Transform) const override {
    return {ViewMatrix::Form::general, held_in(precision_, cam_.view)};
  }
  Mat4d world() const override { return d_.world; }
  Vec3 eye() const override { return cam_.eye; }

 private:
  MatrixPrecision precision_;
  const Draw& d_;
  const AuditCamera& cam_;
};

}  // namespace

VertexStage draw_vertex_stage(const Scene& s, const ProbeConstants& pc, const Draw& d,
                              const AuditCamera& cam) {
  return vertex_stage(s.pipeline, pc.P_full, AuditDraw(s.pipeline.matrix_precision, d, cam));
}

AuditCamera look_at_camera(const std::array<double, 3>& eye, const std::array<double, 3>& target,
                           const std::array<double, 3>& up, double fov_y_deg, int width,
                           int height) {
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(eye[i]) || !std::isfinite(target[i]) || !std::isfinite(up[i]))
      throw InputError("--eye, --target and --up need finite coordinates");
  const Vec3 back = sub(eye, target);
  if (dot(back, back) == 0)
    throw InputError("--eye and --target are the same point: no view direction");
  const Vec3 z = normalized(back);
  const Vec3 x = cross(up, z);
  if (!(dot(x, x) > 1e-24 * dot(up, up)))
    throw InputError(fmt::format(
        "--up ({}, {}, {}) is parallel to the view direction; give another", up[0], up[1], up[2]));
  const Vec3 xn = normalized(x);
  AuditCamera c;
  c.description = fmt::format("eye ({}, {}, {}) target ({}, {}, {}) up ({}, {}, {})", eye[0],
                              eye[1], eye[2], target[0], target[1], target[2], up[0], up[1], up[2]);
  c.view = view_of(eye, xn, cross(z, xn), z);
  c.eye = eye;
  c.fov_y_deg = fov_y_deg;
  c.width = width;
  c.height = height;
  return c;
}

AuditCamera gltf_view(const GltfCamera& g, int width, int height) {
  Vec3 axes[3];
  for (int c = 0; c < 3; ++c) axes[c] = normalized({g.world[c], g.world[4 + c], g.world[8 + c]});
  AuditCamera c;
  c.description = "camera " + g.name;
  c.eye = {g.world[3], g.world[7], g.world[11]};
  c.view = view_of(c.eye, axes[0], axes[1], axes[2]);
  c.fov_y_deg = g.yfov * 180.0 / M_PI;
  c.width = width;
  c.height = height;
  return c;
}

Scene audit_scene(Scene s, const AuditCamera& cam) {
  s.viewport_w = s.kernel_w = cam.width;
  s.viewport_h = s.kernel_h = cam.height;
  s.fov_y_deg = cam.fov_y_deg;
  return s;
}

std::array<double, 4> pixel_ray(const Scene& s, const ProbeConstants& pc) {
  return {0.5f * static_cast<float>(s.viewport_w), 0.5f * static_cast<float>(s.viewport_h),
          pc.P_full[0], pc.P_full[5]};
}

std::vector<std::array<double, 4>> exact_planes(const SceneGeometry& g, const AuditCamera& cam) {
  std::vector<std::array<double, 4>> planes(g.triangles);
  for (const Draw& d : g.draws) {
    const Mat4d mv = mat_mul(cam.view, d.world);
    for (size_t t = 0; t < d.triangles.size(); ++t) {
      std::array<Vec3, 3> e;
      for (int k = 0; k < 3; ++k) {
        const auto& p = d.positions[d.triangles[t][k]];
        e[k] = transform_point(mv, p[0], p[1], p[2]);
      }
      const Vec3 n = cross(sub(e[1], e[0]), sub(e[2], e[0]));
      planes[d.first_triangle + t] = {n[0], n[1], n[2], dot(n, e[0])};
    }
  }
  return planes;
}

double ray_depth(const std::array<double, 4>& ray, const std::array<double, 4>& plane, float px,
                 float py) {
  const double rx = (static_cast<double>(px) / ray[0] - 1.0) / ray[2];
  const double ry = (static_cast<double>(py) / ray[1] - 1.0) / ray[3];
  return plane[3] / ((plane[0] * rx + plane[1] * ry) - plane[2]);
}

namespace {

using Boxes = std::vector<std::array<float, 4>>;  // per record: x min, x max, y min, y max

// A draw's vertices through the vertex stage: window positions, clip errors (the tolerance's),
// and which the set-up cannot use.
struct DrawVertices {
  std::vector<SetupVertex> v;
  std::vector<ClipError> error;
  std::vector<char> bad;
};

DrawVertices draw_vertices(const Scene& s, const AuditSetup& a, const Draw& d,
                           const AuditCamera& cam) {
  const TechniqueInfo& ti = info(depth_path(s, a.pair.technique));
  const bool gl = a.pair.depth_range == DepthRange::gl;
  const VertexStage st = draw_vertex_stage(s, a.pc, d, cam);
  DrawVertices dv;
  dv.v.resize(d.positions.size());
  dv.error.resize(d.positions.size());
  dv.bad.assign(d.positions.size(), 0);
  for (size_t i = 0; i < d.positions.size(); ++i) {
    const auto& p = d.positions[i];
    const float obj[4] = {p[0], p[1], p[2], 1.0f};
    float clip[4];
    vertex_clip(st, a.pc.P, obj, s.pipeline.vertex, clip);
    dv.error[i] = vertex_clip_error(a.pc, st, p);
    if (ti.from == DepthFrom::vertex_log)
      clip[2] = vertex_log_clip_z(a.pc, s.pipeline.log, gl, clip[3]);
    dv.v[i] = window_vertex(s, gl, clip, static_cast<int>(i));
    dv.bad[i] = vertex_non_finite(dv.v[i], ti.from != DepthFrom::fragment);
  }
  return dv;
}

// One set-up record of scene-wide triangle src from window vertices f (clip errors fe), with its
// tolerance, window depths and pixel box; none for a triangle that does not rasterise.
void append_record(const Scene& s, AuditSetup& a, Boxes& boxes, uint32_t src,
                   const SetupVertex* const f[3], const ClipError* const fe[3]) {
  const SetupTriangle st3 = setup_triangle(s.pipeline, f);
  if (!st3.valid) return;
  const RecordTolerance tol = record_tolerance(s, a.pair, a.pc, f, fe, st3.x0, st3.y0);
  for (const double x : {tol.constant, tol.e0, tol.ex, tol.ey, tol.shader})
    a.tolerance.push_back(rounded_up(x));
  a.records.push_back(st3);
  a.source.push_back(src);
  a.window_depths.push_back({f[0]->d, f[1]->d, f[2]->d});
  boxes.push_back({std::min({f[0]->x, f[1]->x, f[2]->x}), std::max({f[0]->x, f[1]->x, f[2]->x}),
                   std::min({f[0]->y, f[1]->y, f[2]->y}), std::max({f[0]->y, f[1]->y, f[2]->y})});
}

// Triangle t of draw d: culled, rasterised whole, or clipped into a fan. A triangle that crosses
// the near or far plane is clipped against all six planes, whatever pipeline.clip says: clipped
// at the near plane alone, its new vertices would land at the near plane's projection, up to
// millions of pixels off screen, where a binary32 set-up loses the depth plane (one anchored
// there, or at the origin, cancels away every bit that matters on screen). Real rasterizers never
// set up such a triangle: llvmpipe clips it to the viewport, hardware to a guard band a few
// viewports wide, homogeneous rasterizers never form the vertex. A triangle within the z planes
// is rasterised whole unless pipeline.clip is llvmpipe.
void set_up_triangle(const Scene& s, const Draw& d, size_t t, const DrawVertices& dv, AuditSetup& a,
                     Boxes& boxes) {
  const bool gl = a.pair.depth_range == DepthRange::gl;
  const bool depth_interpolated = info(depth_path(s, a.pair.technique)).from != DepthFrom::fragment;
  const uint32_t src = d.first_triangle + static_cast<uint32_t>(t);
  const auto& tri = d.triangles[t];
  const SetupVertex* tv[3] = {&dv.v[tri[0]], &dv.v[tri[1]], &dv.v[tri[2]]};
  const ClipError* te[3] = {&dv.error[tri[0]], &dv.error[tri[1]], &dv.error[tri[2]]};
  const unsigned planes = kClipPlanesXY | kClipPlanesZ;
  const unsigned m0 = clip_mask(tv[0]->c, gl, planes), m1 = clip_mask(tv[1]->c, gl, planes),
                 m2 = clip_mask(tv[2]->c, gl, planes);
  if (m0 & m1 & m2) {
    ++a.culled;
    return;
  }
  const unsigned crossed = m0 | m1 | m2;
  if (!(crossed & kClipPlanesZ) && !(s.pipeline.clip == ClipForm::llvmpipe && crossed)) {
    if (dv.bad[tri[0]] || dv.bad[tri[1]] || dv.bad[tri[2]])
      ++a.non_finite;
    else
      append_record(s, a, boxes, src, tv, te);
    return;
  }
  ++a.clipped;
  // A vertex the clip stage made (ids from the draw's vertex count on) gets clipped_vertex_error's
  // bound, from the triangle's largest clip coordinates and vertex errors and the planes crossed.
  ClipError carried{};
  std::array<float, 4> largest{};
  for (int k = 0; k < 3; ++k) {
    for (size_t c = 0; c < carried.size(); ++c) carried[c] = std::max(carried[c], (*te[k])[c]);
    for (int c = 0; c < 4; ++c) largest[c] = std::max(largest[c], std::fabs(tv[k]->c[c]));
  }
  int planes_crossed = 0;
  for (int plane = 0; plane < 6; ++plane) planes_crossed += (crossed >> plane) & 1u;
  const int nv = static_cast<int>(d.positions.size());
  const float hw = 0.5f * static_cast<float>(s.viewport_w);
  const float hh = 0.5f * static_cast<float>(s.viewport_h);
  const std::vector<SetupVertex> poly =
      clip_polygon({*tv[0], *tv[1], *tv[2]}, crossed, hw, hh, gl, s.pipeline.snap_bits,
                   nv + 8 * static_cast<int>(t));
  for (size_t i = 2; i < poly.size(); ++i) {
    const SetupVertex* f[3] = {&poly[i - 1], &poly[i], &poly[0]};
    bool nf = false;
    ClipError made[3];
    const ClipError* fe[3];
    for (int k = 0; k < 3; ++k) {
      nf = nf || vertex_non_finite(*f[k], depth_interpolated);
      made[k] = clipped_vertex_error(largest, carried, planes_crossed, f[k]->c);
      fe[k] = f[k]->id < nv ? &dv.error[f[k]->id] : &made[k];
    }
    if (nf)
      ++a.non_finite;
    else
      append_record(s, a, boxes, src, f, fe);
  }
}

// Each record in the tiles its pixel box meets (pixel i's centre i + 1/2 within the box), by
// counting, so every bin keeps draw order.
void bin_records(AuditSetup& a, const Boxes& boxes) {
  const int tiles = a.tiles_x * a.tiles_y;
  std::vector<std::array<int, 4>> tile_box(a.records.size());
  a.bins.assign(tiles + 1, 0);
  for (size_t r = 0; r < a.records.size(); ++r) {
    const auto& b = boxes[r];
    const int x0 = std::max(0, static_cast<int>(std::ceil(std::max(b[0] - 0.5f, -1.0f))));
    const int x1 = std::min(a.width - 1, static_cast<int>(std::floor(std::min(b[1] - 0.5f, 1e8f))));
    const int y0 = std::max(0, static_cast<int>(std::ceil(std::max(b[2] - 0.5f, -1.0f))));
    const int y1 =
        std::min(a.height - 1, static_cast<int>(std::floor(std::min(b[3] - 0.5f, 1e8f))));
    if (x0 > x1 || y0 > y1) {
      tile_box[r] = {1, 0, 1, 0};
      continue;
    }
    tile_box[r] = {x0 / AUDIT_TILE, x1 / AUDIT_TILE, y0 / AUDIT_TILE, y1 / AUDIT_TILE};
    for (int ty = tile_box[r][2]; ty <= tile_box[r][3]; ++ty)
      for (int tx = tile_box[r][0]; tx <= tile_box[r][1]; ++tx) ++a.bins[ty * a.tiles_x + tx + 1];
  }
  for (int t = 0; t < tiles; ++t) a.bins[t + 1] += a.bins[t];
  a.bin_records.resize(a.bins[tiles]);
  std::vector<uint32_t> fill(a.bins.begin(), a.bins.end() - 1);
  for (size_t r = 0; r < a.records.size(); ++r)
    for (int ty = tile_box[r][2]; ty <= tile_box[r][3]; ++ty)
      for (int tx = tile_box[r][0]; tx <= tile_box[r][1]; ++tx)
        a.bin_records[fill[ty * a.tiles_x + tx]++] = static_cast<uint32_t>(r);
}

}  // namespace

AuditSetup audit_setup(const Scene& s, const EvalPair& pair, const SceneGeometry& g,
                       const AuditCamera& cam) {
  if (pair.technique == Technique::layered)
    throw InputError(
        "audit: the layered technique splits the depth range per distance; audit its "
        "layers' mapping instead (-t " +
        std::string(info(s.params.layer_mapping).name) + ")");
  if (pair.technique == Technique::orthographic)
    throw InputError(
        "audit: orthographic set-ups take the projection from the scene's camera, and the audit "
        "takes a perspective glTF camera; audit a perspective technique");
  if (!s.pipeline.envelope.empty())
    throw InputError(fmt::format(
        "audit: pipeline.envelope {} is an adversary between the two planes of the MTS, not "
        "between a scene's surfaces; audit under its bound instead (--set bound_model={})",
        s.pipeline.envelope, s.pipeline.envelope));
  AuditSetup a;
  a.pair = pair;
  a.pc = probe_constants(s, pair, s.near);
  a.width = cam.width;
  a.height = cam.height;
  a.tiles_x = (a.width + AUDIT_TILE - 1) / AUDIT_TILE;
  a.tiles_y = (a.height + AUDIT_TILE - 1) / AUDIT_TILE;
  a.ray = pixel_ray(s, a.pc);
  a.clear_code =
      s.storage_format(pair).encode(info(depth_path(s, pair.technique)).greater ? 0.0f : 1.0f);
  a.planes = exact_planes(g, cam);
  Boxes boxes;
  for (const Draw& d : g.draws) {
    const DrawVertices dv = draw_vertices(s, a, d, cam);
    for (size_t t = 0; t < d.triangles.size(); ++t) set_up_triangle(s, d, t, dv, a, boxes);
  }
  bin_records(a, boxes);
  return a;
}

std::vector<float> packed_records(const AuditSetup& a) {
  std::vector<float> out(a.records.size() * MTS_TRI_STRIDE, 0.0f);
  for (size_t r = 0; r < a.records.size(); ++r) {
    const SetupTriangle& t = a.records[r];
    float* R = &out[r * MTS_TRI_STRIDE];
    uint32_t bits = t.valid ? MTS_BIT_VALID : 0u;
    for (int e = 0; e < 3; ++e) {
      R[MTS_T_EDGES + 4 * e] = t.e[e].ax;
      R[MTS_T_EDGES + 4 * e + 1] = t.e[e].ay;
      R[MTS_T_EDGES + 4 * e + 2] = t.e[e].dx;
      R[MTS_T_EDGES + 4 * e + 3] = t.e[e].dy;
      bits |= (t.e[e].negate ? MTS_BIT_NEGATE(e) : 0u) | (t.e[e].owns ? MTS_BIT_OWNS(e) : 0u);
    }
    std::memcpy(&R[MTS_T_BITS], &bits, 4);
    R[MTS_T_X0] = t.x0;
    R[MTS_T_Y0] = t.y0;
    R[MTS_T_D0] = t.d0;
    R[MTS_T_DZDX] = t.dzdx;
    R[MTS_T_DZDY] = t.dzdy;
    R[MTS_T_Q0] = t.q0;
    R[MTS_T_DQDX] = t.dqdx;
    R[MTS_T_DQDY] = t.dqdy;
    R[MTS_T_YMIN] = t.ymin;
    R[MTS_T_YMAX] = t.ymax;
  }
  return out;
}

}  // namespace depthprec
