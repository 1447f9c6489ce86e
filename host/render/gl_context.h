// A headless OpenGL 4.5 core context through EGL (no window, no display server), made current on
// the calling thread: Mesa's surfaceless platform (llvmpipe on a machine without a GPU), or an
// EGL device (a GPU driver's). Function pointers come from libepoxy.
#pragma once

#include <string>
#include <vector>

namespace depthprec {

// Which EGL display to render on: "auto" (surfaceless when the EGL client offers it, else the
// first EGL device), "surfaceless", or "device:N" (the N-th of eglQueryDevicesEXT, from 0).
struct GlDeviceChoice {
  std::string text = "auto";
  static GlDeviceChoice parse(const std::string& text);  // throws a usage Error
};

class GlContext {
 public:
  // Throws RuntimeError naming the Debian packages when no OpenGL 4.5 core context can be made.
  explicit GlContext(const GlDeviceChoice& device = {});
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  const std::string& renderer() const { return renderer_; }  // GL_RENDERER
  const std::string& version() const { return version_; }    // GL_VERSION
  const std::string& platform() const { return platform_; }  // "surfaceless" or "device:N"
  std::string description() const;  // "llvmpipe (LLVM 15.0.6, 256 bits); OpenGL 4.5 (Core ...)"

 private:
  void* display_ = nullptr;
  void* context_ = nullptr;
  std::string renderer_, version_, platform_;
};

// Throws RuntimeError naming `what` when the context has an OpenGL error pending.
void check_gl(const char* what);

// Every display --gl-device can name (surfaceless, device:0, ...) with what it renders on, or
// why it cannot: what `depthprec devices` lists.
struct GlDisplay {
  std::string choice;  // "surfaceless", "device:0"
  bool usable = false;
  std::string what;  // GlContext::description(), or the error
};
std::vector<GlDisplay> list_gl_displays();

}  // namespace depthprec
