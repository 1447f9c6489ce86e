// Where the emulation and a real rasterizer part ways, measured per pixel (docs/validation.md).
//
// 1. Depth of plane A read back from the driver's float32 depth buffer (exact: no storage
//    quantisation) at every kernel pixel of a few frames and distances, set against
//    - the emulator's own depth (the host reference pipeline: plane anchored at its first vertex,
//      gradients by division, no FMA), and
//    - the same vertices through llvmpipe's set-up as Mesa 22.3 writes it (lp_state_setup.c:
//      gradients times 1/area, the plane's value a0 at the framebuffer origin, each pixel
//      evaluated from scratch as fma(dzdy, y, fma(dzdx, x, a0))), with and without the viewport
//      transform's FMA (draw_llvm.c: fmuladd(ndc, scale, translate)) and the vertex shader's
//      fused products (pipeline.vertex = fma).
//    Pixels of triangles that cross the viewport edge are tallied apart: llvmpipe clips those
//    into new vertices, which the llvmpipe profile's clip stage (pipeline.clip) rebuilds; the
//    profile's reference pipeline is set against the driver there.
// 2. The unorm conversions, exhaustively over every binary32 in [0, 1]: the emulator's correctly
//    rounded code against llvmpipe's (lp_bld_conv.c: Z24 rint(fl32(d * 16777215)), Z16
//    rint(fl32(fl32(d * 0x1.fffep-1) * 65536)), Z32 from a truncated fl32(d * 2^31)).
//
// Usage: build/bench/render_depth_audit [frames (default 8)] [--no-conversions]
#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "host/model/frame_setup.h"
#include "host/model/scene.h"
#include "host/model/storage_format.h"
#include "host/mts/mts_evaluator.h"
#include "host/mts/mts_search.h"
#include "host/mts/reference_pipeline.h"
#include "host/render/gl_context.h"
#include "host/render/render_evaluator.h"
#include "host/runtime/kernel_variant.h"

using namespace depthprec;

