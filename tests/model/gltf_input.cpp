// The glTF loader on files made here, one feature or fault each: it reads what glTF 2.0 defines
// (strips, fans, morph weights, quantized and strided positions, sparse accessors, files without
// scenes) as the spec says, and refuses the rest by name: the file, what is wrong, what is allowed.
#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "host/base/errors.h"
#include "host/model/scene_geometry.h"
#include "host/output/audit_output.h"
#include "tests/support/files.h"

using namespace depthprec;
using Catch::Matchers::Contains;
using nlohmann::json;

namespace {

std::string gltf_base64(const std::string& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t k = 0; k < bytes.size(); k += 3) {
    uint32_t v = uint32_t(uint8_t(bytes[k])) << 16;
    if (k + 1 < bytes.size()) v |= uint32_t(uint8_t(bytes[k + 1])) << 8;
    if (k + 2 < bytes.size()) v |= uint8_t(bytes[k + 2]);
    for (size_t c = 0; c < 4; ++c)
      out += k + c <= bytes.size() ? digits[(v >> (18 - 6 * c)) & 63] : '=';
  }
  return out;
}

// A .gltf made in memory: one embedded buffer, a buffer view and an accessor per array added.
struct GltfFile {
  json j = {{"asset", {{"version", "2.0"}}}};
  std::string bin;

  // The bytes as a buffer view (4-byte aligned, with byteStride when not 0) and an accessor of
  // `fields` over it; returns the accessor's index.
  int add(const std::string& bytes, json fields, size_t stride = 0) {
    while (bin.size() % 4) bin += '\0';
    json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes.size()}};
    if (stride) view["byteStride"] = stride;
    bin += bytes;
    j["bufferViews"].push_back(view);
    fields["bufferView"] = j["bufferViews"].size() - 1;
    j["accessors"].push_back(fields);
    return static_cast<int>(j["accessors"].size()) - 1;
  }
  template <class T>
  static std::string bytes_of(const std::vector<T>& v) {
    return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  int positions(const std::vector<std::array<float, 3>>& p) {
    std::vector<float> flat;
    for (const auto& v : p) flat.insert(flat.end(), v.begin(), v.end());
    return add(bytes_of(flat), {{"componentType", 5126}, {"count", p.size()}, {"type", "VEC3"}});
  }
  int indices(const std::vector<uint16_t>& i) {
    return add(bytes_of(i), {{"componentType", 5123}, {"count", i.size()}, {"type", "SCALAR"}});
  }
  // A mesh of one primitive per (POSITION accessor, mode, indices or -1); returns its index.
  int mesh(const std::vector<std::array<int, 3>>& prims, const std::string& name = "") {
    json m = {{"primitives", json::array()}};
    if (!name.empty()) m["name"] = name;
    for (const auto& [pos, mode, ind] : prims) {
      json p = {{"attributes", {{"POSITION", pos}}}, {"mode", mode}};
      if (ind >= 0) p["indices"] = ind;
      m["primitives"].push_back(p);
    }
    j["meshes"].push_back(m);
    return static_cast<int>(j["meshes"].size()) - 1;
  }
  std::string write(const std::string& name) {
    j["buffers"] = {{{"byteLength", bin.size()},
                     {"uri", "data:application/octet-stream;base64," + gltf_base64(bin)}}};
    const auto dir = std::filesystem::temp_directory_path() / "depthprec_test_gltf_input";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / name).string();
    test::write_bytes(path, j.dump());
    return path;
  }
};

// A file of one triangle mesh under node 0, scene 0.
GltfFile gltf_one_triangle() {
  GltfFile f;
  const int pos = f.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  f.mesh({{pos, 4, -1}});
  f.j["nodes"] = {{{"name", "tri"}, {"mesh", 0}}};
  f.j["scenes"] = {{{"nodes", {0}}}};
  return f;
}

