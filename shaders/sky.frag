#version 330 core
in float v_height;
uniform vec3 u_bottom;
uniform vec3 u_top;
out vec4 frag_color;
void main() {
  // Half way to the top colour at the top edge: a pale horizon under a soft blue.
  frag_color = vec4(mix(u_bottom, u_top, 0.5 * v_height), 1.0);
}
