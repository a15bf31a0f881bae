// glm's quaternion product, vector rotation and normalization in SSE2 registers (every x86-64 has them),
// each lane computed term for term in glm's order, so the results are glm's to the bit: code that moves
// from glm's operators to these gives the same poses. A quaternion is one register instead of four
// scalars, loaded and stored once (glm's scalar product is sixteen multiplies and twelve adds, each on
// its own lane). Tested against glm in tests/motion/quaternion_ops_test.cpp.
#pragma once

#include <cmath>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "engine/motion/kinematics.h"

namespace prep::quat {

// p * q (glm's operator*).
inline glm::quat mul(const glm::quat& p, const glm::quat& q);
// q * v: v turned by the unit quaternion q (glm's operator*).
inline glm::vec3 rotate(const glm::quat& q, const glm::vec3& v);
// glm::normalize(q): the identity for a zero quaternion.
inline glm::quat normalize(const glm::quat& q);

#if defined(__SSE2__)
inline glm::quat mul(const glm::quat& p, const glm::quat& q) {
  using namespace kinematics_detail;
  // glm, lanes (x, y, z, w):
  //   x = pw qx + px qw + py qz - pz qy      y = pw qy + py qw + pz qx - px qz
  //   z = pw qz + pz qw + px qy - py qx      w = pw qw - px qx - py qy - pz qz
  // added left to right; a - b is a + (-b) exactly, so the signs ride on the products.
  const __m128 a = load_quat(p), b = load_quat(q);
  const __m128 last_negative = _mm_set_ps(-0.0f, 0.0f, 0.0f, 0.0f);
  __m128 r = _mm_mul_ps(_mm_shuffle_ps(a, a, _MM_SHUFFLE(3, 3, 3, 3)), b);
  r = _mm_add_ps(r, _mm_xor_ps(_mm_mul_ps(_mm_shuffle_ps(a, a, _MM_SHUFFLE(0, 2, 1, 0)), _mm_shuffle_ps(b, b, _MM_SHUFFLE(0, 3, 3, 3))),
                               last_negative));
  r = _mm_add_ps(r, _mm_xor_ps(_mm_mul_ps(_mm_shuffle_ps(a, a, _MM_SHUFFLE(1, 0, 2, 1)), _mm_shuffle_ps(b, b, _MM_SHUFFLE(1, 1, 0, 2))),
                               last_negative));
  r = _mm_sub_ps(r, _mm_mul_ps(_mm_shuffle_ps(a, a, _MM_SHUFFLE(2, 1, 0, 2)), _mm_shuffle_ps(b, b, _MM_SHUFFLE(2, 0, 2, 1))));
  glm::quat out;
  store_quat(out, r);
  return out;
}

inline glm::vec3 rotate(const glm::quat& q, const glm::vec3& v) {
  using namespace kinematics_detail;  // its rotate is glm's: v + 2 (w (q x v) + q x (q x v)), crosses alike
  glm::vec3 out;
  store_vec3(out, kinematics_detail::rotate(load_quat(q), load_vec3(v)));
  return out;
}

inline glm::quat normalize(const glm::quat& q) {
  // glm: length = sqrt((w w + x x) + (y y + z z)), then each number times 1 / length.
  const float length = std::sqrt((q.w * q.w + q.x * q.x) + (q.y * q.y + q.z * q.z));
  if (length <= 0.0f) return glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  using namespace kinematics_detail;
  glm::quat out;
  store_quat(out, _mm_mul_ps(load_quat(q), _mm_set1_ps(1.0f / length)));
  return out;
}
#else
inline glm::quat mul(const glm::quat& p, const glm::quat& q) { return p * q; }
inline glm::vec3 rotate(const glm::quat& q, const glm::vec3& v) { return q * v; }
inline glm::quat normalize(const glm::quat& q) { return glm::normalize(q); }
#endif

}  // namespace prep::quat
