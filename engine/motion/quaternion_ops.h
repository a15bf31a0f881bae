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
// glm::conjugate(p) * q and p * glm::conjugate(q): the conjugate's signs are flipped in the register
// instead of a glm::quat being built in memory and read back (a stall, see normalize below).
inline glm::quat conjugate_mul(const glm::quat& p, const glm::quat& q);
inline glm::quat mul_conjugate(const glm::quat& p, const glm::quat& q);
// glm::inverse(p) * q, for any non-zero p: glm's conjugate(p) / dot(p, p), its four divisions one
// division of the register.
inline glm::quat inverse_mul(const glm::quat& p, const glm::quat& q);
// q * v: v turned by the unit quaternion q (glm's operator*).
inline glm::vec3 rotate(const glm::quat& q, const glm::vec3& v);
// glm::normalize(q): the identity for a zero quaternion.
inline glm::quat normalize(const glm::quat& q);
// glm::normalize(glm::quat(w, x, y, z)) for a quaternion made of numbers just computed: they go into the
// register directly. Built as a glm::quat they would be stored a number or two at a time and read back
// as one 16-byte load, which the processor cannot forward from the smaller stores: it waits for them to
// reach the cache (a stall of a dozen cycles or more, every call).
inline glm::quat normalize(float w, float x, float y, float z);
// q or -q, whichever has w >= 0 (the same rotation), without leaving the register.
inline glm::quat with_positive_w(const glm::quat& q);
// normalize(q[i]) for each of the n quaternions, in place: four lengths take one square root and one
// division where four normalizes take four of each (the processor's divider is the bottleneck of a loop
// of normalizes). The same numbers, to the bit.
inline void normalize_each(glm::quat* q, size_t n);

#if defined(__SSE2__)
namespace detail {
// glm's product of the quaternions in a and b, lanes (x, y, z, w):
//   x = pw qx + px qw + py qz - pz qy      y = pw qy + py qw + pz qx - px qz
//   z = pw qz + pz qw + px qy - py qx      w = pw qw - px qx - py qy - pz qz
// added left to right; a - b is a + (-b) exactly, so the signs ride on the products.
inline __m128 glm_product(__m128 a, __m128 b) {
  const __m128 last_negative = _mm_set_ps(-0.0f, 0.0f, 0.0f, 0.0f);
  __m128 r = _mm_mul_ps(_mm_shuffle_ps(a, a, _MM_SHUFFLE(3, 3, 3, 3)), b);
  r = _mm_add_ps(r, _mm_xor_ps(_mm_mul_ps(_mm_shuffle_ps(a, a, _MM_SHUFFLE(0, 2, 1, 0)), _mm_shuffle_ps(b, b, _MM_SHUFFLE(0, 3, 3, 3))),
                               last_negative));
  r = _mm_add_ps(r, _mm_xor_ps(_mm_mul_ps(_mm_shuffle_ps(a, a, _MM_SHUFFLE(1, 0, 2, 1)), _mm_shuffle_ps(b, b, _MM_SHUFFLE(1, 1, 0, 2))),
                               last_negative));
  return _mm_sub_ps(r, _mm_mul_ps(_mm_shuffle_ps(a, a, _MM_SHUFFLE(2, 1, 0, 2)), _mm_shuffle_ps(b, b, _MM_SHUFFLE(2, 0, 2, 1))));
}
inline glm::quat stored(__m128 r) {
  glm::quat out;
  kinematics_detail::store_quat(out, r);
  return out;
}
}  // namespace detail