std::string gltf_refusal(const std::string& path, uint64_t max_triangles = 1000) {
  try {
    load_gltf(path, max_triangles);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(loaded)";
}

// Twice the signed area of triangle t of d in the xy plane: its sign is its gltf_winding.
double gltf_winding(const Draw& d, const std::array<uint32_t, 3>& t) {
  const auto &a = d.positions[t[0]], &b = d.positions[t[1]], &c = d.positions[t[2]];
  return double(b[0] - a[0]) * (c[1] - a[1]) - double(b[1] - a[1]) * (c[0] - a[0]);
}

using GltfTri = std::array<uint32_t, 3>;

}  // namespace

TEST_CASE("glTF: a file that does not exist is refused as one, not as unreadable glTF", "[gltf]") {
  const auto dir = std::filesystem::temp_directory_path() / "depthprec_test_gltf_input";
  std::filesystem::create_directories(dir);
  for (const char* name : {"missing.glb", "missing.gltf"}) {
    const std::string path = (dir / name).string();
    std::filesystem::remove(path);
    CHECK(gltf_refusal(path) == path + ": no such file");
  }
}

TEST_CASE("glTF: buffers are read beside the file, never from the working directory", "[gltf]") {
  // A .gltf whose room.bin was not copied with it, run where another room.bin lies: glTF 2.0
  // resolves the URI against the file's location, so the other one must not be read.
  const auto dir = test::empty_dir("gltf_beside");
  std::filesystem::create_directories(dir / "scene");
  GltfFile f = gltf_one_triangle();
  f.j["buffers"] = {{{"byteLength", f.bin.size()}, {"uri", "room.bin"}}};
  test::write_bytes(dir / "scene" / "room.gltf", f.j.dump());
  test::write_bytes(dir / "room.bin", f.bin);
  const auto cwd = std::filesystem::current_path();
  std::filesystem::current_path(dir);
  const std::string missing = gltf_refusal("scene/room.gltf");
  test::write_bytes(dir / "scene" / "room.bin", f.bin);
  const uint64_t beside = load_gltf("scene/room.gltf", 100).triangles;
  // a URI up a directory is still the file's own
  f.j["buffers"][0]["uri"] = "../room.bin";
  test::write_bytes(dir / "scene" / "up.gltf", f.j.dump());
  const uint64_t up = load_gltf("scene/up.gltf", 100).triangles;
  std::filesystem::current_path(cwd);
  CHECK_THAT(missing, Contains("scene/room.gltf") && Contains("room.bin"));
  CHECK(beside == 1);
  CHECK(up == 1);
}

TEST_CASE("glTF: a default scene the file lacks is refused with the index and the scene count",
          "[gltf]") {
  for (int scene : {1, 5, 1000, -3}) {
    GltfFile f = gltf_one_triangle();
    f.j["scene"] = scene;
    const std::string path = f.write("scene_missing.gltf");
    const std::string e = gltf_refusal(path);
    CHECK_THAT(e, Contains(path));
    CHECK_THAT(e, Contains(fmt::format("\"scene\": {} names a scene that does not exist", scene)));
    CHECK_THAT(e, Contains("the file has 1 scenes (0 to 0)"));
  }
  GltfFile f = gltf_one_triangle();
  f.j.erase("scenes");
  f.j["scene"] = 0;
  CHECK_THAT(gltf_refusal(f.write("scene_none.gltf")), Contains("the file has no scenes"));
}

