#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_view_proj;
uniform mat4 u_light_view_proj;
out vec3 v_position;
out vec3 v_normal;
out vec4 v_light_clip;
void main() {
  v_position = a_position;
  v_normal = a_normal;
  v_light_clip = u_light_view_proj * vec4(a_position, 1.0);
  gl_Position = u_view_proj * vec4(a_position, 1.0);
}
