// The node forest of a glTF file (docs/audit.md "Input"): every node's mesh, camera and children
// checked to exist, the hierarchy checked to be the disjoint trees glTF requires, and the scene's
// trees listed depth first with each node's world matrix: the draw order.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "host/model/matrix.h"

namespace tinygltf {
class Model;
}

namespace depthprec {

// Deeper than any authored file: a chain this long is a broken or hostile file, and each level
// adds a rounding to the world matrix.
constexpr int kMaxNodeDepth = 1024;

struct NodeOrder {
  std::vector<std::pair<int, Mat4d>> nodes;  // node index, object to world; in draw order
  std::string note;  // how the nodes were chosen when the file does not say, else ""
};

// The default scene's nodes (scene 0 when `scene` is absent; with no `scenes`, every root node in
// index order); throws InputError naming the file, the node or scene and the bad value.
NodeOrder node_order(const tinygltf::Model& model, const std::string& path);

}  // namespace depthprec
