// A 3-vector in one SSE2 register (every x86-64 has them), with glm's arithmetic lane by lane: a sum,
// difference or scalar product is glm's component for component, a cross product glm's two products and
// one difference per component, a dot product glm's (x x + y y) + z z. Code written with V3 gives glm's
// floats to the bit while a loop over body parts or joints keeps its vectors in registers instead of
// three scalars each. Tested against glm in tests/motion/vector_ops_test.cpp.
#pragma once

#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "engine/motion/kinematics.h"

namespace prep {

#if defined(__SSE2__)
struct V3 {
  __m128 r;  // (x, y, z, 0) when loaded from a glm::vec3; the fourth lane is never stored

  static V3 zero() { return {_mm_setzero_ps()}; }
  static V3 load(const glm::vec3& v) { return {kinematics_detail::load_vec3(v)}; }
  void store(glm::vec3& v) const { kinematics_detail::store_vec3(v, r); }
  glm::vec3 vec() const {
    glm::vec3 v;
    store(v);
    return v;
  }
  float x() const { return _mm_cvtss_f32(r); }
  float y() const { return _mm_cvtss_f32(_mm_shuffle_ps(r, r, _MM_SHUFFLE(1, 1, 1, 1))); }
  float z() const { return _mm_cvtss_f32(_mm_movehl_ps(r, r)); }

  friend V3 operator+(V3 a, V3 b) { return {_mm_add_ps(a.r, b.r)}; }
  friend V3 operator-(V3 a, V3 b) { return {_mm_sub_ps(a.r, b.r)}; }
  friend V3 operator*(float s, V3 a) { return {_mm_mul_ps(_mm_set1_ps(s), a.r)}; }
  friend V3 operator/(V3 a, float s) { return {_mm_div_ps(a.r, _mm_set1_ps(s))}; }
  friend V3 operator-(V3 a) { return {_mm_xor_ps(a.r, _mm_set1_ps(-0.0f))}; }
  V3& operator+=(V3 b) { return *this = *this + b; }
  V3& operator-=(V3 b) { return *this = *this - b; }
  friend V3 cross(V3 a, V3 b) { return {kinematics_detail::cross(a.r, b.r)}; }
  friend float dot(V3 a, V3 b) {
    const V3 m{_mm_mul_ps(a.r, b.r)};
    return (m.x() + m.y()) + m.z();
  }
  // q * v for a unit quaternion q (glm's operator*, as quat::rotate).
  friend V3 rotate(const glm::quat& q, V3 v) { return {kinematics_detail::rotate(kinematics_detail::load_quat(q), v.r)}; }
  // glm::conjugate(q) * v: v turned back by q, the conjugate's signs flipped in the register.
  friend V3 rotate_back(const glm::quat& q, V3 v) {
    using namespace kinematics_detail;
    return {kinematics_detail::rotate(quat_conjugate(load_quat(q)), v.r)};
  }
  // glm::min and glm::max lane by lane: y < x ? y : x and x < y ? y : x, which of two equal numbers (+0
  // and -0) they return included (minps and maxps return their second operand then).
  friend V3 min(V3 x, V3 y) { return {_mm_min_ps(y.r, x.r)}; }
  friend V3 max(V3 x, V3 y) { return {_mm_max_ps(y.r, x.r)}; }
  // s in x, y and z: v + s and v - s are glm's vec3 and scalar sum and difference.
  static V3 splat(float s) { return {_mm_set_ps(0.0f, s, s, s)}; }
};
#else
struct V3 {
  glm::vec3 r;

  static V3 zero() { return {glm::vec3(0.0f)}; }
  static V3 load(const glm::vec3& v) { return {v}; }
  void store(glm::vec3& v) const { v = r; }
  glm::vec3 vec() const { return r; }
  float x() const { return r.x; }
  float y() const { return r.y; }
  float z() const { return r.z; }

  friend V3 operator+(V3 a, V3 b) { return {a.r + b.r}; }
  friend V3 operator-(V3 a, V3 b) { return {a.r - b.r}; }
  friend V3 operator*(float s, V3 a) { return {s * a.r}; }
  friend V3 operator/(V3 a, float s) { return {a.r / s}; }
  friend V3 operator-(V3 a) { return {-a.r}; }
  V3& operator+=(V3 b) { return *this = *this + b; }
  V3& operator-=(V3 b) { return *this = *this - b; }
  friend V3 cross(V3 a, V3 b) { return {glm::cross(a.r, b.r)}; }
  friend float dot(V3 a, V3 b) { return glm::dot(a.r, b.r); }
  friend V3 rotate(const glm::quat& q, V3 v) { return {q * v.r}; }
  friend V3 rotate_back(const glm::quat& q, V3 v) { return {glm::conjugate(q) * v.r}; }
  friend V3 min(V3 x, V3 y) { return {glm::min(x.r, y.r)}; }
  friend V3 max(V3 x, V3 y) { return {glm::max(x.r, y.r)}; }
  static V3 splat(float s) { return {glm::vec3(s)}; }
};
#endif

// glm::length and glm::normalize: sqrt(dot(v, v)) and v * (1 / sqrt(dot(v, v))).
inline float length(V3 v) { return std::sqrt(dot(v, v)); }
inline V3 normalize(V3 v) { return (1.0f / std::sqrt(dot(v, v))) * v; }

}  // namespace prep
