#pragma once
// The backends' factories (gl_context.cpp picks one by name). Each returns a context already
// current on the calling thread, with its entry points loaded.
#include <memory>

#include "render/gl_context.hpp"

namespace fluidbed::render {

std::unique_ptr<GlContext> make_osmesa_context(int width, int height);
std::unique_ptr<GlContext> make_glfw_context(int width, int height);

}  // namespace fluidbed::render
