#version 330 core
// Planes: flat, so their lighting is one value per plane (u_lit, u_shade) computed on the CPU;
// the fragment shader only draws the grid and looks up the shadow.
layout(location = 0) in vec3 a_position;
uniform mat4 u_view_proj;
uniform mat4 u_light_view_proj;
uniform vec3 u_grid_origin;
uniform vec3 u_grid_u;
uniform vec3 u_grid_v;
out vec2 v_grid;
out vec3 v_light;
void main() {
  vec3 d = a_position - u_grid_origin;
  v_grid = vec2(dot(d, u_grid_u), dot(d, u_grid_v));
  vec4 light_clip = u_light_view_proj * vec4(a_position, 1.0);
  v_light = light_clip.xyz / light_clip.w * 0.5 + 0.5;
  gl_Position = u_view_proj * vec4(a_position, 1.0);
}
