#include "host/model/gltf_accessors.h"

#include <fmt/format.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>

#include "host/base/errors.h"

namespace depthprec {

namespace {

bool out_of(int index, size_t count) {
  return index < 0 || static_cast<size_t>(index) >= count;
}

// Errors about one accessor: the file, the accessor and what the primitive uses it for.
struct Blame {
  const std::string& path;
  int accessor;
  std::string what;
  InputError operator()(const std::string& why) const {
    return InputError(fmt::format("{}: accessor {} ({}): {}", path, accessor, what, why));
  }
};

// The first of `count` elements of `elem` bytes, `stride` apart, from byte `offset` of buffer view
// `view`, once they are checked to lie in the view and the view in its buffer. Checked by
// division, not by the end's byte: a file's count can make that product wrap around.
const unsigned char* elements_at(const tinygltf::Model& m, int view, size_t offset, size_t count,
                                 size_t elem, size_t stride, const Blame& bad) {
  if (out_of(view, m.bufferViews.size()))
    throw bad(fmt::format("buffer view {} does not exist", view));
  const tinygltf::BufferView& bv = m.bufferViews[view];
  if (out_of(bv.buffer, m.buffers.size()))
    throw bad(fmt::format("buffer view {} names buffer {}, which does not exist", view, bv.buffer));
  const std::vector<unsigned char>& data = m.buffers[bv.buffer].data;
  if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
    throw bad(fmt::format("buffer view {} (byte {}, {} bytes) ends past its buffer of {} bytes",
                          view, bv.byteOffset, bv.byteLength, data.size()));
  if (count > 0 && (offset > bv.byteLength || elem > bv.byteLength - offset ||
                    count - 1 > (bv.byteLength - offset - elem) / stride))
    throw bad(fmt::format(
        "{} elements of {} bytes, {} bytes apart, from byte {} do not fit in buffer view {} of {} "
        "bytes",
        count, elem, stride, offset, view, bv.byteLength));
  return data.data() + bv.byteOffset + offset;
}

// The accessor's `type` as the file spells it (tinygltf keeps a code).
std::string type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
    case TINYGLTF_TYPE_VEC3:
    case TINYGLTF_TYPE_VEC4:
      return fmt::format("VEC{}", type);
    case TINYGLTF_TYPE_MAT2:
      return "MAT2";
    case TINYGLTF_TYPE_MAT3:
      return "MAT3";
    case TINYGLTF_TYPE_MAT4:
      return "MAT4";
    default:
      return fmt::format("type {}", type);
  }
}

bool index_type(int type) {
  return type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
         type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
         type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
}

uint32_t unsigned_at(const unsigned char* p, int type) {
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

// A position component as binary32: a float as stored; an integer (KHR_mesh_quantization) as its
// value, exact in binary32, or normalized as glTF 2.0 maps it (3.11: max(c / 127, -1), c / 255,
// ...). The division is binary32's, correctly rounded: the binary32 nearest the exact quotient.
float component_at(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const float c = static_cast<int8_t>(*p);
      return normalized ? std::max(c / 127.0f, -1.0f) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const float c = *p;
      return normalized ? c / 255.0f : c;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t x;
      std::memcpy(&x, p, 2);
      const float c = x;
      return normalized ? std::max(c / 32767.0f, -1.0f) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t x;
      std::memcpy(&x, p, 2);
      const float c = x;
      return normalized ? c / 65535.0f : c;
    }
    default: {
      float x;
      std::memcpy(&x, p, 4);
      return x;
    }
  }
}

