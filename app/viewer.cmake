# `fluidbed view`: the engine thread and its command queue (a library of their own, so that the
# thread-sanitizer build needs only it and the engine), the window, and Dear ImGui. Debian's
# libimgui-dev ships the library and headers; its GLFW and OpenGL 3 backends only as sources among
# the package's examples: they are compiled here from that folder, without our warning flags.
add_library(fluidbed_view_engine STATIC view_engine.cpp view_script.cpp)
target_include_directories(fluidbed_view_engine PUBLIC ${CMAKE_CURRENT_SOURCE_DIR})
target_link_libraries(fluidbed_view_engine PUBLIC fluidbed_engine fluidbed_flags)

pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)
set(FLUIDBED_IMGUI_BACKENDS /usr/share/doc/libimgui-dev/examples/backends)
add_library(fluidbed_imgui_backends STATIC
  ${FLUIDBED_IMGUI_BACKENDS}/imgui_impl_glfw.cpp ${FLUIDBED_IMGUI_BACKENDS}/imgui_impl_opengl3.cpp)
# The backends' own headers; the OpenGL 3 backend loads GL through its bundled gl3w loader
# (imgui_impl_opengl3_loader.h, which opens libGL.so.1 at run time), beside our glad table.
target_include_directories(fluidbed_imgui_backends SYSTEM PUBLIC ${IMGUI_INCLUDEDIR}/backends)
target_link_libraries(fluidbed_imgui_backends PUBLIC PkgConfig::IMGUI PkgConfig::GLFW ${CMAKE_DL_LIBS})

target_sources(fluidbed PRIVATE view_command.cpp view_window.cpp view_panel.cpp)
target_link_libraries(fluidbed PRIVATE fluidbed_view_engine fluidbed_imgui_backends PkgConfig::GLFW)
