#include "imgui_renderer.h"

#include <cstddef>

#include "shader_program.h"

namespace pbm {

ImGuiRenderer::ImGuiRenderer(const gl::Functions& gl) : gl_(gl) {
  program_ = link_program(gl, "imgui");
  unsigned char* pixels = nullptr;
  int width = 0, height = 0;
  ImGuiIO& io = ImGui::GetIO();
  io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
  gl.GenTextures(1, &font_);
  gl.BindTexture(GL_TEXTURE_2D, font_);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
  io.Fonts->SetTexID(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(font_)));

  gl.GenVertexArrays(1, &vao_);
  gl.GenBuffers(1, &vbo_);
  gl.GenBuffers(1, &ibo_);
  gl.BindVertexArray(vao_);
  gl.BindBuffer(GL_ARRAY_BUFFER, vbo_);
  gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo_);
  const auto stride = static_cast<GLsizei>(sizeof(ImDrawVert));
  gl.EnableVertexAttribArray(0);
  gl.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, stride,
                         reinterpret_cast<void*>(offsetof(ImDrawVert, pos)));
  gl.EnableVertexAttribArray(1);
  gl.VertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, stride,
                         reinterpret_cast<void*>(offsetof(ImDrawVert, uv)));
  gl.EnableVertexAttribArray(2);
  gl.VertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, stride,
                         reinterpret_cast<void*>(offsetof(ImDrawVert, col)));
  gl.BindVertexArray(0);
}

ImGuiRenderer::~ImGuiRenderer() {
  gl_.DeleteBuffers(1, &vbo_);
  gl_.DeleteBuffers(1, &ibo_);
  gl_.DeleteVertexArrays(1, &vao_);
  gl_.DeleteTextures(1, &font_);
  gl_.DeleteProgram(program_);
}

void ImGuiRenderer::draw(const ImDrawData* data, int framebuffer_width, int framebuffer_height) {
  if (data == nullptr || data->CmdListsCount == 0) return;
  const gl::Functions& gl = gl_;
  gl.Viewport(0, 0, framebuffer_width, framebuffer_height);
  gl.Enable(GL_BLEND);
  gl.BlendEquation(GL_FUNC_ADD);
  gl.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  gl.Disable(GL_CULL_FACE);
  gl.Disable(GL_DEPTH_TEST);
  gl.Enable(GL_SCISSOR_TEST);
  gl.UseProgram(program_);
  // Display coordinates (points) to clip space, y down.
  const float l = data->DisplayPos.x, r = l + data->DisplaySize.x;
  const float t = data->DisplayPos.y, b = t + data->DisplaySize.y;
  const float projection[16] = {2 / (r - l), 0, 0, 0,  0, 2 / (t - b),       0,
                                0,           0, 0, -1, 0, (r + l) / (l - r), (t + b) / (b - t),
                                0,           1};
  gl.UniformMatrix4fv(gl.GetUniformLocation(program_, "u_projection"), 1, GL_FALSE, projection);
  gl.Uniform1i(gl.GetUniformLocation(program_, "u_texture"), 0);
  gl.ActiveTexture(GL_TEXTURE0);
  gl.BindVertexArray(vao_);
  const float scale_x = framebuffer_width / data->DisplaySize.x;
  const float scale_y = framebuffer_height / data->DisplaySize.y;
  for (int n = 0; n < data->CmdListsCount; ++n) {
    const ImDrawList* list = data->CmdLists[n];
    gl.BindBuffer(GL_ARRAY_BUFFER, vbo_);
    gl.BufferData(GL_ARRAY_BUFFER,
                  list->VtxBuffer.Size * static_cast<GLsizeiptr>(sizeof(ImDrawVert)),
                  list->VtxBuffer.Data, GL_STREAM_DRAW);
    gl.BufferData(GL_ELEMENT_ARRAY_BUFFER,
                  list->IdxBuffer.Size * static_cast<GLsizeiptr>(sizeof(ImDrawIdx)),
                  list->IdxBuffer.Data, GL_STREAM_DRAW);
    for (const ImDrawCmd& cmd : list->CmdBuffer) {
      if (cmd.UserCallback != nullptr) {
        cmd.UserCallback(list, &cmd);
        continue;
      }
      const float x0 = (cmd.ClipRect.x - l) * scale_x, y0 = (cmd.ClipRect.y - t) * scale_y;
      const float x1 = (cmd.ClipRect.z - l) * scale_x, y1 = (cmd.ClipRect.w - t) * scale_y;
      if (x1 <= x0 || y1 <= y0) continue;
      gl.Scissor(static_cast<GLint>(x0), static_cast<GLint>(framebuffer_height - y1),
                 static_cast<GLsizei>(x1 - x0), static_cast<GLsizei>(y1 - y0));
      gl.BindTexture(GL_TEXTURE_2D,
                     static_cast<GLuint>(reinterpret_cast<std::uintptr_t>(cmd.GetTexID())));
      gl.DrawElements(GL_TRIANGLES, static_cast<GLsizei>(cmd.ElemCount),
                      sizeof(ImDrawIdx) == 2 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT,
                      reinterpret_cast<void*>(cmd.IdxOffset * sizeof(ImDrawIdx)));
    }
  }
  gl.BindVertexArray(0);
  gl.Disable(GL_SCISSOR_TEST);
  gl.Disable(GL_BLEND);
}

}  // namespace pbm
