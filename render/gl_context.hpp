#pragma once
// A GL 3.3 core context behind one small interface, chosen by name:
//   "osmesa"  offscreen (Mesa's OSMesa, llvmpipe): frames and tests on machines with no display;
//   "glfw"    a window (the viewer).
// Both live in one binary: GL entry points come from the generated loader (glad, multi-context),
// filled through the active backend's own get-proc function, so no code here calls a GL library's
// exported symbols. A context is current on the thread that made it; only that thread touches GL.
#include <memory>
#include <string>
#include <vector>

#include <glad/gl.h>

namespace fluidbed::render {

class GlContext {
 public:
  virtual ~GlContext() = default;
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // The entry points of this context (loaded once, after it was first made current).
  const GladGLContext& gl() const { return gl_; }
  // Makes the context current on the calling thread.
  virtual void make_current() = 0;
  // The default framebuffer's size in pixels (the window's, or the offscreen buffer's).
  virtual int width() const = 0;
  virtual int height() const = 0;
  // Shows the default framebuffer (a window swaps buffers; offscreen: nothing).
  virtual void present() {}
  // A window asked to close (offscreen: never).
  virtual bool should_close() const { return false; }
  // The backend's window (a GLFWwindow* for glfw, for input and Dear ImGui); nullptr offscreen.
  virtual void* native_window() const { return nullptr; }
  // Backend name and what the driver says: "4.5 (Core Profile) Mesa 22.3.6 | llvmpipe ...".
  virtual std::string name() const = 0;
  std::string version_string() const;

 protected:
  GlContext() = default;
  // Fills gl_ through `load`, checks the version is at least 3.3; throws otherwise.
  void load_entry_points(GLADloadfunc load);

 private:
  GladGLContext gl_{};
};

// The names make_context knows, in the order of preference for headless use.
std::vector<std::string> context_backends();

// A context of backend `name` with a default framebuffer of width x height pixels, current on the
// calling thread. An unknown name throws InputError listing the known ones; a backend that cannot
// start (no display for glfw) throws std::runtime_error saying why.
std::unique_ptr<GlContext> make_context(const std::string& name, int width, int height);

}  // namespace fluidbed::render
