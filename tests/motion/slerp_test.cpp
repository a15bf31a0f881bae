#include "engine/motion/slerp.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <glm/gtc/quaternion.hpp>

namespace {

using namespace prep;

// The textbook slerp on the shorter arc in double precision: what the series must reproduce.
glm::dquat reference_slerp(const glm::quat& a, const glm::quat& b, float t) {
  const glm::dquat qa(a), qb0(b);
  double d = glm::dot(qa, qb0);
  const glm::dquat qb = d < 0.0 ? -qb0 : qb0;
  d = std::abs(d);
  if (d > 1.0 - 1e-12) return glm::normalize(qa + (qb - qa) * static_cast<double>(t));
  const double theta = std::acos(std::min(1.0, d));
  const double wa = std::sin((1.0 - t) * theta) / std::sin(theta), wb = std::sin(t * theta) / std::sin(theta);
  return glm::normalize(wa * qa + wb * qb);
}

// The series slerp with every one of its 40 terms added, none left out: stopping once the terms fall
// below half a unit in the last place of the sums must give this to the bit. The arithmetic of the
// engine's scalar path, in the same order.
glm::quat series_slerp_every_term(const glm::quat& qa, const glm::quat& qb, float t) {
  float a[4], b[4];
  std::memcpy(a, &qa, sizeof a);
  std::memcpy(b, &qb, sizeof b);
  float d = a[0] * b[0] + a[1] * b[1];
  d = d + a[2] * b[2];
  d = d + a[3] * b[3];
  if (d < 0.0f) {
    for (float& c : b) c = -c;
    d = -d;
  }
  const float x = std::max(0.0f, 1.0f - d), s = 1.0f - t;
  float term_a = 1.0f, term_b = 1.0f, sum_a = 1.0f, sum_b = 1.0f;
  for (int i = 1; i <= 40; ++i) {
    const float cx = (1.0f / static_cast<float>(i * (2 * i + 1))) * x;
    const float square = static_cast<float>(i * i);
    term_a = term_a * ((square - s * s) * cx);
    term_b = term_b * ((square - t * t) * cx);
    sum_a = sum_a + term_a;
    sum_b = sum_b + term_b;
  }
  const float weight_a = s * sum_a, weight_b = t * sum_b;
  float q[4];
  for (int c = 0; c < 4; ++c) q[c] = weight_a * a[c] + weight_b * b[c];
  float length2 = q[0] * q[0] + q[1] * q[1];
  length2 = length2 + q[2] * q[2];
  length2 = length2 + q[3] * q[3];
  const float length = std::sqrt(length2);
  for (float& c : q) c = c / length;
  glm::quat out;
  std::memcpy(&out, q, sizeof q);
  return out;
}

// The largest difference between two rotations, as the angle (radians) of the rotation between them.
double angle_between(const glm::dquat& a, const glm::dquat& b) {
  return 2.0 * std::acos(std::min(1.0, std::abs(glm::dot(glm::normalize(a), glm::normalize(b)))));
}

glm::quat random_rotation(std::mt19937& rng) {
  std::normal_distribution<float> n(0.0f, 1.0f);
  return glm::normalize(glm::quat(n(rng), n(rng), n(rng), n(rng)));
}

// A rotation `angle` radians away from q about a random axis.
glm::quat turned(const glm::quat& q, float angle, std::mt19937& rng) {
  std::normal_distribution<float> n(0.0f, 1.0f);
  const glm::vec3 axis = glm::normalize(glm::vec3(n(rng), n(rng), n(rng)));
  return glm::angleAxis(angle, axis) * q;
}

}  // namespace

TEST_CASE("slerp: the series matches the trigonometric slerp from a hundredth of a degree to a half turn") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  double worst = 0.0;
  for (float angle : {1.7e-4f, 0.01f, 0.05f, 0.3f, 1.0f, 2.0f, 3.0f, 3.14f}) {
    for (int k = 0; k < 200; ++k) {
      const glm::quat a = random_rotation(rng);
      glm::quat b = turned(a, angle, rng);
      if (k % 2) b = -b;  // the far sign: the shorter arc must still be taken
      const float t = unit(rng);
      const glm::quat q = slerp_shorter(a, b, t);
      CHECK(std::abs(glm::length(q) - 1.0f) < 1e-6f);
      worst = std::max(worst, angle_between(glm::dquat(q), reference_slerp(a, b, t)));
    }
  }
  // Float precision: a rotation about 1e-6 rad off at most (a 1 m limb's tip 1 micrometre).
  CHECK(worst < 2e-6);
}

TEST_CASE("slerp: the ends are the inputs bit for bit, and out may be an input") {
  std::mt19937 rng(3);
  std::vector<glm::quat> a(7), b(7), out(7);
  for (size_t i = 0; i < a.size(); ++i) a[i] = random_rotation(rng), b[i] = -random_rotation(rng);
  const std::vector<float> t = {0.0f, -0.5f, 1.0f, 1.5f, 0.0f, 1.0f, 0.5f};
  slerp_shorter(a.data(), b.data(), t.data(), out.data(), a.size());
  for (size_t i : {0u, 1u, 4u}) CHECK(out[i] == a[i]);
  for (size_t i : {2u, 3u, 5u}) CHECK(out[i] == b[i]);
  const glm::quat middle = slerp_shorter(a[6], b[6], 0.5f);
  std::vector<glm::quat> in_place = a;
  slerp_shorter(in_place.data(), b.data(), t.data(), in_place.data(), a.size());
  CHECK(in_place[6] == out[6]);
  CHECK(angle_between(glm::dquat(out[6]), glm::dquat(middle)) < 1e-6);
}

