// Spherical linear interpolation of unit quaternions on the shorter arc, without trigonometry, four
// rotations at a time with SSE2 (every x86-64 has it; no -march flag is needed). Blending (Eq. 2), sampling a
// clip between its frames and the world's cross-fades all go through here.
//
// slerp(a, b, t) = (sin((1 - t) theta) a + sin(t theta) b) / sin theta, cos theta = |a . b| (b's sign taken
// so that the arc is the shorter one). Each weight is a power series in x = 1 - cos theta:
//   sin(t theta) / sin theta = t * sum_i u_i(t) x^i,   u_0 = 1,   u_i = u_(i-1) (i^2 - t^2) / (i (2i + 1)),
// (a hypergeometric series in (1 - cos theta) / 2). On the shorter arc 0 <= x <= 1 and successive terms
// shrink by about x / 2, so it converges for every pair; terms are added until the last one is below 2^-24
// (half a float's resolution at the sum, so the terms left out would not change it). Between two frames of
// a clip (theta of a degree or two) that is two or three terms, where the trigonometric form costs an acos
// and a sine or two per joint; at the largest angle (a half turn, x = 1) it is at most 22.
//
// The results are normalized. They agree with the trigonometric slerp to float precision (the test
// "slerp: the series ..." in tests/motion/slerp_test.cpp). The SSE2 and the scalar path do the same
// arithmetic in the same order and agree to the bit: four lanes run as many terms as the slowest of them
// needs, but a term below 2^-24 added to a sum in [1, 2) leaves it as it is.
#pragma once

#include <cstddef>

#include <glm/gtc/quaternion.hpp>

namespace prep {

// One rotation. t <= 0 gives a, t >= 1 gives b (as given, not sign-flipped).
glm::quat slerp_shorter(const glm::quat& a, const glm::quat& b, float t);

// out[i] = slerp_shorter(a[i], b[i], t[i]) for i < n; `out` may be `a` or `b`. The SSE2 path where the
// build has it, four rotations at a time.
void slerp_shorter(const glm::quat* a, const glm::quat* b, const float* t, glm::quat* out, size_t n);
// The same with one t for all.
void slerp_shorter(const glm::quat* a, const glm::quat* b, float t, glm::quat* out, size_t n);
// The scalar path of the array forms (what the SSE2 path is tested against).
void slerp_shorter_scalar(const glm::quat* a, const glm::quat* b, const float* t, glm::quat* out, size_t n);

}  // namespace prep
