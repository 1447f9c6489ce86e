// The glTF loader on files made here, one feature or fault each: it reads what glTF 2.0 defines
// (files without scenes) as the spec says, and refuses the rest by name: the file, what is wrong,
// what is allowed.
#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "host/base/errors.h"
#include "host/model/scene_geometry.h"
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

}  // namespace

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