TEST_CASE("slerp: the SSE2 path and the scalar path agree on every rotation of a skeleton-sized batch") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), angle(0.0f, 3.1f);
  for (size_t n : {1u, 3u, 4u, 22u, 43u, 100u}) {
    std::vector<glm::quat> a(n), b(n), simd(n), scalar(n);
    std::vector<float> t(n);
    for (size_t i = 0; i < n; ++i) {
      a[i] = random_rotation(rng);
      b[i] = turned(a[i], i % 3 == 0 ? 0.02f * unit(rng) : angle(rng), rng);  // clip frames and blends
      if (i % 2) b[i] = -b[i];
      t[i] = i % 5 == 0 ? 0.0f : unit(rng);
    }
    slerp_shorter(a.data(), b.data(), t.data(), simd.data(), n);
    slerp_shorter_scalar(a.data(), b.data(), t.data(), scalar.data(), n);
    double worst = 0.0;
    for (size_t i = 0; i < n; ++i) worst = std::max(worst, angle_between(glm::dquat(simd[i]), glm::dquat(scalar[i])));
    // The same arithmetic; four lanes may run a term or two longer than one alone (each below 2^-24).
    CHECK(worst < 1e-6);
    std::vector<glm::quat> same_t(n);
    slerp_shorter(a.data(), b.data(), 0.37f, same_t.data(), n);
    for (size_t i = 0; i < n; ++i) {
      CHECK(angle_between(glm::dquat(same_t[i]), glm::dquat(slerp_shorter(a[i], b[i], 0.37f))) < 1e-6);
    }
  }
}

TEST_CASE("slerp: four lanes give each rotation's scalar result to the bit, whatever the other lanes ask") {
  // Lanes at an end (t <= 0 or t >= 1) beside lanes between, at small and large angles: a lane's result
  // may not depend on how long its neighbours' series run (it stops adding terms once they are below a
  // half unit in the last place of its sum), nor on whether all four lanes only take an end.
  std::mt19937 rng(29);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), angle(0.0f, 3.1f);
  std::uniform_int_distribution<int> kind(0, 3);
  int between = 0, all_at_ends = 0;
  for (int group = 0; group < 20000; ++group) {
    glm::quat a[4], b[4], simd[4];
    float t[4];
    for (int k = 0; k < 4; ++k) {
      a[k] = random_rotation(rng);
      b[k] = turned(a[k], kind(rng) == 0 ? 0.02f * unit(rng) : angle(rng), rng);
      if (kind(rng) == 0) b[k] = -b[k];
      const int end = group % 7 == 0 ? kind(rng) % 2 : kind(rng);
      t[k] = end == 0 ? -0.5f * unit(rng) : end == 1 ? 1.0f + unit(rng) : unit(rng);
    }
    slerp_shorter(a, b, t, simd, 4);
    bool only_ends = true;
    for (int k = 0; k < 4; ++k) {
      const glm::quat scalar = slerp_shorter(a[k], b[k], t[k]);
      REQUIRE(std::memcmp(&simd[k], &scalar, sizeof scalar) == 0);
      if (t[k] > 0.0f && t[k] < 1.0f) only_ends = false, ++between;
    }
    all_at_ends += only_ends;
  }
  CHECK(between > 20000);
  CHECK(all_at_ends > 1000);
}

TEST_CASE("slerp: leaving out the terms below half a unit in the last place changes no bit of the result") {
  // Angles up to a half turn (x = 1, the slowest series) and blend weights across (0, 1), through the
  // scalar path and four lanes at a time.
  std::mt19937 rng(41);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<glm::quat> a(4000), b(4000), simd(4000);
  std::vector<float> t(4000);
  for (size_t i = 0; i < a.size(); ++i) {
    a[i] = random_rotation(rng);
    const float angle = i % 4 == 0 ? 3.14159f * std::sqrt(unit(rng)) : i % 4 == 1 ? 0.05f * unit(rng) : 3.14159f * unit(rng);
    b[i] = turned(a[i], angle, rng);
    if (i % 3 == 0) b[i] = -b[i];
    t[i] = i % 50 == 0 ? 1e-4f * unit(rng) : unit(rng);
  }
  slerp_shorter(a.data(), b.data(), t.data(), simd.data(), a.size());
  int differing = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    if (!(t[i] > 0.0f && t[i] < 1.0f)) continue;
    const glm::quat whole = series_slerp_every_term(a[i], b[i], t[i]);
    const glm::quat scalar = slerp_shorter(a[i], b[i], t[i]);
    differing += std::memcmp(&scalar, &whole, sizeof whole) != 0;
    differing += std::memcmp(&simd[i], &whole, sizeof whole) != 0;
  }
  CHECK(differing == 0);
}
