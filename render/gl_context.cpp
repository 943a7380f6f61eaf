#include "render/gl_context.hpp"

#include <stdexcept>

#include "core/errors.hpp"
#include "render/backends.hpp"

namespace fluidbed::render {

void GlContext::load_entry_points(GLADloadfunc load) {
  const int version = gladLoadGLContext(&gl_, load);
  if (version == 0) throw std::runtime_error(name() + ": could not load the GL entry points");
  if (GLAD_VERSION_MAJOR(version) * 10 + GLAD_VERSION_MINOR(version) < 33)
    throw std::runtime_error(name() + ": GL 3.3 core is needed, the driver gives " + version_string());
}

std::string GlContext::version_string() const {
  auto text = [this](GLenum what) {
    const auto* s = gl_.GetString ? gl_.GetString(what) : nullptr;
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  return text(GL_VERSION) + " | " + text(GL_RENDERER);
}

std::vector<std::string> context_backends() { return {"osmesa", "glfw"}; }

std::unique_ptr<GlContext> make_context(const std::string& name, int width, int height) {
  if (width <= 0 || height <= 0)
    throw InputError("GL context size must be positive, got " + std::to_string(width) + "x" +
                     std::to_string(height));
  if (name == "osmesa") return make_osmesa_context(width, height);
  if (name == "glfw") return make_glfw_context(width, height);
  std::string known;
  for (const auto& n : context_backends()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("unknown GL backend '" + name + "' (known: " + known + ")");
}

}  // namespace fluidbed::render
