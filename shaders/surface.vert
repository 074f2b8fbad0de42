#version 330 core
// Solids of every kind (ui/drawable_geometry.h): a mesh vertex in its own frame, or a unit
// primitive's, placed by x = R (scale * p + stretch * s e_z) + offset.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in float a_stretch;  // primitives only; 0 where the array is disabled
uniform mat4 u_view_proj;
uniform mat4 u_light_view_proj;
uniform mat3 u_rotation;
uniform vec3 u_offset;
uniform vec3 u_scale;
uniform float u_stretch;
out vec3 v_position;
out vec3 v_normal;
out vec4 v_light_clip;
void main() {
  vec3 world = u_rotation * (u_scale * a_position + vec3(0.0, 0.0, u_stretch * a_stretch)) + u_offset;
  v_position = world;
  v_normal = u_rotation * (a_normal / u_scale);
  v_light_clip = u_light_view_proj * vec4(world, 1.0);
  gl_Position = u_view_proj * vec4(world, 1.0);
}
