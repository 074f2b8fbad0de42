#include "shader_program.h"

#include <stdexcept>
#include <string>

#include "embedded_shaders.h"

namespace pbm {
namespace {

GLuint compile(const gl::Functions& gl, GLenum type, const char* source, const char* name) {
  const GLuint shader = gl.CreateShader(type);
  gl.ShaderSource(shader, 1, &source, nullptr);
  gl.CompileShader(shader);
  GLint ok = 0;
  gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    gl.GetShaderInfoLog(shader, sizeof(log), nullptr, log);
    gl.DeleteShader(shader);
    throw std::runtime_error(std::string("shader ") + name + " does not compile: " + log);
  }
  return shader;
}

}  // namespace

GLuint link_program(const gl::Functions& gl, const char* name) {
  return link_program(gl, name, name);
}

GLuint link_program(const gl::Functions& gl, const char* vertex, const char* fragment) {
  const std::string name =
      vertex == std::string(fragment) ? vertex : std::string(vertex) + "+" + fragment;
  const GLuint vs =
      compile(gl, GL_VERTEX_SHADER, shader_source(std::string(vertex) + ".vert"), name.c_str());
  const GLuint fs =
      compile(gl, GL_FRAGMENT_SHADER, shader_source(std::string(fragment) + ".frag"), name.c_str());
  const GLuint program = gl.CreateProgram();
  gl.AttachShader(program, vs);
  gl.AttachShader(program, fs);
  gl.LinkProgram(program);
  gl.DeleteShader(vs);
  gl.DeleteShader(fs);
  GLint ok = 0;
  gl.GetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    gl.GetProgramInfoLog(program, sizeof(log), nullptr, log);
    gl.DeleteProgram(program);
    throw std::runtime_error("shader program " + name + " does not link: " + log);
  }
  return program;
}

}  // namespace pbm
