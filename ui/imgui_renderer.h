// Draws Dear ImGui's draw lists through our loaded GL function table. Debian's prebuilt OpenGL3
// backend loads libGL by itself, which fails under OSMesa and bypasses our table (PLATFORM.md);
// this is the small part of it we need: one font texture, one program, one streamed buffer.
#pragma once

#include <imgui.h>

#include "gl_functions.h"

namespace pbm {

class ImGuiRenderer {
 public:
  // Builds the current ImGui context's font atlas into a texture. The GL context must be current.
  explicit ImGuiRenderer(const gl::Functions& gl);
  ~ImGuiRenderer();
  ImGuiRenderer(const ImGuiRenderer&) = delete;
  ImGuiRenderer& operator=(const ImGuiRenderer&) = delete;

  // Draws `data` (ImGui::GetDrawData() after ImGui::Render()) over the bound framebuffer of
  // framebuffer_width x framebuffer_height pixels. Leaves blending and scissor disabled.
  void draw(const ImDrawData* data, int framebuffer_width, int framebuffer_height);

 private:
  const gl::Functions& gl_;
  GLuint program_ = 0, font_ = 0, vao_ = 0, vbo_ = 0, ibo_ = 0;
};

}  // namespace pbm
