// Mouse picking geometry: the ray under a pixel, the floor point, boxes, and which object a ray hits.
#include "app/demo/picking.h"

#include <doctest/doctest.h>

#include "app/render/camera.h"
#include "app/demo/world_session.h"
#include "tests/support/paths.h"

using namespace prep;
using namespace prep::demo;

TEST_CASE("the ray under a pixel meets the floor at the point that projects to that pixel") {
  render::Camera camera;
  camera.target = {1.0f, 0.9f, 3.0f};
  camera.yaw = 2.4f;
  camera.pitch = 0.4f;
  camera.distance = 7.0f;
  const glm::mat4 vp = camera.view_projection(1280.0f / 720.0f);
  for (const glm::vec3 point : {glm::vec3(1.0f, 0.0f, 3.0f), glm::vec3(-2.0f, 0.0f, 8.5f), glm::vec3(3.5f, 0.0f, 1.0f)}) {
    glm::vec2 pixel;
    REQUIRE(render::project_to_pixel(vp, point, 1280, 720, pixel));
    const Ray ray = pixel_ray(vp, pixel, 1280, 720);
    CHECK(glm::length(ray.direction) == doctest::Approx(1.0f));
    CHECK(glm::length(ray.origin - camera.eye()) < 0.1f);  // from the near plane, at the eye
    const auto hit = ray_floor(ray);
    REQUIRE(hit);
    CHECK(hit->x == doctest::Approx(point.x).epsilon(1e-3));
    CHECK(hit->y == doctest::Approx(point.z).epsilon(1e-3));
  }
  // Above the horizon the ray never meets the floor.
  glm::vec2 sky;
  const glm::vec3 look = camera.target - camera.eye();
  REQUIRE(render::project_to_pixel(vp, camera.eye() + glm::vec3(look.x, 0.1f * glm::length(look), look.z), 1280, 720, sky));
  CHECK_FALSE(ray_floor(pixel_ray(vp, sky, 1280, 720)));
}

TEST_CASE("ray and box: the entry distance, or a miss") {
  const Ray ray{{0.0f, 1.0f, -5.0f}, {0.0f, 0.0f, 1.0f}};
  const auto t = ray_box(ray, {-1.0f, 0.0f, -0.5f}, {1.0f, 2.0f, 0.5f});
  REQUIRE(t);
  CHECK(*t == doctest::Approx(4.5f));
  CHECK_FALSE(ray_box(ray, {-1.0f, 1.5f, -0.5f}, {1.0f, 2.0f, 0.5f}));  // passes under it
  CHECK_FALSE(ray_box({{0.0f, 1.0f, 5.0f}, {0.0f, 0.0f, 1.0f}}, {-1.0f, 0.0f, -0.5f}, {1.0f, 2.0f, 0.5f}));  // behind
}

TEST_CASE("pick_object: the first object along the ray, turned obstacles, balls, opponents, not used ones") {
  SessionOptions o;
  o.cache_dir = test::tmp_dir() + "/policy-cache";
  o.background = false;
  WorldSession obstacles(o);
  obstacles.open(test::repo() + "/assets/scenarios/obstacles.json");
  const World& w = *obstacles.world();
  // Looking along +Z at bar height from the start: the bar (index 0) is hit before the beam behind it.
  CHECK(pick_object(w, {{0.0f, 0.75f, 0.0f}, {0.0f, 0.0f, 1.0f}}) == 0);
  // At the beam's height over the bar's top: the beam (index 1).
  CHECK(pick_object(w, {{0.5f, 1.3f, 0.0f}, {0.0f, 0.0f, 1.0f}}) == 1);
  // Straight down onto the hurdle's board; and beside the course, nothing.
  const glm::vec3 hurdle = w.objects()[2].position;
  CHECK(pick_object(w, {{hurdle.x + 1.0f, 3.0f, hurdle.z}, {0.0f, -1.0f, 0.0f}}) == 2);
  CHECK_FALSE(pick_object(w, {{4.0f, 0.5f, 0.0f}, {0.0f, 0.0f, 1.0f}}));

  WorldSession kick(o);
  kick.open(test::repo() + "/assets/scenarios/kick.json");
  const glm::vec3 ball = kick.world()->objects()[0].position;
  CHECK(pick_object(*kick.world(), {{ball.x, 2.0f, ball.z}, {0.0f, -1.0f, 0.0f}}) == 0);
  CHECK_FALSE(pick_object(*kick.world(), {{ball.x + 0.5f, 2.0f, ball.z}, {0.0f, -1.0f, 0.0f}}));

  WorldSession fight(o);
  fight.open(test::repo() + "/assets/scenarios/fight.json");
  const World& f = *fight.world();
  const glm::vec2 opponent = f.characters()[static_cast<size_t>(f.objects()[1].character)].position;
  // A ray at chest height toward the second opponent, from its side (the first one is not in the way).
  CHECK(pick_object(f, {{opponent.x + 3.0f, 1.2f, opponent.y}, {-1.0f, 0.0f, 0.0f}}) == 1);
}
