// PNG files through libpng: an RGB image, rows from the top.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace depthprec {

// Writes width x height RGB pixels (3 bytes each, rows from the top) to path; throws OutputError
// naming the file when it cannot be written.
void write_png(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb);

}  // namespace depthprec
