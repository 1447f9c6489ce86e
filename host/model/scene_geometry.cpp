#include "host/model/scene_geometry.h"

#include <fmt/format.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "host/base/errors.h"
#include "host/model/gltf_nodes.h"

namespace depthprec {

namespace {

// The images a glTF file names are not needed: skip decoding them (and their files).
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int,
                const unsigned char*, int, void*) {
  return true;
}

// The bytes of accessor a, checked to lie inside its buffer; element k at base + k * stride.
struct AccessorView {
  const unsigned char* base = nullptr;
  size_t stride = 0, count = 0;
};

AccessorView view_of(const tinygltf::Model& m, int accessor, const std::string& path,
                     const std::string& what) {
  const auto bad = [&](const std::string& why) {
    return InputError(fmt::format("{}: accessor {} ({}): {}", path, accessor, what, why));
  };
  if (accessor < 0 || accessor >= static_cast<int>(m.accessors.size()))
    throw bad("no such accessor");
  const tinygltf::Accessor& a = m.accessors[accessor];
  if (a.bufferView < 0 || a.bufferView >= static_cast<int>(m.bufferViews.size()))
    throw bad("no buffer view (sparse or empty accessors are not supported)");
  const tinygltf::BufferView& bv = m.bufferViews[a.bufferView];
  if (bv.buffer < 0 || bv.buffer >= static_cast<int>(m.buffers.size())) throw bad("no buffer");
  const tinygltf::Buffer& b = m.buffers[bv.buffer];
  const int comp = tinygltf::GetComponentSizeInBytes(a.componentType);
  const int ncomp = tinygltf::GetNumComponentsInType(a.type);
  if (comp <= 0 || ncomp <= 0) throw bad("unknown component type");
  const size_t elem = static_cast<size_t>(comp) * ncomp;
  const size_t stride = bv.byteStride ? bv.byteStride : elem;
  const size_t start = bv.byteOffset + a.byteOffset;
  const size_t need = a.count == 0 ? 0 : start + (a.count - 1) * stride + elem;
  if (bv.byteOffset + bv.byteLength > b.data.size() || need > bv.byteOffset + bv.byteLength)
    throw bad(
        fmt::format("{} elements reach byte {} of a buffer view ending at byte {} (buffer of "
                    "{} bytes)",
                    a.count, need, bv.byteOffset + bv.byteLength, b.data.size()));
  return {b.data.data() + start, stride, a.count};
}

uint32_t read_index(const AccessorView& v, int type, size_t k) {
  const unsigned char* p = v.base + k * v.stride;
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t x;
      std::memcpy(&x, p, 2);
      return x;
    }
    default: {
      uint32_t x;
      std::memcpy(&x, p, 4);
      return x;
    }
  }
}

}  // namespace

Mat4d mat_identity() {
  Mat4d m{};
  for (int i = 0; i < 4; ++i) m[i * 5] = 1;
  return m;
}

Mat4d mat_mul(const Mat4d& a, const Mat4d& b) {
  Mat4d m{};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += a[r * 4 + k] * b[k * 4 + c];
      m[r * 4 + c] = s;
    }
  return m;
}

std::array<double, 3> transform_point(const Mat4d& m, double x, double y, double z) {
  std::array<double, 3> p{};
  for (int r = 0; r < 3; ++r)
    p[r] = m[r * 4] * x + m[r * 4 + 1] * y + m[r * 4 + 2] * z + m[r * 4 + 3];
  return p;
}

bool SceneGeometry::neighbours(uint32_t a, uint32_t b) const {
  const Draw& d = draw_of(a);
  if (&d != &draw_of(b)) return false;
  const auto& ta = d.triangles[a - d.first_triangle];
  const auto& tb = d.triangles[b - d.first_triangle];
  for (uint32_t i : ta)
    for (uint32_t j : tb)
      if (i == j) return true;
  return false;
}

