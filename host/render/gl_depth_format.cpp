#include "host/render/gl_depth_format.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include "host/base/errors.h"

namespace depthprec {

namespace {

struct Candidate {
  const char* name;
  GLenum internal;
  const char* gl_name;
  int bits;
  bool is_float;
};

constexpr Candidate kCandidates[] = {
    {"unorm16", GL_DEPTH_COMPONENT16, "GL_DEPTH_COMPONENT16", 16, false},
    {"unorm24", GL_DEPTH_COMPONENT24, "GL_DEPTH_COMPONENT24", 24, false},
    {"unorm32", GL_DEPTH_COMPONENT32, "GL_DEPTH_COMPONENT32", 32, false},
    {"float32", GL_DEPTH_COMPONENT32F, "GL_DEPTH_COMPONENT32F", 32, true},
};

GlDepthFormat probe(const Candidate& c) {
  GlDepthFormat f;
  f.name = c.name;
  f.internal = c.internal;
  f.gl_name = c.gl_name;
  GLuint fbo = 0, rb = 0;
  glCreateFramebuffers(1, &fbo);
  glCreateRenderbuffers(1, &rb);
  glNamedRenderbufferStorage(rb, c.internal, 4, 4);
  glNamedFramebufferRenderbuffer(fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb);
  glNamedFramebufferDrawBuffer(fbo, GL_NONE);
  glNamedFramebufferReadBuffer(fbo, GL_NONE);
  f.complete = glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  if (f.complete) {
    GLint bits = 0, type = 0;
    glGetNamedFramebufferAttachmentParameteriv(fbo, GL_DEPTH_ATTACHMENT,
                                               GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE, &bits);
    glGetNamedFramebufferAttachmentParameteriv(fbo, GL_DEPTH_ATTACHMENT,
                                               GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &type);
    f.bits = bits;
    f.is_float = type == GL_FLOAT;
  }
  glDeleteFramebuffers(1, &fbo);
  glDeleteRenderbuffers(1, &rb);
  while (glGetError() != GL_NO_ERROR) f.complete = false;
  return f;
}

const Candidate* candidate(const std::string& name) {
  for (const auto& c : kCandidates)
    if (name == c.name) return &c;
  return nullptr;
}

}  // namespace

bool GlDepthFormat::exact() const {
  const Candidate* c = candidate(name);
  return complete && c && bits == c->bits && is_float == c->is_float;
}

std::string GlDepthFormat::given() const {
  if (!complete) return "incomplete framebuffer";
  return fmt::format("{}-bit {}", bits, is_float ? "float" : "unorm");
}

std::vector<GlDepthFormat> probe_gl_depth_formats() {
  std::vector<GlDepthFormat> out;
  for (const auto& c : kCandidates) out.push_back(probe(c));
  return out;
}

GlDepthFormat gl_depth_format(const std::string& name) {
  const auto all = probe_gl_depth_formats();
  std::string offered;
  for (const auto& f : all)
    if (f.exact()) offered += (offered.empty() ? "" : ", ") + f.name;
  if (offered.empty()) offered = "none";
  const Candidate* c = candidate(name);
  if (!c)
    throw InputError(fmt::format(
        "format {}: a GL driver stores only depth buffers of its own formats; this one stores {}",
        name, offered));
  for (const auto& f : all)
    if (f.name == name && !f.exact())
      throw InputError(fmt::format("format {}: {} gives {} on this driver; it stores exactly {}",
                                   name, c->gl_name, f.given(), offered));
  for (const auto& f : all)
    if (f.name == name) return f;
  throw Error(ExitCode::internal, "unreachable: " + name);
}

}  // namespace depthprec
