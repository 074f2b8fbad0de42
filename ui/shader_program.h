#pragma once
// Programs from the shaders embedded at build time (shaders/NAME.vert + NAME.frag).
#include "gl_functions.h"

namespace pbm {

// Compiles and links; throws std::runtime_error with the info log on failure.
GLuint link_program(const gl::Functions& gl, const char* name);
// The same with shaders/VERTEX.vert and shaders/FRAGMENT.frag.
GLuint link_program(const gl::Functions& gl, const char* vertex, const char* fragment);

}  // namespace pbm
