# fluidbed_chart: PNG charts drawn by the program itself (see chart.hpp). Included from
# app/CMakeLists.txt; needs the fluidbed_flags target. stb comes from Debian's libstb-dev.
find_path(FLUIDBED_STB_INCLUDE_DIR stb_truetype.h PATH_SUFFIXES stb REQUIRED)
add_library(fluidbed_chart STATIC
  ${CMAKE_CURRENT_LIST_DIR}/chart.cpp
  ${CMAKE_CURRENT_LIST_DIR}/chart_draw.cpp
  ${CMAKE_CURRENT_LIST_DIR}/chart_raster.cpp
  ${CMAKE_CURRENT_LIST_DIR}/chart_text.cpp
  ${CMAKE_CURRENT_LIST_DIR}/chart_ticks.cpp)
target_include_directories(fluidbed_chart PUBLIC ${CMAKE_CURRENT_LIST_DIR})
target_include_directories(fluidbed_chart SYSTEM PRIVATE ${FLUIDBED_STB_INCLUDE_DIR})
target_link_libraries(fluidbed_chart PRIVATE fluidbed_flags)
