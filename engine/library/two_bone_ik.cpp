#include "engine/library/two_bone_ik.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

namespace prep::library {

TwoBoneSolution solve_two_bone(const TwoBoneChain& chain, glm::vec3 root, glm::vec3 target, glm::vec3 bend_hint) {
  TwoBoneSolution out;
  const float l1 = chain.upper_length, l2 = chain.lower_length;
  glm::vec3 to_target = target - root;
  float d = glm::length(to_target);
  const glm::vec3 dir = d > 1e-6f ? to_target / d : glm::vec3(0, -1, 0);
  const float d_max = (l1 + l2) * 0.99999f, d_min = std::fabs(l1 - l2) + 1e-4f;
  if (d > d_max + 1e-5f) out.reached = false;
  d = std::clamp(d, d_min, d_max);
  // The bend direction: the hint without its component along the limb (any perpendicular if degenerate).
  glm::vec3 perp = bend_hint - glm::dot(bend_hint, dir) * dir;
  if (glm::length(perp) < 1e-5f) perp = glm::cross(dir, std::fabs(dir.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1));
  perp = glm::normalize(perp);
  // Law of cosines: distance a along the limb to the foot of the middle joint, height h of the bend.
  const float a = (l1 * l1 - l2 * l2 + d * d) / (2.0f * d);
  const float h = std::sqrt(std::max(0.0f, l1 * l1 - a * a));
  const glm::vec3 middle = root + a * dir + h * perp;
  const glm::vec3 u = (middle - root) / l1;
  const glm::vec3 v = glm::normalize(root + d * dir - middle);
  // The hinge axis is perpendicular to the limb's plane, oriented so that + rotation turns u toward v.
  const glm::vec3 n = glm::normalize(glm::cross(perp, dir));
  const glm::mat3 world(u, n, glm::cross(u, n));
  const glm::vec3 rd = glm::normalize(chain.rest_direction), rh = glm::normalize(chain.hinge_axis);
  const glm::mat3 local(rd, rh, glm::cross(rd, rh));
  out.upper_world = glm::normalize(glm::quat_cast(world * glm::transpose(local)));
  out.hinge_angle = std::acos(std::clamp(glm::dot(u, v), -1.0f, 1.0f));
  return out;
}

}  // namespace prep::library