std::array<double, 3> bounding_box_centre(const SceneGeometry& g) {
  std::array<double, 3> lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  for (const Draw& d : g.draws)
    for (const auto& p : d.positions) {
      const auto w = transform_point(d.world, p[0], p[1], p[2]);
      for (int i = 0; i < 3; ++i) {
        lo[i] = std::min(lo[i], w[i]);
        hi[i] = std::max(hi[i], w[i]);
      }
    }
  return {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
}

std::string Draw::label() const {
  return fmt::format("{} (mesh {}, primitive {})", node, mesh, primitive);
}

const Draw& SceneGeometry::draw_of(uint32_t t) const {
  auto it = std::upper_bound(draws.begin(), draws.end(), t,
                             [](uint32_t v, const Draw& d) { return v < d.first_triangle; });
  return *(it - 1);
}

SceneGeometry load_gltf(const std::string& path, uint64_t max_triangles) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(fmt::format("{} is a directory, not a glTF file", path));
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skip_image, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  const bool binary = path.size() >= 4 && path.compare(path.size() - 4, 4, ".glb") == 0;
  const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                         : loader.LoadASCIIFromFile(&model, &err, &warn, path);
  while (!err.empty() && std::isspace(static_cast<unsigned char>(err.back()))) err.pop_back();
  if (!ok)
    throw InputError(fmt::format("{}: not a readable glTF 2.0 {} file: {}", path,
                                 binary ? "binary (.glb)" : "JSON (.gltf)",
                                 err.empty() ? "tinygltf gave no reason" : err));
  SceneGeometry g;
  g.source = path;
  const NodeOrder order = node_order(model, path);
  if (!order.note.empty()) g.notes.push_back(order.note);
  // First the count, from the accessors alone, so a huge file is refused before anything is read.
  uint64_t total = 0, skipped = 0;
  for (const auto& [n, world] : order.nodes) {
    const tinygltf::Node& node = model.nodes[n];
    if (node.mesh < 0) continue;
    for (const auto& prim : model.meshes[node.mesh].primitives) {
      if (prim.mode != TINYGLTF_MODE_TRIANGLES || !prim.attributes.count("POSITION")) {
        ++skipped;
        continue;
      }
      const int acc = prim.indices >= 0 ? prim.indices : prim.attributes.at("POSITION");
      if (acc < 0 || acc >= static_cast<int>(model.accessors.size()))
        throw InputError(
            fmt::format("{}: a primitive of mesh {} names accessor {}, which does not exist", path,
                        node.mesh, acc));
      total += model.accessors[acc].count / 3;
    }
  }
  if (total > max_triangles)
    throw InputError(fmt::format(
        "{}: {} triangles, more than the audit takes ({}; --max-triangles raises it, at about 560 "
        "bytes of memory per triangle)",
        path, total, max_triangles));
  for (const auto& [n, world] : order.nodes) {
    const tinygltf::Node& node = model.nodes[n];
    if (node.camera >= 0) {
      const tinygltf::Camera& c = model.cameras[node.camera];
      if (c.type == "perspective") {
        GltfCamera cam;
        cam.name = !c.name.empty()      ? c.name
                   : !node.name.empty() ? node.name
                                        : fmt::format("camera {}", node.camera);
        cam.world = world;
        cam.yfov = c.perspective.yfov;
        cam.aspect = c.perspective.aspectRatio;
        cam.znear = c.perspective.znear;
        cam.zfar = c.perspective.zfar;
        g.cameras.push_back(cam);
      }
    }
    if (node.mesh < 0) continue;
    const tinygltf::Mesh& mesh = model.meshes[node.mesh];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& prim = mesh.primitives[p];
      if (prim.mode != TINYGLTF_MODE_TRIANGLES || !prim.attributes.count("POSITION")) continue;
      Draw d;
      d.node_index = n;
      d.mesh_index = node.mesh;
      d.primitive = static_cast<int>(p);
      d.node = !node.name.empty() ? node.name : fmt::format("node {}", n);
      d.mesh = !mesh.name.empty() ? mesh.name : fmt::format("mesh {}", node.mesh);
      d.world = world;
      const int pos = prim.attributes.at("POSITION");
      const AccessorView pv = view_of(model, pos, path, "POSITION");
      const tinygltf::Accessor& pa = model.accessors[pos];
      if (pa.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || pa.type != TINYGLTF_TYPE_VEC3)
        throw InputError(
            fmt::format("{}: mesh {}: POSITION is not a float VEC3 accessor", path, d.mesh));
      d.positions.resize(pv.count);
      for (size_t k = 0; k < pv.count; ++k)
        std::memcpy(d.positions[k].data(), pv.base + k * pv.stride, 12);
      if (prim.indices >= 0) {
        const AccessorView iv = view_of(model, prim.indices, path, "indices");
        const int type = model.accessors[prim.indices].componentType;
        if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
          throw InputError(fmt::format(
              "{}: mesh {}: indices of component type {}; glTF allows unsigned byte, short or int",
              path, d.mesh, type));
        for (size_t k = 0; k + 2 < iv.count; k += 3) {
          std::array<uint32_t, 3> t = {read_index(iv, type, k), read_index(iv, type, k + 1),
                                       read_index(iv, type, k + 2)};
          for (uint32_t i : t)
            if (i >= d.positions.size())
              throw InputError(fmt::format("{}: mesh {}: index {} past its {} positions", path,
                                           d.mesh, i, d.positions.size()));
          d.triangles.push_back(t);
        }
      } else {
        for (uint32_t k = 0; k + 2 < d.positions.size(); k += 3)
          d.triangles.push_back({k, k + 1, k + 2});
      }
      if (d.triangles.empty()) continue;
      d.first_triangle = static_cast<uint32_t>(g.triangles);
      g.triangles += d.triangles.size();
      g.draws.push_back(std::move(d));
    }
  }
  if (g.draws.empty())
    throw InputError(fmt::format(
        "{}: no triangles to audit ({} primitive(s) of other modes or without POSITION skipped; "
        "the audit draws mode 4, TRIANGLES)",
        path, skipped));
  return g;
}

}  // namespace depthprec
