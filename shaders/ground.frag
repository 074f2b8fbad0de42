#version 330 core
// Gridded plane: colour = albedo * (shade + lit * key visibility), tone mapped like surface.frag.
in vec2 v_grid;
in vec3 v_light;
uniform vec3 u_base_color;
uniform vec3 u_lit;    // key light's contribution where unshadowed
uniform vec3 u_shade;  // fill and sky
uniform sampler2DShadow u_shadow_map;
uniform int u_shadows;
uniform float u_bias;
out vec4 frag_color;
void main() {
  vec2 w = fwidth(v_grid);
  vec2 line = abs(fract(v_grid - 0.5) - 0.5) / max(w, vec2(1e-6));
  float on_line = 1.0 - clamp(min(line.x, line.y), 0.0, 1.0);
  vec3 albedo = mix(u_base_color, u_base_color * 0.55, on_line);
  float visible = 1.0;
  if (u_shadows == 1 && all(greaterThan(v_light, vec3(0.0))) && all(lessThan(v_light, vec3(1.0)))) {
    vec2 texel = 1.0 / vec2(textureSize(u_shadow_map, 0));
    visible = 0.25 * (texture(u_shadow_map, vec3(v_light.xy + vec2(-0.5, -0.5) * texel, v_light.z - u_bias)) +
                      texture(u_shadow_map, vec3(v_light.xy + vec2(0.5, -0.5) * texel, v_light.z - u_bias)) +
                      texture(u_shadow_map, vec3(v_light.xy + vec2(-0.5, 0.5) * texel, v_light.z - u_bias)) +
                      texture(u_shadow_map, vec3(v_light.xy + vec2(0.5, 0.5) * texel, v_light.z - u_bias)));
  }
  vec3 color = albedo * (u_shade + u_lit * visible);
  color = color / (1.0 + color);
  frag_color = vec4(sqrt(color), 1.0);
}
