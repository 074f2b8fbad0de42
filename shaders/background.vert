#version 330 core
// One triangle covering the screen; v_height runs from 0 (bottom) to 1 (top).
out float v_height;
void main() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  v_height = corner.y * 0.5;
  gl_Position = vec4(corner * 2.0 - 1.0, 1.0, 1.0);
}
