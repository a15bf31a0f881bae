#include "engine/motion/quaternion_ops.h"

#include <doctest/doctest.h>

#include <random>
#include <vector>

#include "tests/support/bits.h"

using namespace prep;

using test::same_bits;

TEST_CASE("quaternion ops: product, rotation and normalization are glm's to the bit") {
  // Unit quaternions as the engine keeps them, unnormalized ones (products before normalize), tiny and
  // mixed-sign numbers: any reordering of glm's additions would show in the last bit somewhere.
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), scale(-6.0f, 2.0f);
  int differing_products = 0;
  for (int i = 0; i < 200000; ++i) {
    const float sa = std::pow(10.0f, scale(rng)), sb = std::pow(10.0f, scale(rng));
    glm::quat p(u(rng) * sa, u(rng) * sa, u(rng) * sa, u(rng) * sa);
    glm::quat q(u(rng), u(rng) * sb, u(rng), u(rng) * sb);
    if (i % 2 == 0) {
      p = glm::normalize(p);
      q = glm::normalize(q);
    }
    const glm::vec3 v(u(rng) * sb, u(rng), u(rng) * sa);
    REQUIRE(same_bits(quat::mul(p, q), p * q));
    REQUIRE(same_bits(quat::conjugate_mul(p, q), glm::conjugate(p) * q));
    REQUIRE(same_bits(quat::mul_conjugate(p, q), p * glm::conjugate(q)));
    REQUIRE(same_bits(quat::inverse_mul(p, q), glm::inverse(p) * q));
    REQUIRE(same_bits(quat::rotate(p, v), p * v));
    REQUIRE(same_bits(quat::normalize(p), glm::normalize(p)));
#if defined(__SSE2__)
    // The forward kinematics' register product adds the same terms in another order: the last bit
    // differs often, so the checks above do tell orders apart.
    glm::quat other;
    kinematics_detail::store_quat(other, kinematics_detail::quat_multiply(kinematics_detail::load_quat(p),
                                                                           kinematics_detail::load_quat(q)));
    differing_products += !same_bits(other, p * q);
#else
    differing_products = 1000;
#endif
  }
  CHECK(differing_products >= 1000);
  CHECK(same_bits(quat::normalize(glm::quat(0.0f, 0.0f, 0.0f, 0.0f)), glm::quat(1.0f, 0.0f, 0.0f, 0.0f)));
}

TEST_CASE("quaternion ops: the batched and component-wise normalizes are normalize's to the bit") {
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), scale(-6.0f, 2.0f);
  std::vector<glm::quat> batch, single;
  for (int round = 0; round < 20000; ++round) {
    const size_t n = static_cast<size_t>(round % 11);  // whole groups of four and every tail
    batch.resize(n);
    for (size_t i = 0; i < n; ++i) {
      const float s = std::pow(10.0f, scale(rng));
      batch[i] = (rng() % 13 == 0) ? glm::quat(0.0f, 0.0f, 0.0f, 0.0f) : glm::quat(u(rng) * s, u(rng), u(rng) * s, u(rng));
    }
    single = batch;
    quat::normalize_each(batch.data(), n);
    for (size_t i = 0; i < n; ++i) {
      REQUIRE(same_bits(batch[i], quat::normalize(single[i])));
      REQUIRE(same_bits(quat::normalize(single[i].w, single[i].x, single[i].y, single[i].z), quat::normalize(single[i])));
    }
  }
}

TEST_CASE("quaternion ops: with_positive_w is q or -q, whichever has w >= 0") {
  const glm::quat q(-0.5f, 0.5f, -0.5f, 0.5f);
  CHECK(same_bits(quat::with_positive_w(q), -q));
  CHECK(same_bits(quat::with_positive_w(-q), -q));
  // A negative zero w is not below zero: the quaternion stays as it is, signs and all.
  const glm::quat zero_w(-0.0f, -1.0f, 0.0f, 0.0f);
  CHECK(same_bits(quat::with_positive_w(zero_w), zero_w));
}
