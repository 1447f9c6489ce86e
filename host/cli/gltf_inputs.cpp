#include "host/cli/gltf_inputs.h"

#include <fmt/format.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

namespace depthprec::cli {

namespace {

// The JSON of a glTF file: the whole of a .gltf, the first chunk of a .glb (a 12-byte header,
// then chunks of length, type and data, the JSON chunk first). "" when a .glb is cut short.
std::string json_text(const std::string& bytes) {
  if (bytes.compare(0, 4, "glTF") != 0) return bytes;
  uint32_t length = 0, type = 0;
  if (bytes.size() < 20) return "";
  std::memcpy(&length, bytes.data() + 12, 4);  // glTF is little-endian, as every host we build on
  std::memcpy(&type, bytes.data() + 16, 4);
  if (type != 0x4E4F534Au || length > bytes.size() - 20) return "";
  return bytes.substr(20, length);
}

// Percent-decoding as tinygltf 2.7 does it before opening a URI ('+' is a space too), so the
// path checked is the path read.
std::string url_decoded(const std::string& uri) {
  std::string out;
  const auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return 0;
  };
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '+') {
      out += ' ';
    } else if (uri[i] == '%' && i + 2 < uri.size()) {
      out += static_cast<char>(hex(uri[i + 1]) * 16 + hex(uri[i + 2]));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

}  // namespace

std::vector<NamedInput> gltf_inputs(const std::string& gltf_path) {
  // Only a regular file has buffers to protect; anything else (a directory, a missing file) the
  // loader refuses with its own message.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(gltf_path, ec)) return {};
  std::ifstream in(gltf_path, std::ios::binary);
  if (!in) return {};
  const std::string bytes{std::istreambuf_iterator<char>(in), {}};
  const nlohmann::json j = nlohmann::json::parse(json_text(bytes), nullptr, false);
  if (!j.is_object()) return {};
  // tinygltf joins strings: the glTF file's directory (up to its last slash), a slash and the
  // URI; the loader reads nothing from the working directory (scene_geometry.cpp expand_beside).
  const size_t slash = gltf_path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "" : gltf_path.substr(0, slash + 1);
  std::vector<NamedInput> out;
  for (const auto& [key, what] : {std::pair<const char*, const char*>{"buffers", "buffer"},
                                  std::pair<const char*, const char*>{"images", "image"}}) {
    if (!j.contains(key) || !j[key].is_array()) continue;
    for (size_t k = 0; k < j[key].size(); ++k) {
      const nlohmann::json& item = j[key][k];
      if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
      const std::string uri = item["uri"].get<std::string>();
      if (uri.empty() || uri.rfind("data:", 0) == 0) continue;
      const std::string name = fmt::format("the glTF file's {} {}", what, k);
      const std::string file = url_decoded(uri);
      out.push_back({name, dir + file});
      // An absolute URI names that file to anyone reading the glTF, whatever tinygltf makes of it.
      if (!file.empty() && file[0] == '/') out.push_back({name, file});
    }
  }
  return out;
}

}  // namespace depthprec::cli
