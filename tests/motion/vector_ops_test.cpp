#include "engine/motion/vector_ops.h"

#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "tests/support/bits.h"

using namespace prep;

using test::same_bits;

TEST_CASE("vector ops: sums, products, crosses, dots, lengths, normalization and rotations in a register are glm's to the bit") {
  // Magnitudes from 1e-6 to 1e2 and mixed signs, so that a reordered sum (say x + (y + z) for a dot
  // product) would show in the last bit somewhere.
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), scale(-6.0f, 2.0f);
  int reordered_dots_differ = 0;
  for (int i = 0; i < 200000; ++i) {
    const float sa = std::pow(10.0f, scale(rng)), sb = std::pow(10.0f, scale(rng));
    const glm::vec3 a(u(rng) * sa, u(rng), u(rng) * sb), b(u(rng) * sb, u(rng) * sa, u(rng));
    const float s = u(rng) * sb;
    const glm::quat q = glm::normalize(glm::quat(u(rng), u(rng), u(rng), u(rng)));
    const V3 va = V3::load(a), vb = V3::load(b);
    REQUIRE(same_bits((va + vb).vec(), a + b));
    REQUIRE(same_bits((va - vb).vec(), a - b));
    REQUIRE(same_bits((s * va).vec(), s * a));
    REQUIRE(same_bits((va / s).vec(), a / s));
    REQUIRE(same_bits((-va).vec(), -a));
    REQUIRE(same_bits(cross(va, vb).vec(), glm::cross(a, b)));
    REQUIRE(same_bits(dot(va, vb), glm::dot(a, b)));
    REQUIRE(same_bits(rotate(q, va).vec(), q * a));
    REQUIRE(same_bits(rotate_back(q, va).vec(), glm::conjugate(q) * a));
    REQUIRE(same_bits(length(va), glm::length(a)));
    REQUIRE(same_bits(normalize(va).vec(), glm::normalize(a)));
    V3 sum = va;
    sum += vb;
    sum -= s * va;
    REQUIRE(same_bits(sum.vec(), a + b - s * a));
    REQUIRE(same_bits(va.x(), a.x));
    REQUIRE(same_bits(va.y(), a.y));
    REQUIRE(same_bits(va.z(), a.z));
    const glm::vec3 m = a * b;
    reordered_dots_differ += !same_bits(m.x + (m.y + m.z), glm::dot(a, b));
  }
  CHECK(reordered_dots_differ >= 1000);  // the dot check above does tell orders apart
  CHECK(same_bits(V3::zero().vec(), glm::vec3(0.0f)));
}

TEST_CASE("vector ops: min and max in a register are glm's, which of two equal zeros and NaNs included") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const float specials[] = {0.0f, -0.0f, 1.0f, -1.0f, NAN, INFINITY, -INFINITY};
  const auto pick = [&](int k) { return k % 3 == 0 ? specials[static_cast<size_t>(rng() % 7)] : u(rng); };
  for (int i = 0; i < 100000; ++i) {
    const glm::vec3 a(pick(i), pick(i + 1), pick(i + 2)), b(pick(i + 1), pick(i), pick(i + 3));
    REQUIRE(same_bits(min(V3::load(a), V3::load(b)).vec(), glm::min(a, b)));
    REQUIRE(same_bits(max(V3::load(a), V3::load(b)).vec(), glm::max(a, b)));
    const float s = pick(i);
    REQUIRE(same_bits((V3::load(a) - V3::splat(s)).vec(), a - s));
    REQUIRE(same_bits((V3::load(a) + V3::splat(s)).vec(), a + s));
  }
  // The two zeros: glm's min(+0, -0) is +0 (-0 < +0 is false), its max(-0, +0) is -0.
  CHECK(same_bits(min(V3::load(glm::vec3(0.0f)), V3::load(glm::vec3(-0.0f))).vec(), glm::vec3(0.0f)));
  CHECK(same_bits(max(V3::load(glm::vec3(-0.0f)), V3::load(glm::vec3(0.0f))).vec(), glm::vec3(-0.0f)));
}
