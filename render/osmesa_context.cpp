// The offscreen backend: Mesa's OSMesa (llvmpipe), a core-profile 3.3 context drawing into a
// buffer in memory. Needs no display, so frames and render tests run anywhere.
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "render/backends.hpp"
#include "render/osmesa_api.hpp"

namespace fluidbed::render {
namespace {

GLADapiproc load(const char* name) { return osmesa::get_proc(name); }

class OsmesaContext final : public GlContext {
 public:
  OsmesaContext(int width, int height)
      : width_(width), height_(height),
        buffer_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4) {
    ctx_ = osmesa::create_core_context(3, 3);
    if (!ctx_) throw std::runtime_error("osmesa: could not create a GL 3.3 core-profile context");
    make_current();
    load_entry_points(&load);
  }
  ~OsmesaContext() override { osmesa::destroy(ctx_); }

  void make_current() override {
    if (!osmesa::make_current(ctx_, buffer_.data(), width_, height_))
      throw std::runtime_error("osmesa: could not make the context current");
  }
  int width() const override { return width_; }
  int height() const override { return height_; }
  std::string name() const override { return "osmesa"; }

 private:
  int width_, height_;
  std::vector<std::uint8_t> buffer_;
  void* ctx_ = nullptr;
};

}  // namespace

std::unique_ptr<GlContext> make_osmesa_context(int width, int height) {
  return std::make_unique<OsmesaContext>(width, height);
}

}  // namespace fluidbed::render

#if defined(__SANITIZE_ADDRESS__)
// Under the address sanitizer: OSMesa keeps a few hundred bytes of its context bookkeeping after
// OSMesaDestroyContext (inside libOSMesa, its LLVM and gallium parts), which the leak check
// would report at exit of every program that drew a frame. They are Mesa's, not ours.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libOSMesa.so\nleak:libLLVM-15.so\nleak:libglapi.so\n";
}
#endif
