// A user's scene as the audit draws it (docs/audit.md "Input"): the triangles of a glTF 2.0 file
// (.gltf or .glb, read with tinygltf), each triangle primitive (TRIANGLES, TRIANGLE_STRIP,
// TRIANGLE_FAN) under each node that instances it one draw, in the order the scene's node trees
// list them (depth first), which is the draw order. Object positions are binary32, as a vertex
// buffer holds them: the file's floats, its quantized integers dequantized, or the pose its
// default morph weights give; node transforms are composed in binary64 into each draw's world
// matrix. The file's perspective cameras are kept by name.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "host/model/matrix.h"

namespace depthprec {

// One primitive of one mesh under one node: what a report names a surface by.
struct Draw {
  std::string node, mesh;  // names ("node 3", "mesh 1" where the file gives none)
  int node_index = 0, mesh_index = 0, primitive = 0;
  Mat4d world{};  // object to world, binary64
  // Object positions and triangle corners as the file has them.
  std::vector<std::array<float, 3>> positions;
  std::vector<std::array<uint32_t, 3>> triangles;
  uint32_t first_triangle = 0;  // the scene-wide index of its first triangle
  std::string label() const;    // "decal (mesh decal, primitive 0)"
};

struct GltfCamera {
  std::string name;            // the camera's name, else its node's
  std::string node;            // its node's name ("" where the node has none)
  bool orthographic = false;   // kept to be refused by name: the audit takes perspective ones
  Mat4d world{};               // camera to world (it looks down its -z, +y up)
  double yfov = 0;             // radians
  double aspect = 0;           // 0: not given
  double znear = 0, zfar = 0;  // zfar 0: infinite
};

struct SceneGeometry {
  std::string source;
  std::vector<Draw> draws;
  std::vector<GltfCamera> cameras;
  uint64_t triangles = 0;
  uint64_t skipped = 0;  // primitives under the scene's nodes not drawn (points, lines, ...)
  // What a report says about how the file was read: the primitives not drawn and why, the nodes
  // drawn when the file names no scene. Sentences, without the file's name.
  std::vector<std::string> notes;
  // The draw of scene-wide triangle t (binary search over first_triangle).
  const Draw& draw_of(uint32_t t) const;
  // Whether triangles a and b are neighbours on one surface: the same draw, a corner in common
  // (the same index, or the same object position: a vertex split where normals or UVs differ).
  // At a pixel on their seam the coverage rule gives it to one; whichever, no surface shows
  // through.
  bool neighbours(uint32_t a, uint32_t b) const;
};

// Loads path; throws InputError naming the file and what is wrong: not glTF, a required
// extension the audit does not read (compressed geometry among them), a node, mesh, camera,
// accessor or scene that does not exist, a node hierarchy that is not a set of trees or is deeper
// than kMaxNodeDepth (gltf_nodes.h), no triangles, an accessor reaching past its buffer, or more
// than max_triangles triangles (or 3 vertices a triangle; checked from the accessors before any
// is read).
SceneGeometry load_gltf(const std::string& path, uint64_t max_triangles);

// The centre of the world-space bounding box of every draw's positions.
std::array<double, 3> bounding_box_centre(const SceneGeometry& geometry);

}  // namespace depthprec
