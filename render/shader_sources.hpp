#pragma once
// The GLSL sources of shaders/, embedded at build time (embed_shaders.cmake).
#include <string>
#include <string_view>
#include <vector>

namespace fluidbed::render {

struct ShaderSource {
  std::string_view name;  // file name: "particles.vert"
  std::string_view text;
};

std::vector<ShaderSource> shader_sources();

}  // namespace fluidbed::render
