#include "render/osmesa_api.hpp"

#include <GL/osmesa.h>

namespace fluidbed::render::osmesa {

void* create_core_context(int major, int minor) {
  const int attribs[] = {OSMESA_FORMAT,        OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,    24,
                         OSMESA_PROFILE,       OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION, major,
                         OSMESA_CONTEXT_MINOR_VERSION, minor,
                         0};
  return OSMesaCreateContextAttribs(attribs, nullptr);
}

bool make_current(void* ctx, void* buffer, int width, int height) {
  return OSMesaMakeCurrent(static_cast<OSMesaContext>(ctx), buffer, GL_UNSIGNED_BYTE, width,
                           height) == GL_TRUE;
}

void destroy(void* ctx) { OSMesaDestroyContext(static_cast<OSMesaContext>(ctx)); }

Proc get_proc(const char* name) { return OSMesaGetProcAddress(name); }

}  // namespace fluidbed::render::osmesa
