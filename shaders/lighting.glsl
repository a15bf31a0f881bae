// Shared by the lit shaders (inserted where a shader says #include "lighting.glsl").
// One white directional light with a shadow map, a neutral hemisphere ambient, a faint specular and
// distance fog toward the sky colour. White light keeps every albedo's hue, which the screenshot tests
// rely on (app/render/palette.h).
uniform vec3 u_light_dir;          // unit vector toward the light
uniform mat4 u_light_view_proj;    // world -> light clip space (the shadow map's camera)
uniform sampler2DShadow u_shadow_map;
uniform float u_shadow_texel;      // 1 / shadow map size; 0 disables shadows
uniform vec3 u_eye;                // camera position (specular, rim, fog)
uniform vec3 u_sky;                // fog colour
uniform vec2 u_fog_range;          // fog starts at x metres and is full at y metres

float shadow_visibility(vec3 world, vec3 normal) {
  if (u_shadow_texel <= 0.0) return 1.0;
  // Normal offset (2 cm) and a small depth bias keep surfaces from shadowing themselves.
  vec4 l = u_light_view_proj * vec4(world + normal * 0.02, 1.0);
  vec3 c = l.xyz / l.w * 0.5 + 0.5;
  if (c.x <= 0.0 || c.x >= 1.0 || c.y <= 0.0 || c.y >= 1.0 || c.z >= 1.0) return 1.0;
  float depth = c.z - 0.0015;
  return texture(u_shadow_map, vec3(c.xy, depth));  // one bilinear comparison: a 2x2 PCF in hardware
}

vec3 shade(vec3 albedo, vec3 world, vec3 normal) {
  vec3 n = normalize(normal);
  float diffuse = max(dot(n, u_light_dir), 0.0);
  float visible = shadow_visibility(world, n);
  float sky_facing = 0.5 + 0.5 * n.y;
  vec3 ambient = albedo * mix(0.30, 0.45, sky_facing);
  vec3 v = normalize(u_eye - world);
  vec3 h = normalize(v + u_light_dir);
  float specular = pow(max(dot(n, h), 0.0), 40.0) * 0.10 * visible;
  return ambient + albedo * diffuse * 0.70 * visible + vec3(specular);
}

vec3 apply_fog(vec3 colour, vec3 world) {
  float d = length(world - u_eye);
  float f = clamp((d - u_fog_range.x) / (u_fog_range.y - u_fog_range.x), 0.0, 1.0);
  return mix(colour, u_sky, f);
}
