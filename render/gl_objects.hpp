#pragma once
// Small owners of GL objects (programs, buffers, vertex arrays, framebuffers) for one context.
// Each frees its object with the context's own entry points; the context must outlive them.
#include <string>
#include <utility>

#include "render/gl_context.hpp"

namespace fluidbed::render {

// A linked program from two embedded shaders (shaders/NAME); throws with the driver's log.
class Program {
 public:
  Program(const GladGLContext& gl, const std::string& vertex, const std::string& fragment);
  ~Program();
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;
  GLuint id() const { return id_; }
  GLint uniform(const char* name) const;

 private:
  const GladGLContext& gl_;
  GLuint id_ = 0;
};

// Buffers, vertex arrays, textures, framebuffers and renderbuffers: a generated name, deleted
// on destruction.
class GlName {
 public:
  enum class Kind { buffer, vertex_array, texture, framebuffer, renderbuffer };
  GlName(const GladGLContext& gl, Kind kind);
  ~GlName();
  GlName(const GlName&) = delete;
  GlName& operator=(const GlName&) = delete;
  GLuint id() const { return id_; }

 private:
  const GladGLContext& gl_;
  Kind kind_;
  GLuint id_ = 0;
};

}  // namespace fluidbed::render
