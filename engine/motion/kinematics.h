// Forward kinematics: local pose -> world-space joint positions and rotations.
#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>
#include <cstdint>
#include <vector>

#include "engine/motion/pose.h"
#include "engine/motion/skeleton.h"

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

namespace prep {

// One joint of forward kinematics from its parent's world frame: rotation = parent_rotation * local,
// position = parent_position + parent_rotation * offset. Every forward kinematics pass of the engine
// (the whole body, the legs alone, the balance optimizer's trial postures) composes joints with this, so
// they agree to the bit. With SSE2 (every x86-64) a quaternion is one register: its product is four
// broadcasts, three shuffles and four multiplies instead of sixteen scalar ones.
inline void place_joint(const glm::vec3& parent_position, const glm::quat& parent_rotation, const glm::vec3& offset,
                        const glm::quat& local, glm::vec3& position, glm::quat& rotation);

// World position of every joint. If world_rotations is given it receives every joint's world rotation.
// Output vectors are resized to the joint count (no allocation once they have the size).
void forward_kinematics(const Skeleton& skeleton, const Pose& pose, std::vector<glm::vec3>& world_positions,
                        std::vector<glm::quat>* world_rotations = nullptr);

// A partial forward-kinematics pass over listed joints (parents before children, each listed with its
// ancestors), laid out for its loop: each joint beside its parent's index and its offset (a Joint also
// carries its name and End Site: a cache line each), the roots apart since they are placed from the
// pose's root position. run() is forward_kinematics' arithmetic for those joints, to the bit.
class JointPass {
 public:
  JointPass() = default;
  JointPass(const Skeleton& skeleton, const std::vector<int>& joints);
  void run(const Pose& pose, std::vector<glm::vec3>& positions, std::vector<glm::quat>& rotations) const;
  // run() of two poses joint by joint: two independent chains in flight.
  void run_two(const Pose& pose_a, std::vector<glm::vec3>& positions_a, std::vector<glm::quat>& rotations_a,
               const Pose& pose_b, std::vector<glm::vec3>& positions_b, std::vector<glm::quat>& rotations_b) const;

