#include "engine/synthesis/blending.h"

#include "engine/motion/slerp.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>

namespace prep {

BlendCurves make_blend_curves(const Skeleton& skeleton, const BodyMap& body, const BlendParams& params) {
  const int n = skeleton.size();
  static std::atomic<std::uint64_t> next_id{1};
  BlendCurves curves;
  curves.id = next_id++;
  if (params.method == "linear") {
    curves.linear = true;
  } else if (params.method != "ours") {
    throw std::invalid_argument("blend.method must be \"ours\" or \"linear\", not \"" + params.method + "\"");
  }
  curves.root = body.root;
  curves.C.assign(static_cast<size_t>(n), params.C_lower);
  curves.c.assign(static_cast<size_t>(n), params.c_scale);
  for (int i = 0; i < n; ++i) {
    if (i < static_cast<int>(body.upper_body.size()) && body.upper_body[static_cast<size_t>(i)]) {
      curves.C[static_cast<size_t>(i)] = params.C_upper;
    }
  }
  for (const auto& [name, value] : params.C_override) {
    const int j = skeleton.find(name);
    if (j < 0) throw std::invalid_argument("blend.C_override names no joint of the skeleton: \"" + name + "\"");
    curves.C[static_cast<size_t>(j)] = value;
  }
  for (const auto& [name, value] : params.c_override) {
    const int j = skeleton.find(name);
    if (j < 0) throw std::invalid_argument("blend.c_override names no joint of the skeleton: \"" + name + "\"");
    curves.c[static_cast<size_t>(j)] = value;
  }
  for (int i = 0; i < n; ++i) {
    if (!(curves.C[static_cast<size_t>(i)] > 0.0f)) {
      throw std::invalid_argument("blend: C_i of joint \"" + skeleton.joints[static_cast<size_t>(i)].name +
                                  "\" must be positive");
    }
  }
  for (int i = 0; i < n; ++i) {
    const float C = curves.C[static_cast<size_t>(i)], c = curves.c[static_cast<size_t>(i)];
    size_t k = 0;
    while (k < curves.curve_C.size() && !(curves.curve_C[k] == C && curves.curve_c[k] == c)) ++k;
    if (k == curves.curve_C.size()) {
      curves.curve_C.push_back(C);
      curves.curve_c.push_back(c);
    }
    curves.curve_of_joint.push_back(static_cast<int>(k));
  }
  return curves;
}

float blend_weight(float alpha, float C, float c) {
  const float a = std::clamp(alpha, 0.0f, 1.0f);
  return c * std::sqrt(1.0f - std::pow(1.0f - a, C));  // Eq. 1
}

void blend_weights(const BlendCurves& curves, float alpha, float* weights) {
  const size_t n = curves.C.size();
  if (curves.linear) {
    std::fill(weights, weights + n, std::clamp(alpha, 0.0f, 1.0f));
    return;
  }
  if (curves.curve_of_joint.size() != n || curves.curve_C.size() > 8) {  // curves built by hand, or many shapes
    for (size_t i = 0; i < n; ++i) weights[i] = blend_weight(alpha, curves.C[i], curves.c[i]);
    return;
  }
  float per_curve[8];
  for (size_t k = 0; k < curves.curve_C.size(); ++k) per_curve[k] = blend_weight(alpha, curves.curve_C[k], curves.curve_c[k]);
  for (size_t i = 0; i < n; ++i) weights[i] = per_curve[curves.curve_of_joint[i]];
}

glm::quat blend_rotation(const glm::quat& from, const glm::quat& to, float w) { return slerp_shorter(from, to, w); }

void blend_joint_rotations(const Pose& locomotion, const Pose& reference, const float* weights, Pose& out) {
  const size_t n = locomotion.rotations.size();
  if (n < 2) return;
  // Eq. 2 for every joint but the root (blend_root_rotation), four joints at a time.
  slerp_shorter(locomotion.rotations.data() + 1, reference.rotations.data() + 1, weights + 1, out.rotations.data() + 1, n - 1);
}

}  // namespace prep