TEST_CASE("glTF: strips and fans are triangulated as glTF 2.0 defines them, indexed or not",
          "[gltf]") {
  GltfFile f;
  // a zigzag strip: every triangle faces the way the first does
  const int strip = f.positions({{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0}, {2, 0, 0}});
  const int fan = f.positions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 1, 0}});
  const int reversed = f.indices({4, 3, 2, 1, 0});
  const int degenerate = f.indices({0, 1, 1, 2});
  f.mesh({{strip, 5, -1},
          {strip, 5, reversed},
          {fan, 6, -1},
          {fan, 6, reversed},
          {strip, 5, degenerate}});
  f.j["nodes"] = {{{"mesh", 0}}};
  f.j["scenes"] = {{{"nodes", {0}}}};
  const SceneGeometry g = load_gltf(f.write("strips_fans.gltf"), 100);
  REQUIRE(g.draws.size() == 5);
  // p_i = {v_i, v_(i+1+i%2), v_(i+2-i%2)}
  CHECK(g.draws[0].triangles == std::vector<GltfTri>{{0, 1, 2}, {1, 3, 2}, {2, 3, 4}});
  CHECK(g.draws[1].triangles == std::vector<GltfTri>{{4, 3, 2}, {3, 1, 2}, {2, 1, 0}});
  // p_i = {v_(i+1), v_(i+2), v_0}
  CHECK(g.draws[2].triangles == std::vector<GltfTri>{{1, 2, 0}, {2, 3, 0}, {3, 4, 0}});
  CHECK(g.draws[3].triangles == std::vector<GltfTri>{{3, 2, 4}, {2, 1, 4}, {1, 0, 4}});
  // degenerate triangles are kept (the rasteriser draws nothing of them)
  CHECK(g.draws[4].triangles == std::vector<GltfTri>{{0, 1, 1}, {1, 2, 1}});
  CHECK(g.triangles == 14);
  CHECK(g.skipped == 0);
  for (int k : {0, 2}) {
    const Draw& d = g.draws[k];
    for (const GltfTri& t : d.triangles)
      CHECK(gltf_winding(d, t) == gltf_winding(d, d.triangles[0]));
  }
}

TEST_CASE("glTF: points and lines are not drawn, and the geometry and the audit's text say so",
          "[gltf]") {
  GltfFile f = gltf_one_triangle();
  const int line = f.positions({{0, 0, 0}, {1, 1, 1}});
  f.mesh({{line, 1, -1}, {line, 0, -1}, {line, 3, -1}});
  f.j["nodes"].push_back({{"mesh", 1}});
  f.j["scenes"][0]["nodes"].push_back(1);
  const SceneGeometry g = load_gltf(f.write("lines_points.gltf"), 100);
  CHECK(g.draws.size() == 1);
  CHECK(g.skipped == 3);
  REQUIRE(g.notes.size() == 1);
  CHECK_THAT(g.notes[0],
             Contains("3 primitive(s) not drawn: 1 of mode LINES, 1 of mode LINE_STRIP, 1 of mode "
                      "POINTS"));
  AuditReport r;
  r.geometry = &g;
  r.header = {{"file", "lines_points.gltf"}};
  CHECK_THAT(audit_text(r, "text", false), Contains("3 primitive(s) not drawn"));
  // with nothing else, the gltf_refusal counts them
  GltfFile only_lines;
  only_lines.mesh({{only_lines.positions({{0, 0, 0}, {1, 1, 1}}), 1, -1}});
  only_lines.j["nodes"] = {{{"mesh", 0}}};
  only_lines.j["scenes"] = {{{"nodes", {0}}}};
  CHECK_THAT(gltf_refusal(only_lines.write("only_lines.gltf")),
             Contains("no triangles to audit (1 primitive(s) not drawn: 1 of mode LINES"));
}

