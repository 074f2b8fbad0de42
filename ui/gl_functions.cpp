#include "gl_functions.h"

#include <stdexcept>
#include <string>

namespace pbm::gl {

Functions load_functions(GetProcAddress get_proc) {
  Functions f;
#define PBM_GL_LOAD(type, name)                                           \
  f.name = reinterpret_cast<type>(get_proc("gl" #name));                  \
  if (f.name == nullptr) {                                                \
    throw std::runtime_error("OpenGL context does not provide gl" #name); \
  }
  PBM_GL_FUNCTIONS(PBM_GL_LOAD)
#undef PBM_GL_LOAD
  return f;
}

void require_version(const Functions& gl, int major, int minor) {
  GLint have_major = 0, have_minor = 0;
  gl.GetIntegerv(GL_MAJOR_VERSION, &have_major);
  gl.GetIntegerv(GL_MINOR_VERSION, &have_minor);
  if (have_major < major || (have_major == major && have_minor < minor)) {
    const auto* version = reinterpret_cast<const char*>(gl.GetString(GL_VERSION));
    throw std::runtime_error("OpenGL " + std::to_string(major) + "." + std::to_string(minor) +
                             " core or newer is needed; the context offers " +
                             (version != nullptr ? std::string(version) : std::string("none")));
  }
}

}  // namespace pbm::gl
