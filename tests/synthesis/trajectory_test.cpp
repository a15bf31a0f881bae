#include "engine/synthesis/trajectory.h"

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <random>

#include "engine/synthesis/synthesizer.h"
#include "test_rig.h"

namespace prep {

TEST_CASE("Eq. 3-4 scale the per-frame displacement, Eq. 5 the feet's height change") {
  const glm::vec2 next = advance_root({1.0f, 2.0f}, {0.1f, 0.5f, 0.2f}, 0.25f);
  CHECK(next.x == doctest::Approx(1.075f));
  CHECK(next.y == doctest::Approx(2.15f));
  CHECK(adjust_root_height(0.95f, 0.10f, 0.04f) == doctest::Approx(0.88f));
}

TEST_CASE("Eq. 3-5 through the synthesizer on a hand-made crouch") {
  const auto skeleton = test::make_test_skeleton();
  const BodyMap body = BodyMap::detect(*skeleton);
  const MassModel mass = MassModel::build(*skeleton, body);
  const int n = skeleton->size();
  Params params;
  params.ik.enabled = false;
  params.balance.enabled = false;
  const Synthesizer synth(skeleton, body, mass, params);
  SynthesisScratch scratch = synth.make_scratch();
  SynthesisState state;
  Pose out = synth.make_pose();

  // Locomotion: standing straight, heading 0.5 rad, walking forward 0.1 m a frame. T_p: both thighs
  // pitched forward by theta and both shins back by 2 theta (a crouch whose feet stay under the hips),
  // the pelvis pitched by 0.3 rad relative to its own heading of 2 rad.
  const float theta = 0.6f;
  const float heading = 0.5f;
  Pose loco(n), crouch(n);
  loco.rotations[0] = heading_rotation(heading);
  loco.root_position = {0.0f, 0.95f, 0.0f};
  crouch.rotations[0] = heading_rotation(2.0f) * glm::angleAxis(0.3f, glm::vec3(1, 0, 0));
  for (const char* thigh : {"lThigh", "rThigh"}) crouch.rotations[static_cast<size_t>(skeleton->find(thigh))] = glm::angleAxis(theta, glm::vec3(1, 0, 0));
  for (const char* shin : {"lShin", "rShin"}) crouch.rotations[static_cast<size_t>(skeleton->find(shin))] = glm::angleAxis(-2.0f * theta, glm::vec3(1, 0, 0));

  const float alpha = 0.5f;
  const float w = blend_weight(alpha, params.blend.C_lower, 1.0f);  // root and legs share the lower-body curve
  SynthesisInput in;
  in.locomotion = &loco;
  in.reference = &crouch;
  in.alpha = alpha;
  synth.step(in, state, scratch, out);
  // Eq. 5 by hand. The thigh turns by w*theta and the shin by -2w*theta, so the shin's world pitch is
  // -w*theta: the ankle sits 0.05 + 0.85 cos(w theta) below the hip joint in the pelvis frame. The pelvis
  // itself is pitched by w*0.3, which turns that vertical leg too.
  const float pitch = w * 0.3f;
  const float hip_drop = 0.05f, leg = 0.42f + 0.43f;
  const float rest = -(hip_drop + leg);
  // Ankle relative to the root in the pelvis frame: (x, -0.05 - 0.42 cos + 0.43 cos..., z), then pitched.
  const float wt = w * theta;
  const glm::vec3 ankle_local(0.09f, -hip_drop - 0.42f * std::cos(wt) - 0.43f * std::cos(wt),
                              -0.42f * std::sin(wt) + 0.43f * std::sin(wt));
  const glm::vec3 ankle_pitched = glm::angleAxis(pitch, glm::vec3(1, 0, 0)) * ankle_local;
  const float dy = ankle_pitched.y - rest;
  CHECK(out.root_position.y == doctest::Approx(0.95f - dy).epsilon(1e-5));  // both feet moved alike
  CHECK(out.root_position.x == doctest::Approx(0.0f));
  CHECK(out.root_position.z == doctest::Approx(0.0f));
  // Root orientation: the locomotion's heading, T_p's tilt scaled by w_r.
  CHECK(heading_of(out.rotations[0]) == doctest::Approx(heading).epsilon(1e-5));
  const glm::quat tilt = glm::inverse(heading_rotation(heading)) * out.rotations[0];
  CHECK(std::abs(glm::dot(tilt, glm::angleAxis(pitch, glm::vec3(1, 0, 0)))) == doctest::Approx(1.0f).epsilon(1e-6));

  // Next frame: the locomotion moved by (0.04, 0, 0.1); the synthesized root by (1 - w_r) of that.
  loco.root_position += glm::vec3(0.04f, 0.0f, 0.1f);
  synth.step(in, state, scratch, out);
  CHECK(out.root_position.x == doctest::Approx((1.0f - w) * 0.04f));
  CHECK(out.root_position.z == doctest::Approx((1.0f - w) * 0.1f));
  // An explicit displacement (e.g. after the player re-aligned the clip) wins over the stored root.
  loco.root_position = {5.0f, 0.95f, 5.0f};
  in.has_displacement = true;
  in.displacement = {0.0f, 0.0f, 0.1f};
  synth.step(in, state, scratch, out);
  CHECK(out.root_position.x == doctest::Approx((1.0f - w) * 0.04f));
  CHECK(out.root_position.z == doctest::Approx((1.0f - w) * 0.2f));
}

TEST_CASE("height of a joint relative to the root walks its chain") {
  const auto skeleton = test::make_test_skeleton();
  Pose pose(skeleton->size());
  CHECK(height_relative_to_root(*skeleton, pose, skeleton->find("lFoot")) == doctest::Approx(-0.90f));
  pose.rotations[0] = glm::angleAxis(3.14159265f, glm::vec3(0, 0, 1));  // upside down
  CHECK(height_relative_to_root(*skeleton, pose, skeleton->find("lFoot")) == doctest::Approx(0.90f));
}

TEST_CASE("the feet's height changes are the differences of their heights relative to the root, to the bit") {
  // foot_height_changes walks the blended and the locomotion chains together; each must stay the single
  // walk's arithmetic.
  const auto skeleton = test::make_test_skeleton();
  const BodyMap body = BodyMap::detect(*skeleton);
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const auto random_pose = [&] {
    Pose pose(skeleton->size());
    for (glm::quat& q : pose.rotations) q = glm::normalize(glm::quat(u(rng), u(rng), u(rng), u(rng)));
    return pose;
  };
  // The two legs' chains are walked side by side: also with chains of different lengths (the right one
  // ending at its knee), either way round.
  BodyMap right_shorter = body, left_shorter = body;
  right_shorter.legs[kRight].ankle = body.legs[kRight].knee;
  left_shorter.legs[kLeft].ankle = body.legs[kLeft].knee;
  for (int k = 0; k < 1000; ++k) {
    const Pose locomotion = random_pose(), blended = random_pose();
    for (const BodyMap* b : std::array<const BodyMap*, 3>{&body, &right_shorter, &left_shorter}) {
      float dy_left = 0.0f, dy_right = 0.0f;
      foot_height_changes(*skeleton, *b, locomotion, blended, dy_left, dy_right);
      const int left = b->legs[kLeft].ankle, right = b->legs[kRight].ankle;
      const float left_expected = height_relative_to_root(*skeleton, blended, left) - height_relative_to_root(*skeleton, locomotion, left);
      const float right_expected = height_relative_to_root(*skeleton, blended, right) - height_relative_to_root(*skeleton, locomotion, right);
      REQUIRE(std::memcmp(&dy_left, &left_expected, sizeof(float)) == 0);
      REQUIRE(std::memcmp(&dy_right, &right_expected, sizeof(float)) == 0);
    }
  }
}

}  // namespace prep

TEST_CASE("the root's heading rotation without trigonometry is heading_rotation(heading_of(root))") {
  using namespace prep;
  std::mt19937 rng(31);
  std::normal_distribution<float> n(0.0f, 1.0f);
  for (int k = 0; k < 2000; ++k) {
    glm::quat root = glm::normalize(glm::quat(n(rng), n(rng), n(rng), n(rng)));
    if (k == 0) root = glm::angleAxis(3.14159265f, glm::vec3(0.0f, 1.0f, 0.0f));  // facing -Z exactly
    const glm::quat expected = heading_rotation(heading_of(root));
    const glm::quat got = heading_rotation_of(root);
    CHECK(std::abs(std::abs(glm::dot(expected, got)) - 1.0f) < 1e-6f);  // the same rotation (q and -q alike)
    CHECK(got.x == 0.0f);
    CHECK(got.z == 0.0f);
  }
}
