// The window backend: GLFW (X11), a core-profile 3.3 context on a window, for the viewer.
// GLFW keeps process-wide state: one window at a time (its destructor ends GLFW), made and used on
// the program's main thread as GLFW asks.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <stdexcept>

#include "render/backends.hpp"

namespace fluidbed::render {
namespace {

GLADapiproc load(const char* name) { return glfwGetProcAddress(name); }

// The last error GLFW reported on this thread, for messages.
thread_local std::string glfw_error_text;
void on_glfw_error(int /*code*/, const char* description) { glfw_error_text = description; }

class GlfwContext final : public GlContext {
 public:
  GlfwContext(int width, int height) {
    glfwSetErrorCallback(&on_glfw_error);
    if (!glfwInit())
      throw std::runtime_error("glfw: cannot open a window (" +
                               (glfw_error_text.empty() ? std::string("no display?")
                                                        : glfw_error_text) +
                               "); use the osmesa backend for offscreen frames");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    window_ = glfwCreateWindow(width, height, "fluidbed", nullptr, nullptr);
    if (!window_) {
      glfwTerminate();
      throw std::runtime_error("glfw: could not create a GL 3.3 core window (" + glfw_error_text +
                               ")");
    }
    make_current();
    glfwSwapInterval(1);
    load_entry_points(&load);
  }
  ~GlfwContext() override {
    glfwDestroyWindow(window_);
    glfwTerminate();
  }

  void make_current() override { glfwMakeContextCurrent(window_); }
  int width() const override {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return w;
  }
  int height() const override {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return h;
  }
  void present() override {
    glfwSwapBuffers(window_);
    glfwPollEvents();
  }
  bool should_close() const override { return glfwWindowShouldClose(window_) != 0; }
  std::string name() const override { return "glfw"; }
  void* native_window() const override { return window_; }

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace

std::unique_ptr<GlContext> make_glfw_context(int width, int height) {
  return std::make_unique<GlfwContext>(width, height);
}

}  // namespace fluidbed::render
