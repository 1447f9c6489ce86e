// A glTF primitive's vertices and triangles as the audit draws them (docs/audit.md "Input"):
// positions as a vertex buffer holds them (binary32, integer ones dequantized as
// KHR_mesh_quantization says, morph targets applied), indices, and the triangles of the three
// triangle topologies. Every byte is checked to lie in its buffer before it is read.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
struct Primitive;
}  // namespace tinygltf

namespace depthprec {

// prim's POSITION with its morph targets at `weights` (the node's, else the mesh's; empty or all
// zero: none). `where` names the primitive in errors ("mesh wall, primitive 0").
std::vector<std::array<float, 3>> primitive_positions(const tinygltf::Model& model,
                                                      const tinygltf::Primitive& prim,
                                                      const std::vector<double>& weights,
                                                      const std::string& path,
                                                      const std::string& where);

// The values of an index accessor (unsigned byte, short or int SCALAR).
std::vector<uint32_t> read_indices(const tinygltf::Model& model, int accessor,
                                   const std::string& path, const std::string& where);

// Whether mode is one the audit draws: TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN.
bool triangle_mode(int mode);
// How many triangles n vertices of a triangle mode make.
uint64_t triangle_count(int mode, uint64_t n);
// The triangles of a triangle mode over the vertex list v (the indices, or 0 to count - 1), as
// glTF 2.0 defines them (3.7.2.1): strips alternate their winding, fans turn about v[0].
// Degenerate ones are kept: the rasteriser draws nothing of them.
std::vector<std::array<uint32_t, 3>> triangulate(int mode, const std::vector<uint32_t>& v);

}  // namespace depthprec