namespace {

struct WinVertex {
  float x, y, z;
};

// Window coordinates of the plane's grid vertices as the vertex stage and viewport transform
// produce them: clip = P (MV obj) in either vertex form (host/model/frame_setup.h); 1/w, then
// ndc * scale + translate, with or without FMA.
std::vector<WinVertex> window_vertices(const Scene& s, const EvalPair& pair,
                                       const ProbeConstants& pc, const Mat4f& mv, bool fma_viewport,
                                       bool fma_vertex = false) {
  const int g = s.plane_subdivisions;
  const bool gl = pair.depth_range == DepthRange::gl;
  const float hw = 0.5f * static_cast<float>(s.viewport_w),
              hh = 0.5f * static_cast<float>(s.viewport_h);
  std::vector<WinVertex> v;
  for (int j = 0; j <= g; ++j)
    for (int i = 0; i <= g; ++i) {
      const float obj[4] = {static_cast<float>(i) / static_cast<float>(g) - 0.5f,
                            static_cast<float>(j) / static_cast<float>(g) - 0.5f, 0.0f, 1.0f};
      float eye[4], clip[4];
      const VertexForm form = fma_vertex ? VertexForm::fma : VertexForm::separate;
      for (int r = 0; r < 4; ++r) eye[r] = object_row_dot(mv, r, obj, form);
      for (int r = 0; r < 4; ++r) clip[r] = mat_row_dot(pc.P, r, eye, form);
      const float oow = 1.0f / clip[3];
      const float nx = clip[0] * oow, ny = clip[1] * oow, nz = clip[2] * oow;
      const float zs = gl ? 0.5f : 1.0f, zt = gl ? 0.5f : 0.0f;
      if (fma_viewport)
        v.push_back({std::fma(nx, hw, hw), std::fma(ny, hh, hh), std::fma(nz, zs, zt)});
      else
        v.push_back({nx * hw + hw, ny * hh + hh, nz * zs + zt});
    }
  return v;
}

// The triangles as submitted: quad by quad, (a, b, c) and (a, c, d), lower-left diagonal.
std::vector<std::array<int, 3>> triangles(int g) {
  std::vector<std::array<int, 3>> t;
  for (int qj = 0; qj < g; ++qj)
    for (int qi = 0; qi < g; ++qi) {
      const int a = qj * (g + 1) + qi, b = a + 1, c = a + g + 2, d = a + g + 1;
      t.push_back({a, b, c});
      t.push_back({a, c, d});
    }
  return t;
}

double edge(const WinVertex& a, const WinVertex& b, double px, double py) {
  return (double(b.x) - a.x) * (py - a.y) - (double(b.y) - a.y) * (px - a.x);
}

// The triangle holding the pixel centre, clearly inside (not within 1e-3 px of an edge), or -1.
int holder(const std::vector<WinVertex>& v, const std::vector<std::array<int, 3>>& tris, double px,
           double py) {
  for (size_t t = 0; t < tris.size(); ++t) {
    const auto& T = tris[t];
    const double e0 = edge(v[T[0]], v[T[1]], px, py), e1 = edge(v[T[1]], v[T[2]], px, py),
                 e2 = edge(v[T[2]], v[T[0]], px, py);
    const double area = edge(v[T[0]], v[T[1]], v[T[2]].x, v[T[2]].y);
    const double m = 1e-3 * std::abs(area) / 100;
    if ((e0 > m && e1 > m && e2 > m) || (e0 < -m && e1 < -m && e2 < -m)) return static_cast<int>(t);
  }
  return -1;
}

bool crosses_viewport(const Scene& s, const std::vector<WinVertex>& v,
                      const std::array<int, 3>& T) {
  for (int k : T)
    if (v[k].x < 0 || v[k].y < 0 || v[k].x > s.viewport_w || v[k].y > s.viewport_h) return true;
  return false;
}

// llvmpipe's plane (lp_state_setup.c, Mesa 22.3) from vertices in the order it passes them, at
// integer pixel (x, y): binary32, no FMA in the set-up, FMA in the evaluation.
float llvmpipe_depth(const WinVertex& v0, const WinVertex& v1, const WinVertex& v2, int x, int y) {
  const float x0c = v0.x - 0.5f, y0c = v0.y - 0.5f;
  const float dx01 = v0.x - v1.x, dy01 = v0.y - v1.y, dx20 = v2.x - v0.x, dy20 = v2.y - v0.y;
  const float ooa = 1.0f / (dx01 * dy20 - dx20 * dy01);
  const float dy20o = dy20 * ooa, dy01o = dy01 * ooa, dx20o = dx20 * ooa, dx01o = dx01 * ooa;
  const float dz01 = v0.z - v1.z, dz20 = v2.z - v0.z;
  const float dzdx = dz01 * dy20o - dz20 * dy01o;
  const float dzdy = dz20 * dx01o - dz01 * dx20o;
  const float a0 = v0.z - (dzdx * x0c + dzdy * y0c);
  return std::fma(dzdy, static_cast<float>(y), std::fma(dzdx, static_cast<float>(x), a0));
}

// The emulator's plane: anchored at the first vertex, gradients by division, no FMA.
float anchored_depth(const WinVertex& v0, const WinVertex& v1, const WinVertex& v2, float px,
                     float py) {
  const float e1x = v1.x - v0.x, e1y = v1.y - v0.y, e2x = v2.x - v0.x, e2y = v2.y - v0.y;
  const float det = e1x * e2y - e2x * e1y;
  const float e1d = v1.z - v0.z, e2d = v2.z - v0.z;
  const float dzdx = (e1d * e2y - e2d * e1y) / det, dzdy = (e2d * e1x - e1d * e2x) / det;
  return (v0.z + dzdx * (px - v0.x)) + dzdy * (py - v0.y);
}

int64_t ulps(float a, float b) {
  int32_t ia, ib;
  std::memcpy(&ia, &a, 4);
  std::memcpy(&ib, &b, 4);
  return std::llabs(static_cast<int64_t>(ia) - ib);
}

struct Tally {
  uint64_t pixels = 0, equal = 0, sum_ulps = 0;
  int64_t max_ulps = 0;
  void add(float model, float real) {
    ++pixels;
    const int64_t u = ulps(model, real);
    equal += u == 0;
    sum_ulps += static_cast<uint64_t>(u);
    max_ulps = std::max<int64_t>(max_ulps, u);
  }
  std::string show() const {
    return fmt::format("{:6.2f} % equal, mean {:7.2f} ulp, max {:5d} ulp",
                       100.0 * static_cast<double>(equal) / std::max<double>(1, pixels),
                       static_cast<double>(sum_ulps) / std::max<double>(1, pixels), max_ulps);
  }
};

void audit_depths(int frames) {
  GlContext gl;
  fmt::print("1. Plane A's depth per pixel, {} on {}: float32 buffer, {} frames per z\n",
             "standard/float32/gl", gl.description(), frames);
  Scene scene = load_scene("", {});
  const Scene llvmpipe = load_scene("", {"pipeline.profile=llvmpipe"});
  const EvalPair pair{Technique::standard, "float32", DepthRange::gl};
  RenderEvaluator ev(gl, scene, pair);
  const auto tris = triangles(scene.plane_subdivisions);
  const int ox = (scene.viewport_w - scene.kernel_w) / 2,
            oy = (scene.viewport_h - scene.kernel_h) / 2;
  fmt::print("{:>10}  {:>8}  {:<54} {}\n", "z", "pixels", "model", "against the driver's depth");
  // 1119466: about where plane B sits at the emulated MTS of z = 2^20 (section 3).
  for (double z : {2.0, 64.0, 1024.0, 32768.0, 1048576.0, 1119466.0}) {
    const ProbeConstants pc = probe_constants(scene, pair, z);
    std::map<std::string, Tally> t;
    uint64_t left_out = 0;
    Tally clipped_region;    // the emulator on the pixels left out
    Tally t_clip, clip_emu;  // pixels of clipped triangles: the llvmpipe profile, the emulator
    for (int f = 0; f < frames; ++f) {
      const std::vector<float> real = ev.depths_a({z, 0.0}, f);
      const FrameCodes emu = reference_frame(scene, pair, {z, 0.0}, f);
      const FrameCodes profiled = reference_frame(llvmpipe, pair, {z, 0.0}, f);
      const Mat4f mv = plane_matrix(scene, pc, z, f);
      const auto v_plain = window_vertices(scene, pair, pc, mv, false);
      const auto v_fma = window_vertices(scene, pair, pc, mv, true);
      const auto v_fused = window_vertices(scene, pair, pc, mv, true, true);
      for (int y = 0; y < scene.kernel_h; ++y)
        for (int x = 0; x < scene.kernel_w; ++x) {
          const int px = ox + x, py = oy + y;
          const int h = holder(v_plain, tris, px + 0.5, py + 0.5);
          const size_t k = static_cast<size_t>(y) * scene.kernel_w + x;
          const float d = real[k];
          float e;
          std::memcpy(&e, &emu.code_a[k], 4);
          if (h >= 0 && crosses_viewport(scene, v_plain, tris[h])) {
            // llvmpipe clips this triangle: the llvmpipe profile's reference pipeline, clip stage
            // and all, against the driver
            float p;
            std::memcpy(&p, &profiled.code_a[k], 4);
            t_clip.add(p, d);
            clip_emu.add(e, d);
          }
          if (h < 0 || crosses_viewport(scene, v_plain, tris[h]) ||
              holder(v_fma, tris, px + 0.5, py + 0.5) != h ||
              holder(v_fused, tris, px + 0.5, py + 0.5) != h) {
            ++left_out;
            clipped_region.add(e, d);
            continue;
          }
          t["a emulator (reference pipeline)"].add(e, d);
          const auto& T = tris[h];
          t["b anchored at v0, window vertices as emulated"].add(
              anchored_depth(v_plain[T[0]], v_plain[T[1]], v_plain[T[2]], px + 0.5f, py + 0.5f), d);
          for (const int variant : {0, 1, 2}) {
            const auto& v = variant == 0 ? v_plain : variant == 1 ? v_fma : v_fused;
            // llvmpipe passes (v1, v0, v2) when the fixed-point area is negative; this picks the
            // order by the float area's sign, which agrees except for slivers.
            const bool flip = edge(v[T[0]], v[T[1]], v[T[2]].x, v[T[2]].y) < 0;
            const float got = flip ? llvmpipe_depth(v[T[1]], v[T[0]], v[T[2]], px, py)
                                   : llvmpipe_depth(v[T[0]], v[T[1]], v[T[2]], px, py);
            const char* names[] = {"c llvmpipe set-up, viewport without FMA",
                                   "d llvmpipe set-up, FMA viewport",
                                   "e llvmpipe set-up, FMA viewport and vertex shader"};
            t[names[variant]].add(got, d);
          }
        }
    }
    bool first = true;
    for (const auto& [name, tally] : t) {
      fmt::print("{:>10}  {:>8}  {:<54} {}\n", first ? fmt::format("{:g}", z) : "",
                 first ? std::to_string(tally.pixels) : "", name.substr(2), tally.show());
      first = false;
    }
    fmt::print("{:>10}  {:>8}  {:<54} {}\n", "", left_out,
               "emulator, on triangles llvmpipe clips (left out above)", clipped_region.show());
    fmt::print("{:>10}  {:>8}  {:<54} {}\n", "", clip_emu.pixels,
               "of those, clearly inside one triangle:", "");
    fmt::print("{:>10}  {:>8}  {:<54} {}\n", "", "", "  emulator (reference pipeline)",
               clip_emu.show());
    fmt::print("{:>10}  {:>8}  {:<54} {}\n", "", "",
               "  llvmpipe profile (reference pipeline, clip stage)", t_clip.show());
  }
}

// At the emulated MTS: plane A and plane B per pixel, emulator against driver, and the pixels
// where each says B shows (fights). Whole kernel, every triangle.
void audit_fights(int frames) {
  GlContext gl;
  OpenClRuntime rt;
  fmt::print(
      "\n3. At the emulated MTS, standard/float32/gl, {} frames: per-pixel depth of A and B "
      "equal to the driver's, and fighting pixels\n",
      frames);
  Scene scene = load_scene("", {});
  scene.frames = frames;
  const EvalPair pair{Technique::standard, "float32", DepthRange::gl};
  RenderEvaluator ev(gl, scene, pair);
  MtsEvaluator emu(rt, scene, pair);
  const std::vector<double> zs = {2.0, 1024.0, 1048576.0};
  const auto rows = search_pair(emu, scene, pair, zs);
  fmt::print("{:>10}  {:>10}  {:>8}  {:>8}  {:>14}  {:>14}\n", "z", "emu MTS", "A equal", "B equal",
             "fights (emu)", "fights (driver)");
  for (size_t i = 0; i < zs.size(); ++i) {
    const double z = zs[i], s = rows[i].mts;
    uint64_t n = 0, a_eq = 0, b_eq = 0, f_emu = 0, f_drv = 0;
    for (int f = 0; f < frames; ++f) {
      const FrameCodes c = reference_frame(scene, pair, {z, s}, f);
      const std::vector<float> da = ev.depths_a({z, 0.0}, f);
      const std::vector<float> db = ev.depths_a({z + s, 0.0}, f);
      for (size_t k = 0; k < da.size(); ++k) {
        float ea, eb;
        std::memcpy(&ea, &c.code_a[k], 4);
        std::memcpy(&eb, &c.code_b[k], 4);
        ++n;
        a_eq += ea == da[k];
        b_eq += eb == db[k];
        f_emu += eb <= ea;
        f_drv += db[k] <= da[k];
      }
    }
    fmt::print("{:>10g}  {:>10.4g}  {:>7.2f}%  {:>7.2f}%  {:>14}  {:>14}\n", z, s,
               100.0 * static_cast<double>(a_eq) / static_cast<double>(n),
               100.0 * static_cast<double>(b_eq) / static_cast<double>(n), f_emu, f_drv);
  }
}

// The unorm conversions over every binary32 in [0, 1].
void audit_conversions() {
  fmt::print(
      "\n2. unorm conversion of every binary32 d in [0, 1]: emulator (correctly rounded) "
      "against llvmpipe's\n");
  const StorageFormat u16 = StorageFormat::parse("unorm16"), u24 = StorageFormat::parse("unorm24"),
                      u32 = StorageFormat::parse("unorm32");
  uint64_t n = 0, diff16 = 0, diff24 = 0, diff32 = 0;
  int64_t max16 = 0, max24 = 0, max32 = 0;
  const uint32_t one = 0x3f800000u;
  for (uint32_t bits = 0; bits <= one; ++bits) {
    float d;
    std::memcpy(&d, &bits, 4);
    ++n;
    const float t16 = d * 0x1.fffep-1f;
    const int64_t l16 = static_cast<int64_t>(std::nearbyint(t16 * 65536.0f));
    const int64_t l24 = static_cast<int64_t>(std::nearbyint(d * 16777215.0f));
    const uint64_t u = static_cast<uint64_t>(static_cast<double>(d * 2147483648.0f));
    const int64_t l32 = static_cast<int64_t>(((u << 1) - (u >> 31)) & 0xffffffffu);
    const int64_t e16 = u16.encode(d), e24 = u24.encode(d), e32 = u32.encode(d);
    diff16 += l16 != e16;
    diff24 += l24 != e24;
    diff32 += l32 != e32;
    max16 = std::max<int64_t>(max16, std::llabs(l16 - e16));
    max24 = std::max<int64_t>(max24, std::llabs(l24 - e24));
    max32 = std::max<int64_t>(max32, std::llabs(l32 - e32));
  }
  for (auto [name, diff, mx] :
       {std::tuple{"unorm16", diff16, max16}, std::tuple{"unorm24", diff24, max24},
        std::tuple{"unorm32", diff32, max32}})
    fmt::print("  {}: {} of {} depths get another code ({:.4f} %), at most {} code(s) apart\n",
               name, diff, n, 100.0 * static_cast<double>(diff) / static_cast<double>(n), mx);
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 8;
  bool conversions = true;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--no-conversions")
      conversions = false;
    else
      frames = std::atoi(argv[i]);
  }
  try {
    audit_depths(frames);
    audit_fights(frames);
    if (conversions) audit_conversions();
  } catch (const std::exception& e) {
    fmt::print(stderr, "render_depth_audit: {}\n", e.what());
    return 1;
  }
  return 0;
}
