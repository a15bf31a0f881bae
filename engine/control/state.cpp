#include "engine/control/state.h"

#include <cmath>
#include <initializer_list>
#include <stdexcept>
#include <string>

#include "engine/control/angles.h"

namespace prep {
namespace {

using control_angles::kPi;

int positive(int value, const char* field) {
  if (value <= 0) throw std::invalid_argument(std::string("quantization.") + field + " must be positive");
  return value;
}
float positive(float value, const char* field) {
  if (!(value > 0.0f)) throw std::invalid_argument(std::string("quantization.") + field + " must be positive");
  return value;
}

}  // namespace

StateSpace::StateSpace(const QuantizationParams& q, int core_motions)
    : alpha_levels_(positive(q.alpha_levels, "alpha_levels")),
      motions_(core_motions),
      d_g_bins_(positive(q.d_g_bins, "d_g_bins")),
      theta_g_bins_(positive(q.theta_g_bins, "theta_g_bins")),
      d_i_bins_(positive(q.d_i_bins, "d_i_bins")),
      theta_i_bins_(positive(q.theta_i_bins, "theta_i_bins")),
      d_step_(positive(q.d_step, "d_step")),
      theta_g_step_(positive(q.theta_g_step_deg, "theta_g_step_deg") * kPi / 180.0f),
      theta_i_step_(positive(q.theta_i_step_deg, "theta_i_step_deg") * kPi / 180.0f),
      alpha_step_(positive(q.alpha_step, "alpha_step")) {
  if (motions_ <= 0) throw std::invalid_argument("quantization.core_roles must name at least one core motion");
  if (alpha_levels_ < 2 || std::fabs(alpha_step_ * static_cast<float>(alpha_levels_ - 1) - 1.0f) > 1e-4f)
    throw std::invalid_argument("quantization: (alpha_levels - 1) * alpha_step must be 1 (alpha is forced to 1 at "
                                "the source of influence), got " +
                                std::to_string(alpha_step_ * static_cast<float>(alpha_levels_ - 1)));
  // 360 degrees must be covered by the angle bins, or some bearings would have no bin.
  if (std::fabs(theta_g_step_ * static_cast<float>(theta_g_bins_) - 2.0f * kPi) > 1e-3f)
    throw std::invalid_argument("quantization: theta_g_step_deg * theta_g_bins must be 360");
  if (std::fabs(theta_i_step_ * static_cast<float>(theta_i_bins_) - 2.0f * kPi) > 1e-3f)
    throw std::invalid_argument("quantization: theta_i_step_deg * theta_i_bins must be 360");
  // The product factor by factor, stopping past the limit: six counts of up to 2^31 each would overflow
  // even 64 bits, while a product of at most 2^30 times one count fits.
  long long n = 1;
  for (const int count : {alpha_levels_, motions_, d_g_bins_, theta_g_bins_, d_i_bins_, theta_i_bins_}) {
    n *= count;
    if (n > (1ll << 30))
      throw std::invalid_argument("quantization: too many states (more than 2^30: alpha levels " + std::to_string(alpha_levels_) +
                                  " x motions " + std::to_string(motions_) + " x bins " + std::to_string(d_g_bins_) + ", " +
                                  std::to_string(theta_g_bins_) + ", " + std::to_string(d_i_bins_) + ", " +
                                  std::to_string(theta_i_bins_) + ")");
  }
  size_ = static_cast<int>(n);
  stride_theta_g_ = d_i_bins_ * theta_i_bins_;
  stride_d_g_ = theta_g_bins_ * stride_theta_g_;
  stride_motion_ = d_g_bins_ * stride_d_g_;
  stride_alpha_ = motions_ * stride_motion_;
  inv_d_step_ = 1.0f / d_step_;
  inv_theta_g_step_ = 1.0f / theta_g_step_;
  inv_theta_i_step_ = 1.0f / theta_i_step_;
#if defined(__SSE2__)
  lanes_.inv_step = _mm_setr_ps(inv_d_step_, inv_theta_g_step_, inv_d_step_, inv_theta_i_step_);
  lanes_.offset = _mm_setr_ps(0.0f, 0.5f, 0.0f, 0.5f);
  lanes_.top = _mm_setr_ps(static_cast<float>(d_g_bins_ - 1), 0.0f, static_cast<float>(d_i_bins_ - 1), 0.0f);
  lanes_.bins = _mm_setr_epi32(d_g_bins_, theta_g_bins_, d_i_bins_, theta_i_bins_);
  lanes_.is_distance = _mm_setr_epi32(-1, 0, -1, 0);
#endif
}

int StateSpace::alpha_level(float alpha) const {
  const float k = std::round(alpha / alpha_step_);
  if (!(k > 0.0f)) return 0;
  return k >= static_cast<float>(alpha_levels_ - 1) ? alpha_levels_ - 1 : static_cast<int>(k);
}

StateBins StateSpace::decode(int index) const {
  StateBins b;
  b.theta_i = index % theta_i_bins_;
  index /= theta_i_bins_;
  b.d_i = index % d_i_bins_;
  index /= d_i_bins_;
  b.theta_g = index % theta_g_bins_;
  index /= theta_g_bins_;
  b.d_g = index % d_g_bins_;
  index /= d_g_bins_;
  b.motion = index % motions_;
  b.alpha = index / motions_;
  return b;
}

void StateSpace::distance_range(int bin, float& lo, float& hi) const {
  lo = static_cast<float>(bin) * d_step_;
  hi = lo + d_step_;
}

void StateSpace::theta_g_range(int bin, float& lo, float& hi) const {
  lo = (static_cast<float>(bin) - 0.5f) * theta_g_step_;
  hi = lo + theta_g_step_;
}

void StateSpace::theta_i_range(int bin, float& lo, float& hi) const {
  lo = (static_cast<float>(bin) - 0.5f) * theta_i_step_;
  hi = lo + theta_i_step_;
}

}  // namespace prep
