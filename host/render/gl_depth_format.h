// The depth buffers a GL driver can hold, named as depthprec names storage formats: unorm16,
// unorm24 and unorm32 (GL_DEPTH_COMPONENT16/24/32) and float32 (GL_DEPTH_COMPONENT32F), each
// checked for what the driver really allocates (bits and component type of the attachment).
#pragma once

#include <string>
#include <vector>

namespace depthprec {

struct GlDepthFormat {
  std::string name;          // depthprec's storage format name: "unorm24"
  unsigned internal = 0;     // GL internal format asked for
  const char* gl_name = "";  // "GL_DEPTH_COMPONENT24"
  int bits = 0;              // what the driver gave: depth bits
  bool is_float = false;     // and component type (GL_FLOAT, else GL_UNSIGNED_NORMALIZED)
  bool complete = false;     // a framebuffer with it is complete
  // The driver stores exactly this format: complete, with the bits and type the name says.
  bool exact() const;
  std::string given() const;  // "24-bit unorm", "32-bit float", "incomplete framebuffer"
};

// Every format depthprec can ask a GL driver for, probed on the current context.
std::vector<GlDepthFormat> probe_gl_depth_formats();

// The format for a pair: throws InputError when the name is none of them or the driver does not
// store it exactly, listing the formats this driver does store.
GlDepthFormat gl_depth_format(const std::string& name);

}  // namespace depthprec
