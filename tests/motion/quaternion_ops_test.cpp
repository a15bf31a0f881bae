#include "engine/motion/quaternion_ops.h"

#include <doctest/doctest.h>

#include <random>

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