TEST_CASE("glTF: default morph weights move POSITION, a node's over its mesh's, zero ones none",
          "[gltf]") {
  GltfFile f;
  const float up = std::ldexp(3.0f, -25);  // 0.75 of binary32's unit at 1
  const int pos = f.positions({{1, 0, 0}, {2, 0, 0}, {0, 1, 0}});
  const int t0 = f.positions({{up, 0, 0}, {1, 0, 0}, {0, 0, 0}});
  const int t1 = f.positions({{up, 0, 0}, {0, 2, 0}, {0, 0, 0}});
  // a sparse target without a buffer view, as Blender writes them: zeros but for vertex 2
  std::vector<uint16_t> at = {2};
  std::vector<float> value = {0, 0, 8};
  f.add(GltfFile::bytes_of(at), {{"componentType", 5123}, {"count", 1}, {"type", "SCALAR"}});
  f.add(GltfFile::bytes_of(value), {{"componentType", 5126}, {"count", 1}, {"type", "VEC3"}});
  const int views = static_cast<int>(f.j["bufferViews"].size());
  f.j["accessors"].push_back({{"componentType", 5126},
                              {"count", 3},
                              {"type", "VEC3"},
                              {"sparse",
                               {{"count", 1},
                                {"indices", {{"bufferView", views - 2}, {"componentType", 5123}}},
                                {"values", {{"bufferView", views - 1}}}}}});
  const int t2 = static_cast<int>(f.j["accessors"].size()) - 1;
  f.mesh({{pos, 4, -1}});
  f.j["meshes"][0]["primitives"][0]["targets"] = {
      {{"POSITION", t0}}, {{"POSITION", t1}}, {{"POSITION", t2}}};
  f.j["meshes"][0]["weights"] = {0.5, 0.5, 0.25};
  f.j["nodes"] = {{{"name", "mesh weights"}, {"mesh", 0}},
                  {{"name", "node weights"}, {"mesh", 0}, {"weights", {0, 1, 0}}},
                  {{"name", "rest"}, {"mesh", 0}, {"weights", {0, 0, 0}}}};
  f.j["scenes"] = {{{"nodes", {0, 1, 2}}}};
  const SceneGeometry g = load_gltf(f.write("morph.gltf"), 100);
  REQUIRE(g.draws.size() == 3);
  using P = std::vector<std::array<float, 3>>;
  // 1 + 0.5 * up + 0.5 * up is 0.75 of a unit past 1 in binary64, rounded once to 1 unit; in
  // binary32 each half (0.375 of a unit) would round away and leave 1
  CHECK(g.draws[0].positions == P{{std::nextafter(1.0f, 2.0f), 0, 0}, {2.5f, 1, 0}, {0, 1, 2}});
  CHECK(g.draws[1].positions == P{{std::nextafter(1.0f, 2.0f), 0, 0}, {2, 2, 0}, {0, 1, 0}});
  CHECK(g.draws[2].positions == P{{1, 0, 0}, {2, 0, 0}, {0, 1, 0}});
  f.j["nodes"][1]["weights"] = {1, 0};
  CHECK_THAT(gltf_refusal(f.write("morph_weights.gltf")),
             Contains("mesh 0, primitive 0: 2 morph weights for 3 morph targets"));
}

