#version 330 core
// Key light with a shadow map, a cool fill light and sky ambient, Blinn-Phong with the
// material's roughness setting the highlight, Reinhard tone mapping and display gamma. Planes
// use ground.frag, the same lighting with the normal's terms precomputed.
in vec3 v_position;
in vec3 v_normal;
in vec4 v_light_clip;
uniform vec3 u_camera;
uniform vec3 u_base_color;
uniform float u_roughness;
uniform float u_opacity;  // 1: opaque; below, blended over what is behind
uniform vec3 u_key_direction;   // towards the key light
uniform vec3 u_fill_direction;  // towards the fill light
uniform sampler2DShadow u_shadow_map;
uniform int u_shadows;
out vec4 frag_color;

float key_visibility(vec3 n) {
  if (u_shadows == 0) return 1.0;
  vec3 p = v_light_clip.xyz / v_light_clip.w * 0.5 + 0.5;
  if (p.x <= 0.0 || p.x >= 1.0 || p.y <= 0.0 || p.y >= 1.0 || p.z >= 1.0) return 1.0;
  float bias = 0.002 + 0.006 * (1.0 - abs(dot(n, u_key_direction)));
  vec2 texel = 1.0 / vec2(textureSize(u_shadow_map, 0));
  // Four comparisons, each filtered over 2x2 texels by the sampler: a soft 3x3 edge.
  float lit = 0.0;
  lit += texture(u_shadow_map, vec3(p.xy + vec2(-0.5, -0.5) * texel, p.z - bias));
  lit += texture(u_shadow_map, vec3(p.xy + vec2(0.5, -0.5) * texel, p.z - bias));
  lit += texture(u_shadow_map, vec3(p.xy + vec2(-0.5, 0.5) * texel, p.z - bias));
  lit += texture(u_shadow_map, vec3(p.xy + vec2(0.5, 0.5) * texel, p.z - bias));
  return 0.25 * lit;
}

void main() {
  vec3 n = normalize(v_normal);
  vec3 to_camera = normalize(u_camera - v_position);
  if (dot(n, to_camera) < 0.0) n = -n;
  vec3 albedo = u_base_color;
  float shininess = mix(256.0, 4.0, clamp(u_roughness, 0.0, 1.0));
  float specular_strength = mix(0.6, 0.05, clamp(u_roughness, 0.0, 1.0));
  float key = max(dot(n, u_key_direction), 0.0) * key_visibility(n);
  float highlight = 0.0;
  if (specular_strength > 0.06 && key > 0.0) {  // matte surfaces (the ground) skip it
    vec3 half_key = normalize(u_key_direction + to_camera);
    highlight = pow(max(dot(n, half_key), 0.0), shininess);
  }
  float fill = max(dot(n, u_fill_direction), 0.0);
  float sky = 0.5 + 0.5 * n.z;
  vec3 color = albedo * (vec3(1.0, 0.96, 0.9) * 2.2 * key + vec3(0.55, 0.65, 0.8) * 0.45 * fill +
                         mix(vec3(0.10, 0.09, 0.08), vec3(0.22, 0.25, 0.30), sky)) +
               vec3(1.0, 0.96, 0.9) * specular_strength * highlight * 2.0;
  color = color / (1.0 + color);  // Reinhard
  // Display gamma 2 (sqrt): within a few percent of sRGB's, and a software rasterizer pays for
  // three pow() per pixel.
  frag_color = vec4(sqrt(color), u_opacity);
}
