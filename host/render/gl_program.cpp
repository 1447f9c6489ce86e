#include "host/render/gl_program.h"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <algorithm>
#include <regex>

#include "host/base/embedded_sources.h"
#include "host/base/errors.h"
#include "host/model/frame_setup.h"
#include "host/model/vertex_stage.h"
#include "host/runtime/kernel_variant.h"

namespace depthprec {

namespace {

unsigned compile(GLenum stage, const std::string& path, const std::string& defines) {
  const std::string text = "#version 450 core\n" + defines + "#line 1\n" + glsl_source(path);
  const GLuint sh = glCreateShader(stage);
  const char* src = text.c_str();
  glShaderSource(sh, 1, &src, nullptr);
  glCompileShader(sh);
  GLint ok = 0;
  glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetShaderiv(sh, GL_INFO_LOG_LENGTH, &len);
    std::string log(static_cast<size_t>(std::max(len, 1)), '\0');
    glGetShaderInfoLog(sh, len, nullptr, log.data());
    glDeleteShader(sh);
    throw RuntimeError(fmt::format("{} does not compile on this driver ({}): {}", path,
                                   defines.empty() ? "no defines" : defines, log.c_str()));
  }
  return sh;
}

}  // namespace

std::string glsl_source(const std::string& path) {
  // GLSL's #line takes no file name (without ARB_shading_language_include): the expansion's
  // `#line N "file"` markers keep their numbers only.
  static const std::regex file_line(R"re(#line (\d+) "[^"]*")re");
  return std::regex_replace(expand_embedded(path), file_line, "#line $1");
}

std::string shader_defines(const Scene& scene, const EvalPair& pair) {
  const TechniqueInfo& ti = info(depth_path(scene, pair.technique));
  return fmt::format(
      "#define DEPTH_FROM {}\n#define FRAG_DEPTH {}\n#define VERTEX_LOG {}\n#define DEPTH_RANGE_GL "
      "{}\n#define COMPOSE_PREMULTIPLIED {}\n#define VIEW_TRANSLATE {}\n#define RELATIVE_TO_EYE "
      "{}\n",
      static_cast<int>(ti.from), static_cast<int>(ti.fragment), static_cast<int>(vertex_log(ti)),
      pair.depth_range == DepthRange::gl ? 1 : 0,
      vertex_path(scene.pipeline) == VertexPath::premultiplied ? 1 : 0,
      view_translated_on_gpu(scene) ? 1 : 0,
      vertex_path(scene.pipeline) == VertexPath::relative_to_eye ? 1 : 0);
}

unsigned link_program(const std::string& vertex_path, const std::string& fragment_path,
                      const std::string& defines) {
  const unsigned vs = compile(GL_VERTEX_SHADER, vertex_path, defines);
  const unsigned fs = compile(GL_FRAGMENT_SHADER, fragment_path, defines);
  const GLuint program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint linked = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &linked);
  if (!linked)
    throw RuntimeError(
        fmt::format("{} and {} do not link on this driver", vertex_path, fragment_path));
  return program;
}

}  // namespace depthprec
