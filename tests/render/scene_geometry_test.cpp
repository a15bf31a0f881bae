// The renderer draws the engine's geometry: a character's capsules are its BodyVolumes placed at its pose,
// an obstacle's boxes and a ball's sphere are its object_solids in the frame the clearance measure uses
// (to_object_frame). Without a GL context: the primitives are checked as built.
#include <doctest/doctest.h>

#include <cmath>

#include "app/render/palette.h"
#include "app/render/renderer.h"
#include "engine/library/builtin.h"
#include "engine/world/object_solids.h"
#include "tests/render/test_scene.h"

using namespace prep;

namespace {

// A skeleton's rest pose standing on the floor, turned by `heading` and moved to `at`.
render::SceneCharacter standing(const std::shared_ptr<const Skeleton>& skeleton, glm::vec3 at, float heading) {
  Pose pose(skeleton->size());
  pose.root_position = at + glm::vec3(0.0f, skeleton->joints[0].offset.y, 0.0f);
  pose.rotations[0] = glm::angleAxis(heading, glm::vec3(0.0f, 1.0f, 0.0f));
  return render::make_scene_character(skeleton, pose, render::palette::kCharacter);
}

void check_capsules_are_the_volumes(const std::shared_ptr<const Skeleton>& skeleton) {
  const render::SceneCharacter c = standing(skeleton, {0.4f, 0.0f, -1.2f}, 0.7f);
  const BodyVolumes volumes(*skeleton);
  std::vector<PlacedCapsule> placed;
  volumes.place(c.joint_positions, c.joint_rotations, placed);

  std::vector<render::CapsuleInstance> drawn;
  render::append_character_capsules(c, volumes, drawn);
  REQUIRE(drawn.size() == volumes.capsules().size());
  for (size_t k = 0; k < drawn.size(); ++k) {
    CAPTURE(volumes.capsules()[k].name);
    CHECK(drawn[k].a_radius.w == volumes.capsules()[k].radius);
    CHECK(glm::length(glm::vec3(drawn[k].a_radius) - placed[k].a) < 1e-6f);
    CHECK(glm::length(glm::vec3(drawn[k].b_glow) - placed[k].b) < 1e-6f);
    CHECK(drawn[k].colour == render::palette::kCharacter);
  }
  // The renderer's own path (a scene drawn as capsules) gives the same capsules, and no flagged ones.
  render::Scene scene;
  scene.characters = {c};
  const render::ScenePrimitives prims = render::build_primitives(scene);
  REQUIRE(prims.capsules.size() == volumes.capsules().size());
  for (size_t k = 0; k < prims.capsules.size(); ++k) CHECK(prims.capsules[k].a_radius.w == volumes.capsules()[k].radius);
  CHECK(prims.flagged.empty());
}

}  // namespace

TEST_CASE("the renderer's capsules are the body volumes': the built-in skeleton and a hand-made one") {
  SUBCASE("built-in") { check_capsules_are_the_volumes(builtin_skeleton()); }
  SUBCASE("hand-made") { check_capsules_are_the_volumes(test::stick_skeleton()); }
}

TEST_CASE("flagged capsules: the volumes' capsules by index, a margin thicker, in the clearance colour") {
  const auto skeleton = builtin_skeleton();
  render::SceneCharacter c = standing(skeleton, {0.0f, 0.0f, 0.0f}, 0.0f);
  const BodyVolumes volumes(*skeleton);
  const int last = static_cast<int>(volumes.capsules().size()) - 1;
  c.flagged = {0, last, last + 1, -1};  // the last two are no capsules of this body: ignored
  std::vector<PlacedCapsule> placed;
  volumes.place(c.joint_positions, c.joint_rotations, placed);
  std::vector<render::CapsuleInstance> out;
  render::append_flagged_capsules(c, volumes, out);
  REQUIRE(out.size() == 2);
  for (size_t i = 0; i < out.size(); ++i) {
    const PlacedCapsule& p = placed[static_cast<size_t>(c.flagged[i])];
    CHECK(out[i].a_radius.w == doctest::Approx(p.radius + render::kFlaggedMargin));
    CHECK(glm::length(glm::vec3(out[i].a_radius) - p.a) < 1e-6f);
    CHECK(glm::length(glm::vec3(out[i].b_glow) - p.b) < 1e-6f);
    CHECK(out[i].colour == render::palette::kClearance);
  }
  // A skinned character (no capsules of its own) keeps its flagged ones; they stay out of the shadow casters.
  render::Scene scene;
  scene.characters = {c};
  const render::ScenePrimitives prims = render::build_primitives(scene, {true});
  CHECK(prims.capsules.empty());
  CHECK(prims.flagged.size() == 2);
}