inline glm::quat mul(const glm::quat& p, const glm::quat& q) {
  using kinematics_detail::load_quat;
  return detail::stored(detail::glm_product(load_quat(p), load_quat(q)));
}
inline glm::quat conjugate_mul(const glm::quat& p, const glm::quat& q) {
  using kinematics_detail::load_quat;
  return detail::stored(detail::glm_product(kinematics_detail::quat_conjugate(load_quat(p)), load_quat(q)));
}
inline glm::quat mul_conjugate(const glm::quat& p, const glm::quat& q) {
  using kinematics_detail::load_quat;
  return detail::stored(detail::glm_product(load_quat(p), kinematics_detail::quat_conjugate(load_quat(q))));
}
inline glm::quat inverse_mul(const glm::quat& p, const glm::quat& q) {
  using kinematics_detail::load_quat;
  const float norm2 = (p.w * p.w + p.x * p.x) + (p.y * p.y + p.z * p.z);  // glm's dot(p, p)
  const __m128 inverse = _mm_div_ps(kinematics_detail::quat_conjugate(load_quat(p)), _mm_set1_ps(norm2));
  return detail::stored(detail::glm_product(inverse, load_quat(q)));
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

inline glm::quat normalize(float w, float x, float y, float z) {
  const float length = std::sqrt((w * w + x * x) + (y * y + z * z));  // as normalize(const glm::quat&)
  if (length <= 0.0f) return glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  glm::quat out;
  kinematics_detail::store_quat(out, _mm_mul_ps(_mm_set_ps(w, z, y, x), _mm_set1_ps(1.0f / length)));
  return out;
}

inline void normalize_each(glm::quat* q, size_t n) {
  using namespace kinematics_detail;
  size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    const __m128 a = load_quat(q[i]), b = load_quat(q[i + 1]), c = load_quat(q[i + 2]), d = load_quat(q[i + 3]);
    // Lanes per quaternion: the squares of (x, y, z, w) of a, b, c, d transposed to one register per
    // component, then (w w + x x) + (y y + z z) lane by lane, as normalize adds them.
    __m128 xs = _mm_mul_ps(a, a), ys = _mm_mul_ps(b, b), zs = _mm_mul_ps(c, c), ws = _mm_mul_ps(d, d);
    _MM_TRANSPOSE4_PS(xs, ys, zs, ws);
    const __m128 length = _mm_sqrt_ps(_mm_add_ps(_mm_add_ps(ws, xs), _mm_add_ps(ys, zs)));
    const __m128 inverse = _mm_div_ps(_mm_set1_ps(1.0f), length);
    const int zero = _mm_movemask_ps(_mm_cmple_ps(length, _mm_setzero_ps()));
    const __m128 unit = _mm_set_ps(1.0f, 0.0f, 0.0f, 0.0f);
    const __m128 in[4] = {a, b, c, d};
    const __m128 scale[4] = {_mm_shuffle_ps(inverse, inverse, _MM_SHUFFLE(0, 0, 0, 0)),
                             _mm_shuffle_ps(inverse, inverse, _MM_SHUFFLE(1, 1, 1, 1)),
                             _mm_shuffle_ps(inverse, inverse, _MM_SHUFFLE(2, 2, 2, 2)),
                             _mm_shuffle_ps(inverse, inverse, _MM_SHUFFLE(3, 3, 3, 3))};
    for (int k = 0; k < 4; ++k) store_quat(q[i + static_cast<size_t>(k)], (zero >> k) & 1 ? unit : _mm_mul_ps(in[k], scale[k]));
  }
  for (; i < n; ++i) q[i] = normalize(q[i]);
}

inline glm::quat with_positive_w(const glm::quat& q) {
  using namespace kinematics_detail;
  const __m128 r = load_quat(q);
  // The sign of w, in every lane when w < 0 (a negative zero keeps its sign, as q.w < 0 does not flip it).
  const __m128 negative = _mm_cmplt_ps(_mm_shuffle_ps(r, r, _MM_SHUFFLE(3, 3, 3, 3)), _mm_setzero_ps());
  glm::quat out;
  store_quat(out, _mm_xor_ps(r, _mm_and_ps(negative, _mm_set1_ps(-0.0f))));
  return out;
}
#else
inline glm::quat mul(const glm::quat& p, const glm::quat& q) { return p * q; }
inline glm::quat conjugate_mul(const glm::quat& p, const glm::quat& q) { return glm::conjugate(p) * q; }
inline glm::quat mul_conjugate(const glm::quat& p, const glm::quat& q) { return p * glm::conjugate(q); }
inline glm::quat inverse_mul(const glm::quat& p, const glm::quat& q) { return glm::inverse(p) * q; }
inline glm::vec3 rotate(const glm::quat& q, const glm::vec3& v) { return q * v; }
inline glm::quat normalize(const glm::quat& q) { return glm::normalize(q); }
inline glm::quat normalize(float w, float x, float y, float z) { return glm::normalize(glm::quat(w, x, y, z)); }
inline glm::quat with_positive_w(const glm::quat& q) { return q.w < 0.0f ? -q : q; }
inline void normalize_each(glm::quat* q, size_t n) {
  for (size_t i = 0; i < n; ++i) q[i] = glm::normalize(q[i]);
}
#endif

}  // namespace prep::quat
