// Shadows on the floor: the rectangles where shadows can fall hold every caster's footprint and shadow,
// and the floor drawn in two parts (shadowed rectangles, the rest without the lookup) shows the shadow of
// a box where the light puts it, with no seam at the rectangle's edge.
#include <doctest/doctest.h>

#include <cmath>

#include "app/render/gl_context.h"
#include "app/render/renderer.h"
#include "tests/render/pixels.h"
#include "tests/support/paths.h"

using namespace prep;
using namespace prep::render;

namespace {
bool contains(const std::vector<glm::vec4>& rects, glm::vec2 p) {
  for (const glm::vec4& r : rects)
    if (p.x >= r.x && p.y >= r.y && p.x <= r.z && p.y <= r.w) return true;
  return false;
}
int brightness(const Image& image, glm::vec2 p) {
  const std::uint8_t* c = image.pixel(static_cast<int>(p.x), static_cast<int>(p.y));
  return c[0] + c[1] + c[2];
}
}  // namespace

TEST_CASE("shadow receiver rectangles hold each caster's footprint and shadow, merged to the limit") {
  const glm::vec3 light = glm::normalize(glm::vec3(0.45f, 1.0f, 0.35f));
  Scene scene;
  ScenePrimitives prims;
  // A 2 m pole at (3, 0, -2): its top's shadow falls 2 m / light.y along -light's floor direction.
  prims.capsules.push_back({glm::vec4(3.0f, 0.0f, -2.0f, 0.05f), glm::vec4(3.0f, 2.0f, -2.0f, 0.0f), glm::vec3(1.0f)});
  const std::vector<glm::vec4> one = shadow_receiver_rects(scene, prims, light, kMaxShadowRects);
  REQUIRE(one.size() == 1);
  const glm::vec3 top_shadow = glm::vec3(3.0f, 2.0f, -2.0f) - light * (2.0f / light.y);
  CHECK(contains(one, {3.0f, -2.0f}));
  CHECK(contains(one, {top_shadow.x, top_shadow.z}));
  CHECK_FALSE(contains(one, {3.0f + 1.0f, -2.0f + 1.0f}));  // the light's side of the pole stays out
  // Twenty casters in two far groups: merged to the limit, and the two groups stay apart.
  for (int k = 0; k < 10; ++k) {
    prims.capsules.push_back({glm::vec4(-20.0f + 0.3f * k, 0.0f, 0.0f, 0.05f), glm::vec4(-20.0f + 0.3f * k, 1.0f, 0.0f, 0.0f), glm::vec3(1.0f)});
    prims.capsules.push_back({glm::vec4(20.0f + 0.3f * k, 0.0f, 5.0f, 0.05f), glm::vec4(20.0f + 0.3f * k, 1.0f, 5.0f, 0.0f), glm::vec3(1.0f)});
  }
  const std::vector<glm::vec4> many = shadow_receiver_rects(scene, prims, light, kMaxShadowRects);
  CHECK(many.size() == static_cast<size_t>(kMaxShadowRects));
  CHECK(contains(many, {-20.0f, 0.0f}));
  CHECK(contains(many, {22.7f, 5.0f}));
  CHECK_FALSE(contains(many, {0.0f, 2.5f}));  // nothing between the groups
}

TEST_CASE("a box's shadow darkens the floor where the light puts it, and only there") {
  OsMesaContext context(640, 480);
  Renderer renderer;
  Scene scene;
  SceneObject box;
  box.type = render::ObjectType::Box;
  box.size = {0.6f, 1.0f, 0.6f};
  scene.objects = {box};
  scene.focus = {0.0f, 0.5f, 0.0f};
  Camera camera;
  camera.target = {-0.6f, 0.0f, -0.4f};
  camera.yaw = 3.6f;
  camera.pitch = 0.9f;
  camera.distance = 4.0f;
  renderer.draw(scene, camera, 0, 0, 640, 480);
  const Image image = context.read_pixels();
  write_png(image, test::tmp_dir() + "/render_box_shadow.png");  // for a look by eye
  const glm::mat4 vp = camera.view_projection(640.0f / 480.0f);
  const glm::vec3 l = glm::normalize(renderer.settings().light_dir);
  // The box's top centre cast onto the floor: in shadow. Beside the box, toward the camera: lit.
  const glm::vec3 shadow = glm::vec3(0.0f, 1.0f, 0.0f) - l * (1.0f / l.y);
  const glm::vec3 lit(0.8f, 0.0f, -0.8f);
  const glm::vec2 shadow_px = test::pixel_of(image, vp, shadow), lit_px = test::pixel_of(image, vp, lit);
  CHECK(test::class_at(image, shadow_px) == palette::PixelClass::Ground);
  CHECK(test::class_at(image, lit_px) == palette::PixelClass::Ground);
  CHECK(brightness(image, shadow_px) < 0.75 * brightness(image, lit_px));
  // Across the edge of the shadowed rectangle, in the light, the floor is as bright on both sides.
  const glm::vec4 r = shadow_receiver_rects(scene, build_primitives(scene), l, kMaxShadowRects).at(0);
  const glm::vec2 inside = test::pixel_of(image, vp, {r.x + 0.08f, 0.0f, r.w - 0.08f});
  const glm::vec2 outside = test::pixel_of(image, vp, {r.x - 0.08f, 0.0f, r.w - 0.08f});
  CHECK(std::abs(brightness(image, inside) - brightness(image, outside)) < 12);
}
