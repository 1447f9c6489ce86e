#include "host/model/scene_geometry.h"

#include <fmt/format.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <numeric>

#include "host/base/errors.h"
#include "host/model/gltf_accessors.h"
#include "host/model/gltf_nodes.h"

namespace depthprec {

namespace {

// The images a glTF file names are not needed: skip decoding them (and their files).
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int,
                const unsigned char*, int, void*) {
  return true;
}

// Required extensions that change no position, index or node the audit reads (materials,
// textures, lights, metadata). Any other may change the geometry: refused, not ignored.
bool geometry_neutral(const std::string& e) {
  for (const char* prefix : {"KHR_materials_", "KHR_texture_", "EXT_texture_", "MSFT_texture_"})
    if (e.rfind(prefix, 0) == 0) return true;
  for (const char* name : {"KHR_lights_punctual", "EXT_lights_image_based", "KHR_xmp_json_ld"})
    if (e == name) return true;
  return false;
}

// glTF 2.0 resolves a relative URI against the file's own location; tinygltf looks in the working
// directory too, where a buffer of the same name (Blender names the .bin after the .gltf) would be
// read in place of a missing one. user: the prefix tinygltf puts before a URI beside the file
// (its directory and a slash; empty for a file in the working directory, where both are one).
std::string expand_beside(const std::string& path, void* user) {
  const std::string& beside = *static_cast<const std::string*>(user);
  if (path.compare(0, beside.size(), beside) != 0) return "";  // not found, said as such
  return tinygltf::ExpandFilePath(path, nullptr);
}

constexpr const char* kUncompress =
    "write it without mesh compression first (e.g. with glTF-Transform, with gltfpack without "
    "-c/-cc, which keeps KHR_mesh_quantization the audit reads, or from Blender's glTF exporter "
    "with compression off)";

std::string primitive_name(const tinygltf::Mesh& mesh, int index, size_t p) {
  return fmt::format("mesh {}, primitive {}", mesh.name.empty() ? std::to_string(index) : mesh.name,
                     p);
}

// Also run on what tinygltf returns when it fails: extensionsRequired and the meshes are parsed
// before the check a Draco primitive fails ("accessor[3] invalid bufferView"), so the refusal
// names the cause, not that symptom.
void check_extensions(const tinygltf::Model& m, const std::string& path) {
  for (const std::string& e : m.extensionsRequired) {
    if (e == "KHR_mesh_quantization" || geometry_neutral(e)) continue;
    if (e == "KHR_draco_mesh_compression" || e == "EXT_meshopt_compression" ||
        e == "KHR_meshopt_compression")
      throw InputError(fmt::format(
          "{}: its geometry is compressed with {} (extensionsRequired), which the audit does not "
          "decode: {}",
          path, e, kUncompress));
    throw InputError(fmt::format(
        "{}: it requires the extension {}, which the audit does not read; it reads glTF 2.0 with "
        "KHR_mesh_quantization and extensions that change no geometry (KHR_materials_*, "
        "KHR_texture_*, KHR_lights_punctual, ...)",
        path, e));
  }
  // Without extensionsRequired, a Draco primitive may carry an uncompressed copy for readers
  // without Draco (accessors with buffer views), which is read; with none, it is refused.
  for (size_t mi = 0; mi < m.meshes.size(); ++mi)
    for (size_t p = 0; p < m.meshes[mi].primitives.size(); ++p) {
      const tinygltf::Primitive& prim = m.meshes[mi].primitives[p];
      if (!prim.extensions.count("KHR_draco_mesh_compression")) continue;
      std::vector<int> used = {prim.indices};
      if (prim.attributes.count("POSITION")) used.push_back(prim.attributes.at("POSITION"));
      for (int a : used)
        if (a >= 0 && static_cast<size_t>(a) < m.accessors.size() &&
            m.accessors[a].bufferView < 0 && !m.accessors[a].sparse.isSparse)
          throw InputError(fmt::format(
              "{}: {} is compressed with KHR_draco_mesh_compression and has no uncompressed copy; "
              "the audit does not decode Draco: {}",
              path, primitive_name(m.meshes[mi], static_cast<int>(mi), p), kUncompress));
    }
}

const char* const kModeNames[] = {"POINTS",    "LINES",          "LINE_LOOP",   "LINE_STRIP",
                                  "TRIANGLES", "TRIANGLE_STRIP", "TRIANGLE_FAN"};

// The triangles prim makes, from its accessors' counts alone; 0 with *why (for the note that
// counts what is not drawn) when it is not drawn.
uint64_t drawn_triangles(const tinygltf::Model& m, const tinygltf::Primitive& prim,
                         const std::string& path, const std::string& where, std::string* why) {
  if (prim.mode < 0 || prim.mode > 6)
    throw InputError(fmt::format("{}: {}: mode {}; glTF's modes are 0 (POINTS) to 6 (TRIANGLE_FAN)",
                                 path, where, prim.mode));
  if (!triangle_mode(prim.mode)) {
    *why = fmt::format("of mode {}", kModeNames[prim.mode]);
    return 0;
  }
  const auto pos = prim.attributes.find("POSITION");
  if (pos == prim.attributes.end()) {
    *why = "without POSITION";
    return 0;
  }
  const int list = prim.indices >= 0 ? prim.indices : pos->second;
  for (int a : {pos->second, list})
    if (a < 0 || static_cast<size_t>(a) >= m.accessors.size())
      throw InputError(
          fmt::format("{}: {} names accessor {}, which does not exist", path, where, a));
  const uint64_t n = triangle_count(prim.mode, m.accessors[list].count);
  if (n == 0) *why = fmt::format("of mode {} with fewer than 3 vertices", kModeNames[prim.mode]);
  return n;
}

// a + b, or UINT64_MAX for a sum past it: a file's counts are its own to claim.
uint64_t add_counts(uint64_t a, uint64_t b) {
  return b > UINT64_MAX - a ? UINT64_MAX : a + b;
}

}  // namespace

