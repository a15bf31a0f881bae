// Sec. 6.1, Eq. 11 and Table I: the controller's state s = {alpha, m, d_g, theta_g, d_i, theta_i} and its
// quantization.
//
// Our reading of the state count. Table I prints 5 samples of alpha, but 4 core motions x 5 x 5 x 8 x 5 x 4
// gives 16,000, not the 19,200 the paper reports. 19,200 = 4 core motions x 6 alpha levels (0, 0.2, ..., 1.0:
// a step of 0.2 from 0 to 1 inclusive has six samples) x 5 d_g x 8 theta_g x 5 d_i x 4 theta_i. So the
// paper's configuration has alpha_levels = 6, and "Next(m)" in Eq. 11 is represented by the last motion m
// (it fixes which actions are allowed). Table I's 5 samples are then the levels an action chooses from
// (0 .. 0.8, QuantizationParams::forced_top_level): the state's sixth level, 1, comes only from the
// forcing at the source (Eq. 13's override), which is the one thing Table I's count leaves out.
//
// Bins (all from QuantizationParams):
// - distances d_g, d_i: bin k holds [k * d_step, (k + 1) * d_step); a distance beyond the last bin clamps
//   into the last bin (so the last bin means "that far or farther").
// - angles theta_g, theta_i: relative bearing of the goal / source from the character's facing, in
//   (-pi, pi], positive to the character's left (counter-clockwise seen from above, +Y up). The bins are
//   centred on straight ahead: bin 0 holds [-step/2, step/2), bin k holds [k*step - step/2, k*step + step/2)
//   modulo a full turn, counting counter-clockwise. With 45 degrees x 8, bin 0 is "facing the goal"; with
//   90 degrees x 4, the source is ahead, left, behind or right.
// - alpha: level l is alpha = l * alpha_step; an alpha between levels goes to the nearest level.
#pragma once

#include <algorithm>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "engine/params/params.h"

namespace prep {

// The state's components as bin indices.
struct StateBins {
  int alpha = 0;    // level index
  int motion = 0;   // index of the last core motion played
  int d_g = 0;
  int theta_g = 0;
  int d_i = 0;
  int theta_i = 0;
};

// The quantized state space. Cheap to copy; every function is inline-fast (called per training step).
class StateSpace {
 public:
  // Throws std::invalid_argument naming the field if a count or step is not positive, or if the top alpha
  // level is not 1 (alpha is forced to 1 at the source of influence, which must be a level).
  // core_motions: how many core motions the action table has (core_clips in action_effects.h).
  StateSpace(const QuantizationParams& q, int core_motions);

  int size() const { return size_; }
  int alpha_levels() const { return alpha_levels_; }
  int motions() const { return motions_; }
  int d_g_bins() const { return d_g_bins_; }
  int theta_g_bins() const { return theta_g_bins_; }
  int d_i_bins() const { return d_i_bins_; }
  int theta_i_bins() const { return theta_i_bins_; }

  float alpha_of(int level) const { return static_cast<float>(level) * alpha_step_; }
  int alpha_level(float alpha) const;  // nearest level, clamped
  int top_alpha_level() const { return alpha_levels_ - 1; }

  int d_g_bin(float d) const { return distance_bin(d, inv_d_step_, d_g_bins_); }
  int d_i_bin(float d) const { return distance_bin(d, inv_d_step_, d_i_bins_); }
  int theta_g_bin(float theta) const { return angle_bin(theta, inv_theta_g_step_, theta_g_bins_); }
  int theta_i_bin(float theta) const { return angle_bin(theta, inv_theta_i_step_, theta_i_bins_); }

  // Eq. 11 flattened: alpha is the slowest-varying component, theta_i the fastest.
  int index(const StateBins& b) const {
    // The same integer as the nested form ((((alpha M + m) D_g + d_g) ...) T_i + theta_i, by strides: the
    // products do not wait on one another.
    return b.alpha * stride_alpha_ + b.motion * stride_motion_ + b.d_g * stride_d_g_ + b.theta_g * stride_theta_g_ +
           b.d_i * theta_i_bins_ + b.theta_i;
  }
  StateBins decode(int index) const;

