#include "host/model/gltf_nodes.h"

#include <fmt/format.h>
#include <tiny_gltf.h>

#include <algorithm>

#include "host/base/errors.h"

namespace depthprec {

namespace {

// A node's local matrix: its `matrix` (column-major in glTF), else T * R * S.
Mat4d local_matrix(const tinygltf::Node& n) {
  Mat4d m = mat_identity();
  if (n.matrix.size() == 16) {
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) m[r * 4 + c] = n.matrix[c * 4 + r];
    return m;
  }
  Mat4d t = mat_identity(), rot = mat_identity(), s = mat_identity();
  if (n.translation.size() == 3)
    for (int i = 0; i < 3; ++i) t[i * 4 + 3] = n.translation[i];
  if (n.rotation.size() == 4) {
    const double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
    const double r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - z * w),     2 * (x * z + y * w),
                         2 * (x * y + z * w),     1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
                         2 * (x * z - y * w),     2 * (y * z + x * w),     1 - 2 * (x * x + y * y)};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) rot[i * 4 + j] = r[i * 3 + j];
  }
  if (n.scale.size() == 3)
    for (int i = 0; i < 3; ++i) s[i * 4 + i] = n.scale[i];
  return mat_mul(t, mat_mul(rot, s));
}

std::string node_name(const tinygltf::Model& m, int n) {
  const std::string& name = m.nodes[n].name;
  return name.empty() ? fmt::format("node {}", n) : fmt::format("node {} (\"{}\")", n, name);
}

// "the file has 3 meshes (0 to 2)": what a reference may name.
std::string range_of(size_t count, const char* what) {
  if (count == 0) return fmt::format("the file has no {}", what);
  return fmt::format("the file has {} {} (0 to {})", count, what, count - 1);
}

bool outside(int index, size_t count) {
  return index < 0 || static_cast<size_t>(index) >= count;
}

// Each node's parent (-1 for a root node), every reference checked on the way.
std::vector<int> parents(const tinygltf::Model& m, const std::string& path) {
  const size_t count = m.nodes.size();
  std::vector<int> parent(count, -1);
  for (size_t i = 0; i < count; ++i) {
    const int n = static_cast<int>(i);
    const tinygltf::Node& node = m.nodes[i];
    // tinygltf stores an absent mesh or camera as -1, so a file's own -1 cannot be told apart
    if (node.mesh != -1 && outside(node.mesh, m.meshes.size()))
      throw InputError(fmt::format("{}: {} names mesh {}, which does not exist: {}", path,
                                   node_name(m, n), node.mesh,
                                   range_of(m.meshes.size(), "meshes")));
    if (node.camera != -1 && outside(node.camera, m.cameras.size()))
      throw InputError(fmt::format("{}: {} names camera {}, which does not exist: {}", path,
                                   node_name(m, n), node.camera,
                                   range_of(m.cameras.size(), "cameras")));
    for (int c : node.children) {
      if (outside(c, count))
        throw InputError(fmt::format("{}: {} lists child {}, which does not exist: {}", path,
                                     node_name(m, n), c, range_of(count, "nodes")));
      if (parent[c] != -1)
        throw InputError(fmt::format(
            "{}: {} is listed as a child by {} and by {}; in glTF a node has at most one parent",
            path, node_name(m, c), node_name(m, parent[c]), node_name(m, n)));
      parent[c] = n;
    }
  }
  return parent;
}

