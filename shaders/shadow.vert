#version 330 core
// Where a solid's vertex lands in clip space, placed as surface.vert places it: the key light's
// view in the shadow pass, the camera's in the bare pass.
layout(location = 0) in vec3 a_position;
layout(location = 2) in float a_stretch;
uniform mat4 u_view_proj;
uniform mat3 u_rotation;
uniform vec3 u_offset;
uniform vec3 u_scale;
uniform float u_stretch;
void main() {
  vec3 world = u_rotation * (u_scale * a_position + vec3(0.0, 0.0, u_stretch * a_stretch)) + u_offset;
  gl_Position = u_view_proj * vec4(world, 1.0);
}
