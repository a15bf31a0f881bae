#include "engine/synthesis/blending.h"

#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

#include "engine/synthesis/synthesizer.h"
#include "test_rig.h"

namespace prep {
namespace {

glm::quat rotation(float angle, glm::vec3 axis) { return glm::angleAxis(angle, glm::normalize(axis)); }

// Two clearly different poses on the test rig: a walking-like one and a guard-like one.
void make_poses(int n, Pose& walk, Pose& guard) {
  walk = Pose(n);
  guard = Pose(n);
  for (int i = 0; i < n; ++i) {
    const float k = static_cast<float>(i + 1);
    walk.rotations[static_cast<size_t>(i)] = rotation(0.05f * k, {1.0f, 0.3f * k, 0.2f});
    guard.rotations[static_cast<size_t>(i)] = rotation(-0.04f * k + 0.3f, {0.2f, 1.0f, 0.5f * k});
  }
  walk.root_position = {0.3f, 0.93f, 1.2f};
  guard.root_position = {-2.0f, 0.80f, 5.0f};
}

}  // namespace

TEST_CASE("Eq. 1 at tabulated points") {
  CHECK(blend_weight(0.5f, 0.5f, 1.0f) == doctest::Approx(0.5412).epsilon(1e-4));
  CHECK(blend_weight(0.5f, 1.0f, 1.0f) == doctest::Approx(0.7071).epsilon(1e-4));
  CHECK(blend_weight(0.0f, 0.5f, 1.0f) == 0.0f);
  CHECK(blend_weight(1.0f, 0.5f, 1.0f) == 1.0f);
  CHECK(blend_weight(1.0f, 1.0f, 0.8f) == doctest::Approx(0.8f));  // c_i scales the curve
}

TEST_CASE("w_i rises monotonically with alpha for every curve shape") {
  for (float C : {0.25f, 0.5f, 1.0f, 2.0f, 4.0f}) {
    float last = blend_weight(0.0f, C, 1.0f);
    for (int k = 1; k <= 190; ++k) {  // up to alpha = 0.95: beyond it float rounds the steepest curves to 1
      const float w = blend_weight(static_cast<float>(k) / 200.0f, C, 1.0f);
      CHECK(w > last);
      last = w;
    }
  }
}

TEST_CASE("defaults: at alpha = 0.2 every upper-body weight exceeds every leg weight") {
  const auto skeleton = test::make_test_skeleton();
  const BodyMap body = BodyMap::detect(*skeleton);
  const BlendCurves curves = make_blend_curves(*skeleton, body, BlendParams{});
  std::vector<float> w(static_cast<size_t>(skeleton->size()));
  blend_weights(curves, 0.2f, w.data());
  float min_upper = 2.0f, max_lower = -1.0f;
  int uppers = 0, lowers = 0;
  for (int j = 0; j < skeleton->size(); ++j) {
    if (body.upper_body[static_cast<size_t>(j)]) min_upper = std::min(min_upper, w[static_cast<size_t>(j)]), ++uppers;
    if (body.lower_body[static_cast<size_t>(j)]) max_lower = std::max(max_lower, w[static_cast<size_t>(j)]), ++lowers;
  }
  REQUIRE(uppers >= 10);
  REQUIRE(lowers >= 7);
  CHECK(min_upper > max_lower);
  CHECK(w[static_cast<size_t>(body.root)] == doctest::Approx(blend_weight(0.2f, 0.5f, 1.0f)));
  // The same holds at every alpha in (0, 1).
  for (int k = 1; k < 20; ++k) {
    const float a = static_cast<float>(k) / 20.0f;
    CHECK(blend_weight(a, BlendParams{}.C_upper, 1.0f) > blend_weight(a, BlendParams{}.C_lower, 1.0f));
  }
}

TEST_CASE("overrides by joint name, linear method, bad names") {
  const auto skeleton = test::make_test_skeleton();
  const BodyMap body = BodyMap::detect(*skeleton);
  BlendParams p;
  p.C_override["lShin"] = 2.0f;
  p.c_override["head"] = 0.5f;
  BlendCurves curves = make_blend_curves(*skeleton, body, p);
  CHECK(curves.C[static_cast<size_t>(skeleton->find("lShin"))] == 2.0f);
  CHECK(curves.c[static_cast<size_t>(skeleton->find("head"))] == 0.5f);
  CHECK(curves.C[static_cast<size_t>(skeleton->find("rShin"))] == p.C_lower);
  // blend_weights evaluates Eq. 1 once per distinct curve (upper, lower, and the overridden shin and head
  // make two more): the same value as per joint.
  CHECK(curves.curve_C.size() == 4);
  std::vector<float> per_curve(static_cast<size_t>(skeleton->size()));
  for (float alpha : {0.0f, 0.13f, 0.5f, 0.97f, 1.0f}) {
    blend_weights(curves, alpha, per_curve.data());
    for (int j = 0; j < skeleton->size(); ++j) {
      const size_t jj = static_cast<size_t>(j);
      CHECK(per_curve[jj] == blend_weight(alpha, curves.C[jj], curves.c[jj]));
    }
  }

  p.method = "linear";
  curves = make_blend_curves(*skeleton, body, p);
  std::vector<float> w(static_cast<size_t>(skeleton->size()));
  blend_weights(curves, 0.37f, w.data());
  for (float x : w) CHECK(x == doctest::Approx(0.37f));

  BlendParams bad;
  bad.C_override["noSuchJoint"] = 1.0f;
  CHECK_THROWS_AS(make_blend_curves(*skeleton, body, bad), std::invalid_argument);
  bad = BlendParams{};
  bad.method = "euler";
  CHECK_THROWS_AS(make_blend_curves(*skeleton, body, bad), std::invalid_argument);
}

TEST_CASE("slerp blend is the shorter arc and exact at the ends") {
  const glm::quat a = rotation(0.2f, {0, 1, 0});
  const glm::quat b = -rotation(1.0f, {0, 1, 0});  // same rotation as +, stored in the other hemisphere
  const glm::quat mid = blend_rotation(a, b, 0.5f);
  CHECK(std::abs(glm::dot(mid, rotation(0.6f, {0, 1, 0}))) == doctest::Approx(1.0f).epsilon(1e-6));
  CHECK(blend_rotation(a, b, 0.0f) == a);
  CHECK(blend_rotation(a, b, 1.0f) == b);
}

TEST_CASE("alpha = 0 gives the locomotion pose, alpha = 1 T_p's joint rotations (before IK and balance)") {
  const auto skeleton = test::make_test_skeleton();
  const BodyMap body = BodyMap::detect(*skeleton);
  const MassModel mass = MassModel::build(*skeleton, body);
  const int n = skeleton->size();
  Pose walk, guard;
  make_poses(n, walk, guard);
  for (const char* method : {"ours", "linear"}) {
    Params params;
    params.blend.method = method;
    const Synthesizer synth(skeleton, body, mass, params);
    SynthesisScratch scratch = synth.make_scratch();
    Pose out = synth.make_pose();
    SynthesisInput in;
    in.locomotion = &walk;
    in.reference = &guard;

    in.alpha = 0.0f;
    synth.stage_blend(in, scratch, out);
    for (int j = 0; j < n; ++j) CHECK(out.rotations[static_cast<size_t>(j)] == walk.rotations[static_cast<size_t>(j)]);
    SynthesisState state;
    synth.stage_trajectory(in, state, scratch, out);
    CHECK(out.root_position == walk.root_position);

    in.alpha = 1.0f;
    synth.stage_blend(in, scratch, out);
    for (int j = 1; j < n; ++j) CHECK(out.rotations[static_cast<size_t>(j)] == guard.rotations[static_cast<size_t>(j)]);
    // The root takes T_p's tilt but keeps the locomotion's heading.
    CHECK(heading_of(out.rotations[0]) == doctest::Approx(heading_of(walk.rotations[0])).epsilon(1e-5));
    const glm::vec3 up_out = out.rotations[0] * glm::vec3(0, 1, 0);
    const glm::vec3 up_guard = guard.rotations[0] * glm::vec3(0, 1, 0);
    CHECK(up_out.y == doctest::Approx(up_guard.y).epsilon(1e-5));
  }
}

}  // namespace prep
