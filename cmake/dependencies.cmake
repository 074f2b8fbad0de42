# Every third-party package comes from Debian (tools/setup installs them).
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(spdlog REQUIRED)
find_package(assimp 5.2 REQUIRED CONFIG)
if(PBM_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
# The liquid's surface mesh and .vdb level sets (engine/liquid/liquid_surface_mesh.h). Debian
# installs OpenVDB's find module beside its library rather than on CMake's path; it wants Boost's
# iostreams (libboost-iostreams-dev), whose headers OpenVDB's own include.
list(APPEND CMAKE_MODULE_PATH /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/OpenVDB)
find_package(OpenVDB 10 REQUIRED)
# Bullet is the side-by-side peer of `pbm bench deform`.
find_package(Bullet REQUIRED)
# The renderer's headless context and the PNG frames. Never OpenGL::GL (PLATFORM.md): OSMesa's
# gl* must not be shadowed by libGL's.
find_package(PkgConfig REQUIRED)
pkg_check_modules(OSMESA REQUIRED IMPORTED_TARGET osmesa)
pkg_check_modules(PNG REQUIRED IMPORTED_TARGET libpng)
# Dear ImGui (1.86, Debian's static library; its OpenGL backend is not used, see
# ui/imgui_renderer.h): the studio's panels, and the font of `pbm bench tradeoff`'s plot.
pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)
# The studio: Qt 6 widgets with an OpenGL viewport.
option(PBM_BUILD_STUDIO "Build the Qt studio (pbm-studio)" ON)
if(PBM_BUILD_STUDIO)
  find_package(Qt6 6.4 REQUIRED COMPONENTS Widgets OpenGL OpenGLWidgets)
endif()