bool SceneGeometry::neighbours(uint32_t a, uint32_t b) const {
  const Draw& d = draw_of(a);
  if (&d != &draw_of(b)) return false;
  const auto& ta = d.triangles[a - d.first_triangle];
  const auto& tb = d.triangles[b - d.first_triangle];
  // A corner in common by index, or by position: exporters give a vertex one index per face
  // where its normals or texture coordinates differ (Blender's flat-shaded box: 24 positions for
  // 8 corners), so the faces of one surface meet at corners with different indices.
  for (uint32_t i : ta)
    for (uint32_t j : tb)
      if (i == j || d.positions[i] == d.positions[j]) return true;
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

namespace {

tinygltf::Model read_model(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(fmt::format("{} is a directory, not a glTF file", path));
  if (!std::filesystem::exists(path, ec) && !ec)
    throw InputError(fmt::format("{}: no such file", path));
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skip_image, nullptr);
  // tinygltf's base directory: the path up to its last slash, joined to a URI with a slash
  const size_t slash = path.find_last_of("/\\");
  std::string beside = slash == std::string::npos ? "" : path.substr(0, slash);
  if (!beside.empty() && beside.back() != '/') beside += '/';
  loader.SetFsCallbacks({&tinygltf::FileExists, &expand_beside, &tinygltf::ReadWholeFile,
                         &tinygltf::WriteWholeFile, &beside});
  tinygltf::Model model;
  std::string err, warn;
  const bool binary = path.size() >= 4 && path.compare(path.size() - 4, 4, ".glb") == 0;
  const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                         : loader.LoadASCIIFromFile(&model, &err, &warn, path);
  while (!err.empty() && std::isspace(static_cast<unsigned char>(err.back()))) err.pop_back();
  check_extensions(model, path);
  if (!ok)
    throw InputError(fmt::format("{}: not a readable glTF 2.0 {} file: {}", path,
                                 binary ? "binary (.glb)" : "JSON (.gltf)",
                                 err.empty() ? "tinygltf gave no reason" : err));
  return model;
}

struct PrimitiveCounts {
  uint64_t triangles = 0, vertices = 0;
  std::map<std::string, uint64_t> skipped;  // by why
};

PrimitiveCounts count_primitives(const tinygltf::Model& model, const NodeOrder& order,
                                 const std::string& path) {
  PrimitiveCounts c;
  std::string why;
  for (const auto& [n, world] : order.nodes) {
    const int mi = model.nodes[n].mesh;
    if (mi < 0) continue;
    const tinygltf::Mesh& mesh = model.meshes[mi];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& prim = mesh.primitives[p];
      const uint64_t t = drawn_triangles(model, prim, path, primitive_name(mesh, mi, p), &why);
      if (t == 0) {
        ++c.skipped[why];
        continue;
      }
      c.triangles = add_counts(c.triangles, t);
      c.vertices = add_counts(c.vertices, model.accessors[prim.attributes.at("POSITION")].count);
    }
  }
  return c;
}

