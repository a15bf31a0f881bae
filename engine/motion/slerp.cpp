#include "engine/motion/slerp.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#include <xmmintrin.h>
#endif

namespace prep {
namespace {

static_assert(sizeof(glm::quat) == 4 * sizeof(float), "a quaternion is four packed floats");

constexpr int kMaxTerms = 40;  // x = 1 needs at most 22 for the last term to fall below kSmallestTerm
// A sum of the series lies in [1, pi/2] (its first term is 1, the others positive, and t sum_i is
// sin(t theta) / sin theta <= theta / sin theta <= pi/2 on the shorter arc), where a unit in the last place
// is 2^-23. A term below half of that, 2^-24, rounds away when added, and every later term is smaller still
// (each is less than half the one before): the loop stops there, and the sums are those of the whole series
// summed term by term, to the bit.
constexpr float kSmallestTerm = 0x1p-24f;

// The series' constants per term i: i^2 and 1 / (i (2i + 1)).
struct SeriesTable {
  float square[kMaxTerms + 1]{};
  float inverse[kMaxTerms + 1]{};
};
constexpr SeriesTable make_series_table() {
  SeriesTable table;
  for (int i = 1; i <= kMaxTerms; ++i) {
    table.square[i] = static_cast<float>(i * i);
    table.inverse[i] = 1.0f / static_cast<float>(i * (2 * i + 1));
  }
  return table;
}
constexpr SeriesTable kSeries = make_series_table();

// The quaternion's four numbers in memory order (the arithmetic below treats them alike, so the order
// glm stores them in does not matter).
struct Four {
  float c[4];
};
inline Four load(const glm::quat& q) {
  Four f;
  std::memcpy(f.c, &q, sizeof f.c);
  return f;
}
inline glm::quat store(const Four& f) {
  glm::quat q;
  std::memcpy(&q, f.c, sizeof f.c);
  return q;
}

// The scalar path, term for term the arithmetic of the SSE2 one.
glm::quat slerp_one(const glm::quat& qa, const glm::quat& qb, float t) {
  if (t <= 0.0f) return qa;
  if (t >= 1.0f) return qb;
  const Four a = load(qa);
  Four b = load(qb);
  float d = a.c[0] * b.c[0] + a.c[1] * b.c[1];
  d = d + a.c[2] * b.c[2];
  d = d + a.c[3] * b.c[3];
  if (d < 0.0f) {  // the shorter arc: q and -q are the same rotation
    for (float& c : b.c) c = -c;
    d = -d;
  }
  const float x = std::max(0.0f, 1.0f - d);
  const float s = 1.0f - t;
  float term_a = 1.0f, term_b = 1.0f, sum_a = 1.0f, sum_b = 1.0f;
  for (int i = 1; i <= kMaxTerms; ++i) {
    const float cx = kSeries.inverse[i] * x;
    term_a = term_a * ((kSeries.square[i] - s * s) * cx);
    term_b = term_b * ((kSeries.square[i] - t * t) * cx);
    sum_a = sum_a + term_a;
    sum_b = sum_b + term_b;
    if (!(std::max(term_a, term_b) >= kSmallestTerm)) break;
  }
  const float weight_a = s * sum_a, weight_b = t * sum_b;
  Four q;
  for (int c = 0; c < 4; ++c) q.c[c] = weight_a * a.c[c] + weight_b * b.c[c];
  float length2 = q.c[0] * q.c[0] + q.c[1] * q.c[1];
  length2 = length2 + q.c[2] * q.c[2];
  length2 = length2 + q.c[3] * q.c[3];
  const float length = std::sqrt(length2);
  for (float& c : q.c) c = c / length;
  return store(q);
}

#if defined(__SSE2__)
inline __m128 select(__m128 mask, __m128 if_set, __m128 if_clear) {
  return _mm_or_ps(_mm_and_ps(mask, if_set), _mm_andnot_ps(mask, if_clear));
}

// Four rotations: the quaternions transposed so that each register holds one number of all four.
void slerp_four(const glm::quat* qa, const glm::quat* qb, __m128 t, glm::quat* out) {
  const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f);
  // t <= 0 keeps a, t >= 1 takes b as given (as slerp_one); when every lane does, nothing else is needed.
  const __m128 at_a = _mm_cmple_ps(t, zero), at_b = _mm_cmpge_ps(t, one);
  const int taken_a = _mm_movemask_ps(at_a), taken_b = _mm_movemask_ps(at_b);
  if ((taken_a | taken_b) == 0xF) {
    for (int k = 0; k < 4; ++k) out[k] = (taken_a >> k) & 1 ? qa[k] : qb[k];
    return;
  }
  const float* fa = reinterpret_cast<const float*>(qa);
  const float* fb = reinterpret_cast<const float*>(qb);
  __m128 a0 = _mm_loadu_ps(fa), a1 = _mm_loadu_ps(fa + 4), a2 = _mm_loadu_ps(fa + 8), a3 = _mm_loadu_ps(fa + 12);
  __m128 b0 = _mm_loadu_ps(fb), b1 = _mm_loadu_ps(fb + 4), b2 = _mm_loadu_ps(fb + 8), b3 = _mm_loadu_ps(fb + 12);
  _MM_TRANSPOSE4_PS(a0, a1, a2, a3);
  _MM_TRANSPOSE4_PS(b0, b1, b2, b3);
  __m128 d = _mm_add_ps(_mm_mul_ps(a0, b0), _mm_mul_ps(a1, b1));
  d = _mm_add_ps(d, _mm_mul_ps(a2, b2));
  d = _mm_add_ps(d, _mm_mul_ps(a3, b3));
  const __m128 flip = _mm_and_ps(_mm_cmplt_ps(d, zero), _mm_set1_ps(-0.0f));  // the sign bit where d < 0
  const __m128 f0 = _mm_xor_ps(b0, flip), f1 = _mm_xor_ps(b1, flip), f2 = _mm_xor_ps(b2, flip), f3 = _mm_xor_ps(b3, flip);
  d = _mm_xor_ps(d, flip);
  // A lane that takes a or b as given needs no series: its x is taken as 0, so its terms vanish and do
  // not keep the loop going. The other lanes' sums are the same to the bit: the loop only ever runs on past
  // a lane once its terms are below kSmallestTerm, half a unit in the last place of its sum, which adding
  // them leaves as it is.
  const __m128 x = _mm_andnot_ps(_mm_or_ps(at_a, at_b), _mm_max_ps(zero, _mm_sub_ps(one, d)));
  const __m128 tc = _mm_min_ps(_mm_max_ps(t, zero), one);
  const __m128 s = _mm_sub_ps(one, tc);
  const __m128 s2 = _mm_mul_ps(s, s), t2 = _mm_mul_ps(tc, tc);
  const __m128 smallest = _mm_set1_ps(kSmallestTerm);
  __m128 term_a = one, term_b = one, sum_a = one, sum_b = one;
  for (int i = 1; i <= kMaxTerms; ++i) {
    const __m128 cx = _mm_mul_ps(_mm_set1_ps(kSeries.inverse[i]), x);
    const __m128 square = _mm_set1_ps(kSeries.square[i]);
    term_a = _mm_mul_ps(term_a, _mm_mul_ps(_mm_sub_ps(square, s2), cx));
    term_b = _mm_mul_ps(term_b, _mm_mul_ps(_mm_sub_ps(square, t2), cx));
    sum_a = _mm_add_ps(sum_a, term_a);
    sum_b = _mm_add_ps(sum_b, term_b);
    if (_mm_movemask_ps(_mm_cmpge_ps(_mm_max_ps(term_a, term_b), smallest)) == 0) break;
  }
  const __m128 weight_a = _mm_mul_ps(s, sum_a), weight_b = _mm_mul_ps(tc, sum_b);
  __m128 q0 = _mm_add_ps(_mm_mul_ps(weight_a, a0), _mm_mul_ps(weight_b, f0));
  __m128 q1 = _mm_add_ps(_mm_mul_ps(weight_a, a1), _mm_mul_ps(weight_b, f1));
  __m128 q2 = _mm_add_ps(_mm_mul_ps(weight_a, a2), _mm_mul_ps(weight_b, f2));
  __m128 q3 = _mm_add_ps(_mm_mul_ps(weight_a, a3), _mm_mul_ps(weight_b, f3));
  __m128 length2 = _mm_add_ps(_mm_mul_ps(q0, q0), _mm_mul_ps(q1, q1));
  length2 = _mm_add_ps(length2, _mm_mul_ps(q2, q2));
  length2 = _mm_add_ps(length2, _mm_mul_ps(q3, q3));
  const __m128 length = _mm_sqrt_ps(length2);
  q0 = _mm_div_ps(q0, length);
  q1 = _mm_div_ps(q1, length);
  q2 = _mm_div_ps(q2, length);
  q3 = _mm_div_ps(q3, length);
  if ((taken_a | taken_b) != 0) {  // (usually no lane is at an end)
    q0 = select(at_a, a0, select(at_b, b0, q0));
    q1 = select(at_a, a1, select(at_b, b1, q1));
    q2 = select(at_a, a2, select(at_b, b2, q2));
    q3 = select(at_a, a3, select(at_b, b3, q3));
  }
  _MM_TRANSPOSE4_PS(q0, q1, q2, q3);
  float* fo = reinterpret_cast<float*>(out);
  _mm_storeu_ps(fo, q0);
  _mm_storeu_ps(fo + 4, q1);
  _mm_storeu_ps(fo + 8, q2);
  _mm_storeu_ps(fo + 12, q3);
}
#endif

}  // namespace

glm::quat slerp_shorter(const glm::quat& a, const glm::quat& b, float t) { return slerp_one(a, b, t); }

void slerp_shorter_scalar(const glm::quat* a, const glm::quat* b, const float* t, glm::quat* out, size_t n) {
  for (size_t i = 0; i < n; ++i) out[i] = slerp_one(a[i], b[i], t[i]);
}

void slerp_shorter(const glm::quat* a, const glm::quat* b, const float* t, glm::quat* out, size_t n) {
  size_t i = 0;
#if defined(__SSE2__)
  for (; i + 4 <= n; i += 4) slerp_four(a + i, b + i, _mm_loadu_ps(t + i), out + i);
#endif
  for (; i < n; ++i) out[i] = slerp_one(a[i], b[i], t[i]);
}

void slerp_shorter(const glm::quat* a, const glm::quat* b, float t, glm::quat* out, size_t n) {
  size_t i = 0;
#if defined(__SSE2__)
  for (; i + 4 <= n; i += 4) slerp_four(a + i, b + i, _mm_set1_ps(t), out + i);
#endif
  for (; i < n; ++i) out[i] = slerp_one(a[i], b[i], t);
}

}  // namespace prep
