// Kernel and format sources compiled into the binary (cmake/embed_sources.cmake).
#pragma once

#include <map>
#include <string>

namespace depthprec {

// Keyed by path relative to the project root, e.g. "kernels/mts.cl".
const std::map<std::string, std::string>& embedded_sources();

// The source with every #include "path" of an embedded file replaced by that file's text (each
// file once). Throws RuntimeError naming the file when an include is not embedded.
std::string expand_embedded(const std::string& path);

}  // namespace depthprec