 private:
  struct Step {
    std::uint32_t joint = 0, parent = 0;
    glm::vec3 offset{0.0f};
  };
  std::vector<std::uint32_t> roots_;
  std::vector<Step> steps_;
};

// World position of joint j's End Site, given the world positions and rotations from forward_kinematics.
// Inline: the IK, the floor stage and the support polygon take a few per character and frame.
inline glm::vec3 end_site_position(const Skeleton& skeleton, int joint, const std::vector<glm::vec3>& world_positions,
                                   const std::vector<glm::quat>& world_rotations);

namespace kinematics_detail {

#if defined(__SSE2__)
static_assert(sizeof(glm::quat) == 16 && sizeof(glm::vec3) == 12, "packed glm types");

// A vec3 into the first three lanes (the fourth zero) and back, touching its twelve bytes only.
inline __m128 load_vec3(const glm::vec3& v) {
  const __m128 xy = _mm_loadl_pi(_mm_setzero_ps(), reinterpret_cast<const __m64*>(&v.x));
  return _mm_movelh_ps(xy, _mm_load_ss(&v.z));
}
inline void store_vec3(glm::vec3& v, __m128 r) {
  _mm_storel_pi(reinterpret_cast<__m64*>(&v.x), r);
  _mm_store_ss(&v.z, _mm_movehl_ps(r, r));
}
// The quaternion's memory order is (x, y, z, w): glm's default.
inline __m128 load_quat(const glm::quat& q) { return _mm_loadu_ps(&q.x); }
inline void store_quat(glm::quat& q, __m128 r) { _mm_storeu_ps(&q.x, r); }

// The conjugate of the quaternion in q: x, y and z negated exactly (a sign flip), w as it is.
inline __m128 quat_conjugate(__m128 q) { return _mm_xor_ps(q, _mm_set_ps(0.0f, -0.0f, -0.0f, -0.0f)); }

// a * b, lanes (x, y, z, w): a.w b + a.x (b.w, -b.z, b.y, -b.x) + a.y (b.z, b.w, -b.x, -b.y)
// + a.z (-b.y, b.x, b.w, -b.z).
inline __m128 quat_multiply(__m128 a, __m128 b) {
  const __m128 x_terms = _mm_xor_ps(_mm_shuffle_ps(b, b, _MM_SHUFFLE(0, 1, 2, 3)), _mm_set_ps(-0.0f, 0.0f, -0.0f, 0.0f));
  const __m128 y_terms = _mm_xor_ps(_mm_shuffle_ps(b, b, _MM_SHUFFLE(1, 0, 3, 2)), _mm_set_ps(-0.0f, -0.0f, 0.0f, 0.0f));
  const __m128 z_terms = _mm_xor_ps(_mm_shuffle_ps(b, b, _MM_SHUFFLE(2, 3, 0, 1)), _mm_set_ps(-0.0f, 0.0f, 0.0f, -0.0f));
  __m128 r = _mm_mul_ps(_mm_shuffle_ps(a, a, _MM_SHUFFLE(3, 3, 3, 3)), b);
  r = _mm_add_ps(r, _mm_mul_ps(_mm_shuffle_ps(a, a, _MM_SHUFFLE(0, 0, 0, 0)), x_terms));
  r = _mm_add_ps(r, _mm_mul_ps(_mm_shuffle_ps(a, a, _MM_SHUFFLE(1, 1, 1, 1)), y_terms));
  return _mm_add_ps(r, _mm_mul_ps(_mm_shuffle_ps(a, a, _MM_SHUFFLE(2, 2, 2, 2)), z_terms));
}

// a x b in the first three lanes (a's fourth lane may hold anything: it cancels).
inline __m128 cross(__m128 a, __m128 b) {
  const __m128 a_yzx = _mm_shuffle_ps(a, a, _MM_SHUFFLE(3, 0, 2, 1)), b_yzx = _mm_shuffle_ps(b, b, _MM_SHUFFLE(3, 0, 2, 1));
  const __m128 c = _mm_sub_ps(_mm_mul_ps(a, b_yzx), _mm_mul_ps(a_yzx, b));
  return _mm_shuffle_ps(c, c, _MM_SHUFFLE(3, 0, 2, 1));
}

// v turned by the unit quaternion q: v + 2 (w (q x v) + q x (q x v)), q's vector part in lanes x, y, z.
inline __m128 rotate(__m128 q, __m128 v) {
  const __m128 uv = cross(q, v);
  const __m128 uuv = cross(q, uv);
  const __m128 w = _mm_shuffle_ps(q, q, _MM_SHUFFLE(3, 3, 3, 3));
  const __m128 t = _mm_add_ps(_mm_mul_ps(uv, w), uuv);
  return _mm_add_ps(v, _mm_add_ps(t, t));
}
#endif

}  // namespace kinematics_detail

inline void place_joint(const glm::vec3& parent_position, const glm::quat& parent_rotation, const glm::vec3& offset,
                        const glm::quat& local, glm::vec3& position, glm::quat& rotation) {
#if defined(__SSE2__)
  using namespace kinematics_detail;
  const __m128 parent = load_quat(parent_rotation);
  const __m128 moved = _mm_add_ps(load_vec3(parent_position), rotate(parent, load_vec3(offset)));
  store_quat(rotation, quat_multiply(parent, load_quat(local)));
  store_vec3(position, moved);
#else
  position = parent_position + parent_rotation * offset;
  rotation = parent_rotation * local;
#endif
}

inline glm::vec3 end_site_position(const Skeleton& skeleton, int joint, const std::vector<glm::vec3>& world_positions,
                                   const std::vector<glm::quat>& world_rotations) {
  const size_t j = static_cast<size_t>(joint);
#if defined(__SSE2__)
  using namespace kinematics_detail;
  glm::vec3 out;
  store_vec3(out, _mm_add_ps(load_vec3(world_positions[j]),
                             rotate(load_quat(world_rotations[j]), load_vec3(skeleton.joints[j].end_site))));
  return out;
#else
  return world_positions[j] + world_rotations[j] * skeleton.joints[j].end_site;
#endif
}

}  // namespace prep
