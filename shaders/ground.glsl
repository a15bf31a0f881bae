// The floor's fragment shader, shared by ground.frag (FLOOR_SHADOWS 1) and ground_unshadowed.frag (0):
// neutral grey with a 1 m grid (darker, wider lines every 5 m), antialiased by the screen-space
// derivative of the position and faded out with distance before it can alias, lit and shadowed.
// It covers most of the screen, so its lighting is the cheap special case of shade() for a normal of +Y
// with no specular. The shadow map lookup is most of its cost on llvmpipe (which runs both sides of a
// branch), so the renderer draws the floor in two parts: with the lookup only where some caster's shadow
// can fall (rectangles from shadow_receiver_rects, drawn first), and without it everywhere else.
#include "lighting.glsl"

in vec3 v_world;
uniform vec3 u_ground;
uniform vec3 u_grid_line;
out vec4 frag_colour;

void main() {
  vec2 p = v_world.xz;
  vec2 w = max(fwidth(p), vec2(1e-5));
  // Distance to the nearest 1 m and 5 m lines, in pixels.
  vec2 d1 = abs(fract(p - 0.5) - 0.5) / w;
  vec2 d5 = abs(fract(p * 0.2 - 0.5) - 0.5) * 5.0 / w;
  float minor = 1.0 - clamp(min(d1.x, d1.y), 0.0, 1.0);      // 1 pixel wide
  float major = 1.0 - clamp(min(d5.x, d5.y) - 0.5, 0.0, 1.0); // 2 pixels wide
  float fade = 1.0 - clamp(max(w.x, w.y) * 4.0, 0.0, 1.0);     // lines vanish where a pixel spans >= 25 cm
  vec3 albedo = mix(u_ground, u_grid_line, max(minor * 0.7, major) * fade);
#if FLOOR_SHADOWS
  float visible = shadow_visibility(v_world, vec3(0.0, 1.0, 0.0));
#else
  float visible = 1.0;
#endif
  // shade() with n = +Y: ambient at full sky factor, diffuse = light_dir.y.
  vec3 colour = albedo * (0.45 + max(u_light_dir.y, 0.0) * 0.70 * visible);
  frag_colour = vec4(apply_fog(colour, v_world), 1.0);
}
