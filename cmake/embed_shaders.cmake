# Writes OUT_CPP: shader_source(name) returning each file of SHADER_DIR as a string, so the
# binaries carry their GLSL (run at build time by ui/CMakeLists.txt).
file(GLOB shader_files "${SHADER_DIR}/*.vert" "${SHADER_DIR}/*.frag")
list(SORT shader_files)
set(body "")
foreach(file IN LISTS shader_files)
  get_filename_component(name "${file}" NAME)
  file(READ "${file}" text)
  string(APPEND body "  if (name == \"${name}\") return R\"pbm_glsl(${text})pbm_glsl\";\n")
endforeach()
file(WRITE "${OUT_CPP}.tmp"
     "// Generated from shaders/ by cmake/embed_shaders.cmake; do not edit.\n"
     "#include \"embedded_shaders.h\"\n\n#include <stdexcept>\n\nnamespace pbm {\n\n"
     "const char* shader_source(const std::string& name) {\n${body}"
     "  throw std::runtime_error(\"no embedded shader '\" + name + \"'\");\n}\n\n}  // namespace pbm\n")
file(COPY_FILE "${OUT_CPP}.tmp" "${OUT_CPP}" ONLY_IF_DIFFERENT)
