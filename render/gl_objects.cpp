#include "render/gl_objects.hpp"

#include <stdexcept>

#include "render/shader_sources.hpp"

namespace fluidbed::render {
namespace {

std::string_view find_source(const std::string& name) {
  for (const auto& s : shader_sources())
    if (s.name == name) return s.text;
  throw std::runtime_error("no embedded shader named " + name);
}

GLuint compile(const GladGLContext& gl, GLenum type, const std::string& name) {
  const std::string_view text = find_source(name);
  const GLchar* src = text.data();
  const auto len = static_cast<GLint>(text.size());
  const GLuint s = gl.CreateShader(type);
  gl.ShaderSource(s, 1, &src, &len);
  gl.CompileShader(s);
  GLint ok = GL_FALSE;
  gl.GetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[2048] = {};
    gl.GetShaderInfoLog(s, sizeof log, nullptr, log);
    gl.DeleteShader(s);
    throw std::runtime_error("shader " + name + " does not compile: " + log);
  }
  return s;
}

}  // namespace

Program::Program(const GladGLContext& gl, const std::string& vertex, const std::string& fragment)
    : gl_(gl) {
  const GLuint vs = compile(gl, GL_VERTEX_SHADER, vertex);
  const GLuint fs = compile(gl, GL_FRAGMENT_SHADER, fragment);
  id_ = gl.CreateProgram();
  gl.AttachShader(id_, vs);
  gl.AttachShader(id_, fs);
  gl.LinkProgram(id_);
  gl.DeleteShader(vs);
  gl.DeleteShader(fs);
  GLint ok = GL_FALSE;
  gl.GetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[2048] = {};
    gl.GetProgramInfoLog(id_, sizeof log, nullptr, log);
    gl.DeleteProgram(id_);
    throw std::runtime_error("shaders " + vertex + " + " + fragment + " do not link: " + log);
  }
}

Program::~Program() { gl_.DeleteProgram(id_); }

GLint Program::uniform(const char* name) const { return gl_.GetUniformLocation(id_, name); }

GlName::GlName(const GladGLContext& gl, Kind kind) : gl_(gl), kind_(kind) {
  switch (kind_) {
    case Kind::buffer: gl_.GenBuffers(1, &id_); break;
    case Kind::vertex_array: gl_.GenVertexArrays(1, &id_); break;
    case Kind::texture: gl_.GenTextures(1, &id_); break;
    case Kind::framebuffer: gl_.GenFramebuffers(1, &id_); break;
    case Kind::renderbuffer: gl_.GenRenderbuffers(1, &id_); break;
  }
}

GlName::~GlName() {
  switch (kind_) {
    case Kind::buffer: gl_.DeleteBuffers(1, &id_); break;
    case Kind::vertex_array: gl_.DeleteVertexArrays(1, &id_); break;
    case Kind::texture: gl_.DeleteTextures(1, &id_); break;
    case Kind::framebuffer: gl_.DeleteFramebuffers(1, &id_); break;
    case Kind::renderbuffer: gl_.DeleteRenderbuffers(1, &id_); break;
  }
}

}  // namespace fluidbed::render
