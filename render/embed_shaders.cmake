# Writes OUT, a C++ file holding the GLSL sources listed in SOURCES (a ;-list of paths), so the
# program carries its shaders. Run at build time: cmake -DOUT=... -DSOURCES=... -P this-file.
set(text "// Generated from shaders/ by render/embed_shaders.cmake; edit the .vert/.frag files.\n")
string(APPEND text "#include \"render/shader_sources.hpp\"\n\nnamespace fluidbed::render {\n\n")
string(APPEND text "std::vector<ShaderSource> shader_sources() {\n  return {\n")
foreach(path IN LISTS SOURCES)
  file(READ "${path}" body)
  get_filename_component(name "${path}" NAME)
  string(APPEND text "      {\"${name}\", R\"glsl(${body})glsl\"},\n")
endforeach()
string(APPEND text "  };\n}\n\n}  // namespace fluidbed::render\n")
file(WRITE "${OUT}.tmp" "${text}")
execute_process(COMMAND ${CMAKE_COMMAND} -E copy_if_different "${OUT}.tmp" "${OUT}")
file(REMOVE "${OUT}.tmp")