// The accessor's components, all of an element together, each converted by get(bytes): from its
// buffer view (byteStride apart when the view gives one), or zeros for a sparse accessor without
// one, then the sparse substitutions. The caller bounds the count of an accessor with no bytes
// behind it (the triangle and vertex limits, or the base positions' count).
template <class T, class Get>
std::vector<T> components(const tinygltf::Model& m, int accessor, const Blame& bad, Get get) {
  const tinygltf::Accessor& a = m.accessors[accessor];
  const int size = tinygltf::GetComponentSizeInBytes(a.componentType);
  const int ncomp = tinygltf::GetNumComponentsInType(a.type);
  if (size <= 0 || ncomp <= 0) throw bad("unknown component type or type");
  const size_t elem = static_cast<size_t>(size) * ncomp;
  std::vector<T> out;
  if (a.bufferView >= 0) {
    if (out_of(a.bufferView, m.bufferViews.size()))
      throw bad(fmt::format("buffer view {} does not exist", a.bufferView));
    const size_t byte_stride = m.bufferViews[a.bufferView].byteStride;
    const size_t stride = byte_stride ? byte_stride : elem;
    const unsigned char* p = elements_at(m, a.bufferView, a.byteOffset, a.count, elem, stride, bad);
    out.resize(a.count * ncomp);
    for (size_t k = 0; k < a.count; ++k)
      for (int c = 0; c < ncomp; ++c) out[k * ncomp + c] = get(p + k * stride + c * size);
  } else if (a.sparse.isSparse) {
    out.assign(a.count * ncomp, T(0));
  } else {
    // glTF reads such an accessor as zeros unless an extension supplies the data: for a position
    // that is compressed geometry, not a mesh collapsed to the origin
    throw bad(
        "no buffer view and not sparse: its data would come from an extension the audit does not "
        "read (compressed geometry?)");
  }
  if (!a.sparse.isSparse) return out;
  const auto& sp = a.sparse;
  if (sp.count < 0 || sp.indices.byteOffset < 0 || sp.values.byteOffset < 0)
    throw bad("a negative sparse count or byte offset");
  if (!index_type(sp.indices.componentType))
    throw bad(
        fmt::format("sparse indices of component type {}; glTF allows unsigned byte, short "
                    "or int",
                    sp.indices.componentType));
  const size_t isize = tinygltf::GetComponentSizeInBytes(sp.indices.componentType);
  const unsigned char* ip =
      elements_at(m, sp.indices.bufferView, sp.indices.byteOffset, sp.count, isize, isize, bad);
  const unsigned char* vp =
      elements_at(m, sp.values.bufferView, sp.values.byteOffset, sp.count, elem, elem, bad);
  for (size_t k = 0; k < static_cast<size_t>(sp.count); ++k) {
    const uint32_t i = unsigned_at(ip + k * isize, sp.indices.componentType);
    if (i >= a.count) throw bad(fmt::format("sparse index {} past its {} elements", i, a.count));
    for (int c = 0; c < ncomp; ++c) out[i * ncomp + c] = get(vp + k * elem + c * size);
  }
  return out;
}

// A VEC3 of positions or position offsets, as binary32.
std::vector<std::array<float, 3>> read_vec3(const tinygltf::Model& m, int accessor,
                                            const Blame& bad) {
  if (out_of(accessor, m.accessors.size())) throw bad("no such accessor");
  const tinygltf::Accessor& a = m.accessors[accessor];
  const int t = a.componentType;
  if (a.type != TINYGLTF_TYPE_VEC3 ||
      (t != TINYGLTF_COMPONENT_TYPE_FLOAT && t != TINYGLTF_COMPONENT_TYPE_BYTE &&
       t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && t != TINYGLTF_COMPONENT_TYPE_SHORT &&
       t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT))
    throw bad(fmt::format(
        "{} of component type {}: positions are VEC3 of float (5126), or with "
        "KHR_mesh_quantization of byte or short, signed or not, normalized or not (5120 to 5123)",
        type_name(a.type), t));
  const std::vector<float> flat = components<float>(
      m, accessor, bad, [&](const unsigned char* p) { return component_at(p, t, a.normalized); });
  std::vector<std::array<float, 3>> out(a.count);
  for (size_t k = 0; k < a.count; ++k) out[k] = {flat[3 * k], flat[3 * k + 1], flat[3 * k + 2]};
  return out;
}

}  // namespace