TEST_CASE("glTF: a required extension the audit does not read is refused by name", "[gltf]") {
  for (const char* e : {"EXT_meshopt_compression", "KHR_draco_mesh_compression"}) {
    GltfFile f = gltf_one_triangle();
    f.j["extensionsUsed"] = {e};
    f.j["extensionsRequired"] = {e};
    const std::string msg = gltf_refusal(f.write("compressed.gltf"));
    CHECK_THAT(msg, Contains(fmt::format("compressed with {}", e)));
    CHECK_THAT(msg, Contains("without mesh compression"));
    CHECK_THAT(msg, Contains("gltfpack without -c/-cc"));  // gltfpack -cc writes meshopt
  }
  GltfFile instanced = gltf_one_triangle();
  instanced.j["extensionsRequired"] = {"EXT_mesh_gpu_instancing"};
  CHECK_THAT(gltf_refusal(instanced.write("instanced.gltf")),
             Contains("requires the extension EXT_mesh_gpu_instancing"));
  // extensions that change no geometry, and quantization, which is read
  GltfFile plain = gltf_one_triangle();
  plain.j["extensionsRequired"] = {"KHR_texture_transform", "KHR_materials_variants",
                                   "KHR_mesh_quantization", "KHR_lights_punctual"};
  CHECK(load_gltf(plain.write("neutral.gltf"), 100).triangles == 1);
  // Draco only in extensionsUsed: refused when the primitive has no uncompressed copy...
  GltfFile draco = gltf_one_triangle();
  draco.j["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  draco.j["accessors"].push_back({{"componentType", 5123}, {"count", 3}, {"type", "SCALAR"}});
  json& prim = draco.j["meshes"][0]["primitives"][0];
  prim["indices"] = 1;
  prim["extensions"] = {
      {"KHR_draco_mesh_compression", {{"bufferView", 0}, {"attributes", {{"POSITION", 0}}}}}};
  const std::string msg = gltf_refusal(draco.write("draco.gltf"));
  CHECK_THAT(msg, Contains("mesh 0, primitive 0 is compressed with KHR_draco_mesh_compression"));
  CHECK_THAT(msg, !Contains("invalid bufferView"));
  // ...and read from the copy when it has one
  prim["indices"] = draco.indices({0, 1, 2});
  CHECK(load_gltf(draco.write("draco_fallback.gltf"), 100).triangles == 1);
}

TEST_CASE("glTF: quantized positions are dequantized, and byteStride is respected", "[gltf]") {
  GltfFile f;
  // byte VEC3s padded to 4 bytes, short VEC3s to 8, as glTF aligns vertex attributes
  const std::vector<int8_t> b = {-128, -127, 127, 0, 64, 1, -1, 0, 0, 0, 0, 0};
  const std::vector<uint8_t> ub = {255, 128, 0, 0, 1, 2, 3, 0, 0, 0, 0, 0};
  const std::vector<int16_t> s = {-32768, 16384, 32767, 0, 5, -5, 7, 0, 0, 0, 0, 0};
  const std::vector<uint16_t> us = {65535, 1, 0, 0, 300, 2, 9, 0, 0, 0, 0, 0};
  std::vector<int> acc;
  for (bool normalized : {true, false}) {
    const auto fields = [&](int type) {
      return json{
          {"componentType", type}, {"count", 3}, {"type", "VEC3"}, {"normalized", normalized}};
    };
    acc.push_back(f.add(GltfFile::bytes_of(b), fields(5120), 4));
    acc.push_back(f.add(GltfFile::bytes_of(ub), fields(5121), 4));
    acc.push_back(f.add(GltfFile::bytes_of(s), fields(5122), 8));
    acc.push_back(f.add(GltfFile::bytes_of(us), fields(5123), 8));
  }
  // floats interleaved with 4 bytes of something else
  const std::vector<float> interleaved = {1, 2, 3, -9, 4, 5, 6, -9, 7, 8, 9, -9};
  acc.push_back(f.add(GltfFile::bytes_of(interleaved),
                      {{"componentType", 5126}, {"count", 3}, {"type", "VEC3"}}, 16));
  std::vector<std::array<int, 3>> prims;
  for (int a : acc) prims.push_back({a, 4, -1});
  f.mesh(prims);
  f.j["nodes"] = {{{"mesh", 0}}};
  f.j["scenes"] = {{{"nodes", {0}}}};
  f.j["extensionsUsed"] = {"KHR_mesh_quantization"};
  f.j["extensionsRequired"] = {"KHR_mesh_quantization"};
  const SceneGeometry g = load_gltf(f.write("quantized.gltf"), 100);
  REQUIRE(g.draws.size() == 9);
  using P = std::vector<std::array<float, 3>>;
  CHECK(g.draws[0].positions == P{{-1, -1, 1}, {64 / 127.0f, 1 / 127.0f, -1 / 127.0f}, {0, 0, 0}});
  CHECK(g.draws[1].positions ==
        P{{1, 128 / 255.0f, 0}, {1 / 255.0f, 2 / 255.0f, 3 / 255.0f}, {0, 0, 0}});
  CHECK(g.draws[2].positions ==
        P{{-1, 16384 / 32767.0f, 1}, {5 / 32767.0f, -5 / 32767.0f, 7 / 32767.0f}, {0, 0, 0}});
  CHECK(g.draws[3].positions ==
        P{{1, 1 / 65535.0f, 0}, {300 / 65535.0f, 2 / 65535.0f, 9 / 65535.0f}, {0, 0, 0}});
  CHECK(g.draws[4].positions == P{{-128, -127, 127}, {64, 1, -1}, {0, 0, 0}});
  CHECK(g.draws[5].positions == P{{255, 128, 0}, {1, 2, 3}, {0, 0, 0}});
  CHECK(g.draws[6].positions == P{{-32768, 16384, 32767}, {5, -5, 7}, {0, 0, 0}});
  CHECK(g.draws[7].positions == P{{65535, 1, 0}, {300, 2, 9}, {0, 0, 0}});
  CHECK(g.draws[8].positions == P{{1, 2, 3}, {4, 5, 6}, {7, 8, 9}});
  // an integer type glTF has no position of
  f.j["accessors"][acc[0]]["componentType"] = 5125;
  CHECK_THAT(gltf_refusal(f.write("quantized_int.gltf")), Contains("positions are VEC3 of float"));
}

TEST_CASE("glTF: a node naming a mesh, camera or child that does not exist is refused", "[gltf]") {
  const auto with = [](const json& node) {
    GltfFile f = gltf_one_triangle();
    f.j["nodes"].push_back(node);
    f.j["scenes"][0]["nodes"].push_back(1);
    return gltf_refusal(f.write("bad_node.gltf"));
  };
  CHECK_THAT(with({{"name", "lost"}, {"mesh", -2}}),
             Contains("node 1 (\"lost\") names mesh -2, which does not exist: the file has 1 "
                      "meshes (0 to 0)"));
  CHECK_THAT(with({{"mesh", 1}}), Contains("node 1 names mesh 1, which does not exist"));
  CHECK_THAT(with({{"camera", 3}}),
             Contains("node 1 names camera 3, which does not exist: the file has no cameras"));
  CHECK_THAT(with({{"children", {7}}}),
             Contains("node 1 lists child 7, which does not exist: the file has 2 nodes (0 to 1)"));
  CHECK_THAT(with({{"children", {0}}}),
             Contains("scene 0 lists node 0 (\"tri\"), a child of node 1"));
}

TEST_CASE("glTF: trees up to 1024 levels are read, deeper ones refused by depth, cycles as cycles",
          "[gltf]") {
  // a chain of `levels` nodes, each moved by (1, 0, 0), the triangle at the bottom
  const auto chain = [](int levels) {
    GltfFile f = gltf_one_triangle();
    f.j["nodes"] = json::array();
    for (int n = 0; n < levels; ++n) {
      json node = {{"translation", {1, 0, 0}}};
      if (n + 1 < levels)
        node["children"] = {n + 1};
      else
        node["mesh"] = 0;
      f.j["nodes"].push_back(node);
    }
    return f;
  };
  for (int levels : {70, 1024}) {
    const SceneGeometry g = load_gltf(chain(levels).write("chain.gltf"), 100);
    REQUIRE(g.draws.size() == 1);
    CHECK(transform_point(g.draws[0].world, 0, 0, 0) ==
          std::array<double, 3>{double(levels), 0, 0});
  }
  const std::string deep = gltf_refusal(chain(1025).write("chain_deep.gltf"));
  CHECK_THAT(deep, Contains("node 1024 is at level 1025 of the tree of root node 0"));
  CHECK_THAT(deep, Contains("limit of 1024 levels (a depth limit; the hierarchy has no cycle)"));
  // 1 -> 2 -> 3 -> 1 beside the root
  GltfFile cycle = gltf_one_triangle();
  cycle.j["nodes"].push_back({{"children", {2}}});
  cycle.j["nodes"].push_back({{"children", {3}}});
  cycle.j["nodes"].push_back({{"children", {1}}});
  CHECK_THAT(gltf_refusal(cycle.write("cycle.gltf")),
             Contains("the node hierarchy has a cycle (node 1 -> node 2 -> node 3 -> node 1"));
  GltfFile self = gltf_one_triangle();
  self.j["nodes"].push_back({{"children", {1}}});
  CHECK_THAT(gltf_refusal(self.write("self.gltf")), Contains("cycle (node 1 -> node 1"));
  GltfFile two_parents = gltf_one_triangle();
  two_parents.j["nodes"].push_back({{"children", {3}}});
  two_parents.j["nodes"].push_back({{"children", {3}}});
  two_parents.j["nodes"].push_back({{"mesh", 0}});
  CHECK_THAT(gltf_refusal(two_parents.write("two_parents.gltf")),
             Contains("node 3 is listed as a child by node 1 and by node 2"));
}

TEST_CASE("glTF: without scenes each root node is drawn once; without `scene`, scene 0", "[gltf]") {
  GltfFile f = gltf_one_triangle();
  f.j["nodes"] = {{{"mesh", 0}, {"children", {1}}}, {{"mesh", 0}}, {{"mesh", 0}}};
  f.j.erase("scenes");
  const SceneGeometry g = load_gltf(f.write("no_scenes.gltf"), 100);
  REQUIRE(g.draws.size() == 3);
  CHECK(g.draws[0].node_index == 0);
  CHECK(g.draws[1].node_index == 1);
  CHECK(g.draws[2].node_index == 2);
  REQUIRE(g.notes.size() == 1);
  CHECK_THAT(g.notes[0], Contains("the file has no scenes: its 2 root node(s)"));
  f.j["scenes"] = {{{"nodes", {2}}}, {{"nodes", {0}}}};
  const SceneGeometry first = load_gltf(f.write("two_scenes.gltf"), 100);
  REQUIRE(first.draws.size() == 1);
  CHECK(first.draws[0].node_index == 2);
  CHECK_THAT(first.notes.at(0), Contains("names no default scene: scene 0 of its 2 is drawn"));
  f.j["scene"] = 1;
  const SceneGeometry second = load_gltf(f.write("scene_1.gltf"), 100);
  CHECK(second.draws.size() == 2);
  CHECK(second.notes.empty());
}

TEST_CASE("glTF: counts no buffer can hold are refused, not allocated", "[gltf]") {
  // 2^62 + 1 positions of 12 bytes: their end wraps past 2^64 to byte 12
  GltfFile f = gltf_one_triangle();
  f.j["accessors"][0]["count"] = (uint64_t(1) << 62) + 1;
  f.j["meshes"][0]["primitives"][0]["indices"] = f.indices({0, 1, 2});
  CHECK_THAT(gltf_refusal(f.write("wrap.gltf"), UINT64_MAX),
             Contains("elements of 12 bytes, 12 bytes apart, from byte 0 do not fit in buffer "
                      "view 0 of 36 bytes"));
  // a sparse accessor without a buffer view holds as many elements as it claims
  GltfFile sparse = gltf_one_triangle();
  sparse.j["accessors"][0].erase("bufferView");
  sparse.j["accessors"][0]["count"] = 1000000000;
  sparse.j["accessors"][0]["sparse"] = {{"count", 1},
                                        {"indices", {{"bufferView", 0}, {"componentType", 5125}}},
                                        {"values", {{"bufferView", 0}}}};
  sparse.j["meshes"][0]["primitives"][0]["indices"] = sparse.indices({0, 1, 2});
  CHECK_THAT(gltf_refusal(sparse.write("sparse_huge.gltf")),
             Contains("1000000000 vertices, more than the audit takes"));
}
