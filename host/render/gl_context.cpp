#include "host/render/gl_context.h"

#include <dlfcn.h>
#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <fmt/format.h>

#include <cstdlib>
#include <cstring>
#include <vector>

#include "host/base/errors.h"

namespace depthprec {

namespace {

// What a user without a working driver installs (Debian's names): the EGL and GL loaders and
// Mesa's drivers, llvmpipe among them.
constexpr const char* kPackages = "libegl1 libgl1 libegl-mesa0 libgl1-mesa-dri libepoxy0";

[[noreturn]] void fail(const std::string& what) {
  throw RuntimeError(fmt::format(
      "no OpenGL 4.5 core context through EGL: {} (the emulator is unaffected; for rendering "
      "install {}, or on a GPU machine its driver's EGL; LIBGL_ALWAYS_SOFTWARE=1 selects "
      "llvmpipe)",
      what, kPackages));
}

bool has_extension(const char* list, const char* name) {
  if (!list) return false;
  const size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

EGLDisplay open_device(int index, std::string& platform) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!has_extension(client, "EGL_EXT_device_enumeration") ||
      !has_extension(client, "EGL_EXT_platform_device"))
    fail("the EGL client offers no EGL devices (EGL_EXT_device_enumeration)");
  EGLint count = 0;
  eglQueryDevicesEXT(0, nullptr, &count);
  std::vector<EGLDeviceEXT> devices(static_cast<size_t>(std::max(count, 0)));
  if (count > 0) eglQueryDevicesEXT(count, devices.data(), &count);
  if (index >= count) {
    // A device that is not there is the choice's fault, not the installation's: no packages to
    // install, but the displays there are to choose from.
    std::string there;
    for (const GlDisplay& d : list_gl_displays())
      there += fmt::format("{}{} ({}{})", there.empty() ? "" : ", ", d.choice,
                           d.usable ? "" : "not usable: ", d.what);
    throw RuntimeError(fmt::format(
        "--gl-device device:{}: out of range: this machine has {} EGL device{}{}; the displays "
        "to choose from: {} (`depthprec devices` lists them)",
        index, count, count == 1 ? "" : "s",
        count > 0 ? fmt::format(" (device:0 to device:{})", count - 1) : "",
        there.empty() ? "none" : there));
  }
  platform = fmt::format("device:{}", index);
  return eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[static_cast<size_t>(index)],
                                  nullptr);
}

}  // namespace

GlDeviceChoice GlDeviceChoice::parse(const std::string& text) {
  if (text == "auto" || text == "surfaceless") return {text};
  if (text.rfind("device:", 0) == 0) {
    const std::string n = text.substr(7);
    if (!n.empty() && n.find_first_not_of("0123456789") == std::string::npos && n.size() < 4)
      return {text};
  }
  throw Error(ExitCode::usage, fmt::format("--gl-device {}: expected auto, surfaceless or "
                                           "device:N (N from 0, see `depthprec devices`)",
                                           text));
}

GlContext::GlContext(const GlDeviceChoice& device) {
  // libepoxy loads libEGL itself and aborts the process when it is missing: look first.
  if (!dlopen("libEGL.so.1", RTLD_LAZY | RTLD_GLOBAL)) fail("libEGL.so.1 is not installed");
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!client) fail("the EGL client library answers no extensions");
  EGLDisplay dpy = EGL_NO_DISPLAY;
  const bool surfaceless_offered = has_extension(client, "EGL_MESA_platform_surfaceless");
  if (device.text == "surfaceless" || (device.text == "auto" && surfaceless_offered)) {
    if (!surfaceless_offered) fail("the EGL client has no surfaceless platform");
    dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    platform_ = "surfaceless";
  } else {
    dpy = open_device(device.text == "auto" ? 0 : std::atoi(device.text.c_str() + 7), platform_);
  }
  EGLint major = 0, minor = 0;
  if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, &major, &minor))
    fail(fmt::format("eglInitialize failed on the {} platform (EGL error 0x{:x})", platform_,
                     eglGetError()));
  display_ = dpy;
  const char* dpy_ext = eglQueryString(dpy, EGL_EXTENSIONS);
  if (!has_extension(dpy_ext, "EGL_KHR_surfaceless_context") ||
      !has_extension(dpy_ext, "EGL_KHR_no_config_context"))
    fail(fmt::format("the {} display cannot render without a surface", platform_));
  if (!eglBindAPI(EGL_OPENGL_API)) fail("the EGL display offers no desktop OpenGL");
  const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                            4,
                            EGL_CONTEXT_MINOR_VERSION,
                            5,
                            EGL_CONTEXT_OPENGL_PROFILE_MASK,
                            EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                            EGL_NONE};
  EGLContext ctx = eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
  if (ctx == EGL_NO_CONTEXT)
    fail(fmt::format("the {} display made no OpenGL 4.5 core context (EGL error 0x{:x})", platform_,
                     eglGetError()));
  context_ = ctx;
  if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx))
    fail(fmt::format("eglMakeCurrent failed (EGL error 0x{:x})", eglGetError()));
  renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  version_ = reinterpret_cast<const char*>(glGetString(GL_VERSION));
}

GlContext::~GlContext() {
  if (context_) {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
  }
  if (display_) eglTerminate(display_);
}

std::vector<GlDisplay> list_gl_displays() {
  std::vector<GlDisplay> out;
  const auto probe = [&out](const std::string& choice) {
    try {
      GlContext gl(GlDeviceChoice::parse(choice));
      out.push_back({choice, true, gl.description()});
    } catch (const std::exception& e) {
      out.push_back({choice, false, e.what()});
    }
  };
  if (!dlopen("libEGL.so.1", RTLD_LAZY | RTLD_GLOBAL)) {
    out.push_back({"auto", false, "libEGL.so.1 is not installed"});
    return out;
  }
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (has_extension(client, "EGL_MESA_platform_surfaceless")) probe("surfaceless");
  EGLint count = 0;
  if (has_extension(client, "EGL_EXT_device_enumeration")) eglQueryDevicesEXT(0, nullptr, &count);
  for (EGLint i = 0; i < count; ++i) probe(fmt::format("device:{}", i));
  return out;
}

std::string GlContext::description() const {
  return fmt::format("{}; OpenGL {}", renderer_, version_);
}

void check_gl(const char* what) {
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR) throw RuntimeError(fmt::format("OpenGL error 0x{:x} in {}", e, what));
}

}  // namespace depthprec