TEST_CASE("body volumes are made once per skeleton") {
  render::BodyVolumesCache cache;
  const auto a = builtin_skeleton();
  const auto b = test::stick_skeleton();
  const BodyVolumes& va = cache.get(a);
  CHECK(&cache.get(b) != &va);
  CHECK(cache.get(b).capsules().size() == BodyVolumes(*b).capsules().size());
  CHECK(&cache.get(a) == &va);  // the same one again, not rebuilt
}

TEST_CASE("obstacle boxes and the ball are the object solids, placed in the clearance measure's object frame") {
  const glm::vec3 at(1.5f, 0.0f, -2.0f);
  const float heading = 0.6f;
  struct Case {
    render::ObjectType render;
    prep::ObjectType engine;
    glm::vec3 size;
  };
  for (const Case& k : {Case{render::ObjectType::Bar, prep::ObjectType::Bar, {3.0f, 0.7f, 0.1f}},
                        Case{render::ObjectType::Beam, prep::ObjectType::Beam, {2.0f, 1.2f, 0.0f}},  // default rail depth
                        Case{render::ObjectType::Hurdle, prep::ObjectType::Hurdle, {1.5f, 0.45f, 0.05f}},
                        Case{render::ObjectType::Ball, prep::ObjectType::Ball, {0.22f, 0.22f, 0.22f}}}) {
    CAPTURE(render::object_type_name(k.render));
    render::SceneObject o;
    o.type = k.render;
    o.position = at;
    o.heading = heading;
    o.size = k.size;
    render::ScenePrimitives prims;
    render::append_object_primitives(o, prims);
    const std::vector<ObjectSolid> solids = object_solids(k.engine, k.size);
    size_t box = 0;
    for (const ObjectSolid& s : solids) {
      CAPTURE(solid_part_name(s.part));
      if (s.sphere) {
        REQUIRE(prims.capsules.size() == 1);
        const render::CapsuleInstance& ball = prims.capsules[0];
        CHECK(ball.a_radius.w == doctest::Approx(0.5f * s.extents.x));
        const glm::vec3 local = to_object_frame(glm::vec3(ball.a_radius), {at.x, at.z}, heading);
        CHECK(glm::length(local - s.centre) < 1e-5f);
        CHECK(ball.colour == render::palette::kBall);
        continue;
      }
      REQUIRE(box < prims.boxes.size());
      const glm::mat4& m = prims.boxes[box++].model;
      // The box's centre, brought back into the object's frame the way the clearance measure does, is the
      // solid's centre; its edges are the solid's extents.
      const glm::vec3 centre(m * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
      CHECK(glm::length(to_object_frame(centre, {at.x, at.z}, heading) - s.centre) < 1e-5f);
      for (int axis = 0; axis < 3; ++axis) CHECK(glm::length(glm::vec3(m[axis])) == doctest::Approx(s.extents[axis]));
    }
    CHECK(box == prims.boxes.size());
  }
  // A Box (the renderer's own type) is its size, standing on the floor.
  render::SceneObject plain;
  plain.type = render::ObjectType::Box;
  plain.size = {0.5f, 0.8f, 0.3f};
  render::ScenePrimitives prims;
  render::append_object_primitives(plain, prims);
  REQUIRE(prims.boxes.size() == 1);
  CHECK((prims.boxes[0].model * glm::vec4(0.0f, -0.5f, 0.0f, 1.0f)).y == doctest::Approx(0.0f));
  CHECK(glm::length(glm::vec3(prims.boxes[0].model[1])) == doctest::Approx(0.8f));
}