std::vector<std::array<float, 3>> primitive_positions(const tinygltf::Model& m,
                                                      const tinygltf::Primitive& prim,
                                                      const std::vector<double>& weights,
                                                      const std::string& path,
                                                      const std::string& where) {
  const int pos = prim.attributes.at("POSITION");
  std::vector<std::array<float, 3>> base = read_vec3(m, pos, {path, pos, where + ", POSITION"});
  // All-zero weights are the unmorphed mesh: its positions exactly, the targets unread.
  if (std::all_of(weights.begin(), weights.end(), [](double w) { return w == 0; })) return base;
  if (weights.size() != prim.targets.size())
    throw InputError(fmt::format(
        "{}: {}: {} morph weights for {} morph targets; glTF gives each target one weight", path,
        where, weights.size(), prim.targets.size()));
  // The pose the file defines is base + sum of w_i * target_i, exactly; a renderer sums it in
  // binary32, in an order and with fused operations of its own. Summed in binary64 and rounded to
  // binary32 once, the position is the binary32 nearest the exact pose (up to binary64's error,
  // far below half a binary32 unit), the same whatever order the targets come in.
  std::vector<std::array<double, 3>> sum(base.size());
  for (size_t k = 0; k < base.size(); ++k) sum[k] = {base[k][0], base[k][1], base[k][2]};
  for (size_t t = 0; t < prim.targets.size(); ++t) {
    const auto it = prim.targets[t].find("POSITION");
    if (weights[t] == 0 || it == prim.targets[t].end()) continue;
    const Blame bad{path, it->second, fmt::format("{}, morph target {} POSITION", where, t)};
    if (out_of(it->second, m.accessors.size())) throw bad("no such accessor");
    if (m.accessors[it->second].count != base.size())
      throw bad(fmt::format("{} offsets for the primitive's {} positions; glTF requires as many",
                            m.accessors[it->second].count, base.size()));
    const std::vector<std::array<float, 3>> delta = read_vec3(m, it->second, bad);
    for (size_t k = 0; k < base.size(); ++k)
      for (int c = 0; c < 3; ++c) sum[k][c] += weights[t] * static_cast<double>(delta[k][c]);
  }
  for (size_t k = 0; k < base.size(); ++k)
    for (int c = 0; c < 3; ++c) base[k][c] = static_cast<float>(sum[k][c]);
  return base;
}

std::vector<uint32_t> read_indices(const tinygltf::Model& m, int accessor, const std::string& path,
                                   const std::string& where) {
  const Blame bad{path, accessor, where + ", indices"};
  if (out_of(accessor, m.accessors.size())) throw bad("no such accessor");
  const tinygltf::Accessor& a = m.accessors[accessor];
  const int type = a.componentType;
  if (a.type != TINYGLTF_TYPE_SCALAR || !index_type(type))
    throw bad(fmt::format(
        "{} of component type {}; glTF's indices are SCALAR of unsigned byte, short or int "
        "(5121, 5123, 5125)",
        type_name(a.type), type));
  return components<uint32_t>(m, accessor, bad,
                              [type](const unsigned char* p) { return unsigned_at(p, type); });
}

bool triangle_mode(int mode) {
  return mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
         mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

uint64_t triangle_count(int mode, uint64_t n) {
  if (mode == TINYGLTF_MODE_TRIANGLES) return n / 3;
  return n < 3 ? 0 : n - 2;
}

std::vector<std::array<uint32_t, 3>> triangulate(int mode, const std::vector<uint32_t>& v) {
  std::vector<std::array<uint32_t, 3>> t;
  t.reserve(triangle_count(mode, v.size()));
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    for (size_t i = 0; i + 2 < v.size(); i += 3) t.push_back({v[i], v[i + 1], v[i + 2]});
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    // p_i = {v_i, v_(i + 1 + i % 2), v_(i + 2 - i % 2)}: every other one turned, so all face
    // the way the first does
    for (size_t i = 0; i + 2 < v.size(); ++i)
      t.push_back({v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]});
  } else {
    for (size_t i = 0; i + 2 < v.size(); ++i) t.push_back({v[i + 1], v[i + 2], v[0]});  // p_i
  }
  return t;
}

}  // namespace depthprec