// With one parent a node, a cycle is a loop of parent links: followed up from every node, with
// the nodes on the current path marked, a link back onto the path is one. The depths found on the
// way make the walk O(nodes), and the depth limit is told apart from a cycle.
void check_tree(const tinygltf::Model& m, const std::vector<int>& parent, const std::string& path) {
  constexpr int unknown = -1, on_path = -2;
  std::vector<int> depth(parent.size(), unknown), up;
  for (size_t start = 0; start < parent.size(); ++start) {
    up.clear();
    int k = static_cast<int>(start);
    while (k >= 0 && depth[k] == unknown) {
      depth[k] = on_path;
      up.push_back(k);
      k = parent[k];
    }
    if (k >= 0 && depth[k] == on_path) {
      // up runs child to parent; the cycle is its part from k on, shown parent to child
      std::vector<int> loop(std::find(up.begin(), up.end(), k), up.end());
      std::reverse(loop.begin(), loop.end());
      std::rotate(loop.begin(), loop.end() - 1, loop.end());  // from k, where the walk met it
      std::string shown;
      for (size_t i = 0; i < loop.size() && i < 8; ++i) shown += node_name(m, loop[i]) + " -> ";
      shown += loop.size() > 8 ? "..." : node_name(m, loop[0]);
      throw InputError(fmt::format(
          "{}: the node hierarchy has a cycle ({}, each listing the next as a child); glTF's "
          "node hierarchy is a set of trees",
          path, shown));
    }
    int d = k < 0 ? -1 : depth[k];
    for (auto it = up.rbegin(); it != up.rend(); ++it) {
      depth[*it] = ++d;
      if (d >= kMaxNodeDepth) {
        int root = *it;
        while (parent[root] >= 0) root = parent[root];
        throw InputError(fmt::format(
            "{}: {} is at level {} of the tree of root {} (level 1): past the audit's limit of {} "
            "levels (a depth limit; the hierarchy has no cycle)",
            path, node_name(m, *it), d + 1, node_name(m, root), kMaxNodeDepth));
      }
    }
  }
}

// The root nodes to draw, in order.
std::vector<int> scene_roots(const tinygltf::Model& m, const std::vector<int>& parent,
                             const std::string& path, std::string& note) {
  const size_t scenes = m.scenes.size();
  // tinygltf leaves -1 for an absent `scene`
  if (m.defaultScene != -1 && outside(m.defaultScene, scenes))
    throw InputError(fmt::format("{}: \"scene\": {} names a scene that does not exist: {}", path,
                                 m.defaultScene, range_of(scenes, "scenes")));
  std::vector<int> roots;
  if (scenes == 0) {
    // glTF lets a loader draw nothing here (a library of nodes); the audit draws what the file
    // holds, each tree once, as common viewers do
    for (size_t n = 0; n < parent.size(); ++n)
      if (parent[n] < 0) roots.push_back(static_cast<int>(n));
    if (!roots.empty())
      note = fmt::format(
          "the file has no scenes: its {} root node(s) (those no node lists as a child) are "
          "drawn, in index order",
          roots.size());
    return roots;
  }
  const int s = std::max(m.defaultScene, 0);
  if (m.defaultScene == -1 && scenes > 1)
    note = fmt::format("the file names no default scene: scene 0 of its {} is drawn", scenes);
  std::vector<bool> listed(parent.size(), false);
  for (int n : m.scenes[s].nodes) {
    if (outside(n, parent.size()))
      throw InputError(fmt::format("{}: scene {} lists node {}, which does not exist: {}", path, s,
                                   n, range_of(parent.size(), "nodes")));
    if (parent[n] >= 0)
      throw InputError(fmt::format(
          "{}: scene {} lists {}, a child of {}; a scene lists root nodes (nodes without a parent)",
          path, s, node_name(m, n), node_name(m, parent[n])));
    if (listed[n])
      throw InputError(fmt::format("{}: scene {} lists {} twice; a scene lists each root node once",
                                   path, s, node_name(m, n)));
    listed[n] = true;
    roots.push_back(n);
  }
  return roots;
}

}  // namespace

NodeOrder node_order(const tinygltf::Model& m, const std::string& path) {
  const std::vector<int> parent = parents(m, path);
  check_tree(m, parent, path);
  NodeOrder out;
  // Trees, each visited once from its root: at most one entry a node. An explicit stack, so no
  // depth of hierarchy reaches the call stack. A root's matrix is the product I * local, as a
  // child's is parent * local, so a -0 entry becomes +0 alike at every level.
  std::vector<std::pair<int, Mat4d>> stack;
  for (int root : scene_roots(m, parent, path, out.note)) {
    stack.emplace_back(root, mat_mul(mat_identity(), local_matrix(m.nodes[root])));
    while (!stack.empty()) {
      auto [n, world] = stack.back();
      stack.pop_back();
      out.nodes.emplace_back(n, world);
      const std::vector<int>& children = m.nodes[n].children;
      for (auto c = children.rbegin(); c != children.rend(); ++c)
        stack.emplace_back(*c, mat_mul(world, local_matrix(m.nodes[*c])));
    }
  }
  return out;
}

}  // namespace depthprec