  // Eq. 11 from the continuous components: index() of the four bins above. Where SSE2 is there the four
  // bins are taken together, lane by lane with the same float operations as d_g_bin ... theta_i_bin (a
  // distance lane adds 0 where a bearing adds 0.5, which changes no bin), falling back to them for
  // anything out of the ordinary (a bearing more than a turn off, NaN). Per training step.
  int index_of(int alpha, int motion, float d_g, float theta_g, float d_i, float theta_i) const {
#if defined(__SSE2__)
    const __m128 k = _mm_add_ps(_mm_mul_ps(_mm_setr_ps(d_g, theta_g, d_i, theta_i), lanes_.inv_step), lanes_.offset);
    // Distances: std::min(top, std::max(0, k)), i.e. c = k > 0 ? k : 0 (NaN: 0), then c < top ? c : top.
    const __m128i distance = _mm_cvttps_epi32(_mm_min_ps(_mm_max_ps(k, _mm_setzero_ps()), lanes_.top));
    // Bearings: the floor of k, then one turn up below 0.
    const __m128 in_range = _mm_and_ps(_mm_cmpgt_ps(k, _mm_set1_ps(-1e6f)), _mm_cmplt_ps(k, _mm_set1_ps(1e6f)));
    const __m128i truncated = _mm_cvttps_epi32(k);
    const __m128i floor_k = _mm_add_epi32(truncated, _mm_castps_si128(_mm_cmplt_ps(k, _mm_cvtepi32_ps(truncated))));
    const __m128i turn = _mm_and_si128(lanes_.bins, _mm_cmplt_epi32(floor_k, _mm_setzero_si128()));
    const __m128i bearing = _mm_add_epi32(floor_k, turn);
    const __m128i bearing_ok = _mm_and_si128(_mm_cmpgt_epi32(bearing, _mm_set1_epi32(-1)), _mm_cmplt_epi32(bearing, lanes_.bins));
    const __m128i ok = _mm_or_si128(lanes_.is_distance, _mm_and_si128(_mm_castps_si128(in_range), bearing_ok));
    if (_mm_movemask_epi8(ok) == 0xFFFF) {
      const __m128i bins = _mm_or_si128(_mm_and_si128(lanes_.is_distance, distance), _mm_andnot_si128(lanes_.is_distance, bearing));
      alignas(16) int b[4];
      _mm_store_si128(reinterpret_cast<__m128i*>(b), bins);
      return index({alpha, motion, b[0], b[1], b[2], b[3]});
    }
#endif
    return index({alpha, motion, d_g_bin(d_g), theta_g_bin(theta_g), d_i_bin(d_i), theta_i_bin(theta_i)});
  }

  // The continuous extent of a bin, for exploring starts: [lo, hi) in metres or radians (angles relative to
  // facing). The last distance bin is sampled as [k * step, (k + 1) * step).
  void distance_range(int bin, float& lo, float& hi) const;
  void theta_g_range(int bin, float& lo, float& hi) const;
  void theta_i_range(int bin, float& lo, float& hi) const;

  float d_step() const { return d_step_; }
  float theta_g_step() const { return theta_g_step_; }
  float theta_i_step() const { return theta_i_step_; }
  float alpha_step() const { return alpha_step_; }

  // Both bins are computed without data-dependent branches in the usual case (a training step takes four
  // bins of random-signed bearings and varying distances; mispredicted branches were a third of its time).
  static int distance_bin(float d, float inv_step, int bins) {
    const float k = d * inv_step, top = static_cast<float>(bins - 1);
    // std::max(0, k) is k > 0 ? k : 0 (NaN: 0) and std::min(top, c) is c < top ? c : top: maxss and minss.
    return static_cast<int>(std::min(top, std::max(0.0f, k)));  // below 0 and NaN: bin 0
  }
  // theta in radians, any value (wrapped). Bins centred on 0, counted counter-clockwise.
  static int angle_bin(float theta, float inv_step, int bins) {
    const float k = theta * inv_step + 0.5f;
    if (!(k > -1e6f && k < 1e6f)) return 0;  // NaN or absurd input: never undefined behaviour
    const int truncated = static_cast<int>(k);
    const int floor_k = truncated - (k < static_cast<float>(truncated) ? 1 : 0);  // truncation is toward zero
    const int b = floor_k + (bins & -static_cast<int>(floor_k < 0));  // theta in (-pi, 0): one turn up
    if (b >= 0 && b < bins) return b;  // theta in (-pi, pi] is at most one turn off: no division
    const int wrapped = floor_k % bins;
    return wrapped < 0 ? wrapped + bins : wrapped;
  }

 private:
  int alpha_levels_, motions_, d_g_bins_, theta_g_bins_, d_i_bins_, theta_i_bins_;
  int size_;
  int stride_alpha_, stride_motion_, stride_d_g_, stride_theta_g_;  // index(): states per step of each component
#if defined(__SSE2__)
  struct Lanes {  // index_of(): per lane d_g, theta_g, d_i, theta_i
    __m128 inv_step, offset, top;
    __m128i bins, is_distance;
  } lanes_;
#endif
  float d_step_, theta_g_step_, theta_i_step_, alpha_step_;
  float inv_d_step_, inv_theta_g_step_, inv_theta_i_step_;
};

}  // namespace prep