void check_size(const PrimitiveCounts& c, const std::string& path, uint64_t max_triangles) {
  if (c.triangles > max_triangles)
    throw InputError(fmt::format(
        "{}: {} triangles, more than the audit takes ({}; --max-triangles raises it, at about 560 "
        "bytes of memory per triangle)",
        path, c.triangles, max_triangles));
  // A sparse accessor without a buffer view claims elements the file does not hold: the vertices
  // are bounded too, at three a triangle, as many as an unindexed mesh has.
  if (c.vertices / 3 > max_triangles)
    throw InputError(fmt::format(
        "{}: {} vertices, more than the audit takes (3 a triangle of its limit of {} triangles; "
        "--max-triangles raises it)",
        path, c.vertices, max_triangles));
}

// The file's perspective cameras are the ones `--camera` can name (docs/audit.md, "Input").
void add_camera(const tinygltf::Model& model, const tinygltf::Node& node, const Mat4d& world,
                SceneGeometry& g) {
  const tinygltf::Camera& c = model.cameras[node.camera];
  GltfCamera cam;
  cam.node = node.name;
  cam.orthographic = c.type != "perspective";
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

std::vector<uint32_t> vertex_list(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                  size_t positions, const std::string& path,
                                  const std::string& where) {
  std::vector<uint32_t> list;
  if (prim.indices >= 0) {
    list = read_indices(model, prim.indices, path, where);
    for (uint32_t i : list)
      if (i >= positions)
        throw InputError(
            fmt::format("{}: {}: index {} past its {} positions", path, where, i, positions));
  } else {
    list.resize(positions);
    std::iota(list.begin(), list.end(), 0u);
  }
  return list;
}

void add_draws(const tinygltf::Model& model, int n, const Mat4d& world, const std::string& path,
               SceneGeometry& g) {
  const tinygltf::Node& node = model.nodes[n];
  const tinygltf::Mesh& mesh = model.meshes[node.mesh];
  // glTF 2.0 3.7.4: the node's morph weights, else the mesh's, else none
  const std::vector<double>& weights = node.weights.empty() ? mesh.weights : node.weights;
  std::string why;
  for (size_t p = 0; p < mesh.primitives.size(); ++p) {
    const tinygltf::Primitive& prim = mesh.primitives[p];
    const std::string where = primitive_name(mesh, node.mesh, p);
    if (drawn_triangles(model, prim, path, where, &why) == 0) continue;
    Draw d;
    d.node_index = n;
    d.mesh_index = node.mesh;
    d.primitive = static_cast<int>(p);
    d.node = !node.name.empty() ? node.name : fmt::format("node {}", n);
    d.mesh = !mesh.name.empty() ? mesh.name : fmt::format("mesh {}", node.mesh);
    d.world = world;
    d.positions = primitive_positions(model, prim, weights, path, where);
    d.triangles = triangulate(prim.mode, vertex_list(model, prim, d.positions.size(), path, where));
    d.first_triangle = static_cast<uint32_t>(g.triangles);
    g.triangles += d.triangles.size();
    g.draws.push_back(std::move(d));
  }
}

void note_undrawn(const std::map<std::string, uint64_t>& skipped, const std::string& path,
                  SceneGeometry& g) {
  std::string undrawn;
  for (const auto& [reason, count] : skipped) {
    g.skipped += count;
    undrawn += fmt::format("{}{} {}", undrawn.empty() ? "" : ", ", count, reason);
  }
  constexpr const char* drawn_modes = "the audit draws TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN";
  if (g.draws.empty() && g.skipped == 0)
    throw InputError(
        fmt::format("{}: no triangles to audit: none of the nodes drawn has a mesh", path));
  if (g.draws.empty())
    throw InputError(fmt::format("{}: no triangles to audit ({} primitive(s) not drawn: {}; {})",
                                 path, g.skipped, undrawn, drawn_modes));
  if (g.skipped)
    g.notes.push_back(
        fmt::format("{} primitive(s) not drawn: {} ({})", g.skipped, undrawn, drawn_modes));
}

}  // namespace

SceneGeometry load_gltf(const std::string& path, uint64_t max_triangles) {
  const tinygltf::Model model = read_model(path);
  SceneGeometry g;
  g.source = path;
  const NodeOrder order = node_order(model, path);
  if (!order.note.empty()) g.notes.push_back(order.note);
  // First the counts, from the accessors alone, so a huge file is refused before anything is read.
  const PrimitiveCounts counts = count_primitives(model, order, path);
  check_size(counts, path, max_triangles);
  for (const auto& [n, world] : order.nodes) {
    const tinygltf::Node& node = model.nodes[n];
    if (node.camera >= 0) add_camera(model, node, world, g);
    if (node.mesh >= 0) add_draws(model, n, world, path, g);
  }
  note_undrawn(counts.skipped, path, g);
  return g;
}

}  // namespace depthprec
