// The GLSL of shaders/, embedded at build time (cmake/embed_shaders.cmake).
#pragma once

#include <string>

namespace pbm {

// Source of shaders/<name> (e.g. "surface.frag"); throws std::runtime_error if there is none.
const char* shader_source(const std::string& name);

}  // namespace pbm
