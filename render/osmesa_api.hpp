#pragma once
// A thin wrapper over OSMesa's C API, in its own translation unit: <GL/osmesa.h> pulls in Mesa's
// <GL/gl.h>, which must not meet the generated loader's <glad/gl.h> in one file.
#include <string>

namespace fluidbed::render::osmesa {

using Proc = void (*)(void);

// A core-profile context of at least `major`.`minor` with an RGBA8 buffer and a 24-bit depth
// buffer; nullptr when OSMesa refuses.
void* create_core_context(int major, int minor);
// Binds `ctx` to the RGBA8 `buffer` of width x height on the calling thread.
bool make_current(void* ctx, void* buffer, int width, int height);
void destroy(void* ctx);
Proc get_proc(const char* name);

}  // namespace fluidbed::render::osmesa
