#version 330 core
// One triangle covering the screen at the far plane, drawn after the opaque geometry so only
// background pixels (depth still 1) run the fragment shader.
out float v_height;  // 0 at the bottom edge of the image, 1 at the top
void main() {
  const vec2 corners[3] = vec2[3](vec2(-1.0, -1.0), vec2(3.0, -1.0), vec2(-1.0, 3.0));
  vec2 p = corners[gl_VertexID];
  v_height = 0.5 * (p.y + 1.0);
  gl_Position = vec4(p, 1.0, 1.0);
}
