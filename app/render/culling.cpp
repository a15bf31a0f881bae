#include "app/render/culling.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace prep::render {

namespace {
// Rounding in the plane test must never leave out what the clipper would keep: spheres are grown by this
// much (m) and this fraction before they are tested.
constexpr float kSlack = 1e-4f;
}  // namespace

ClipVolume::ClipVolume(const glm::mat4& view_proj, const glm::vec3& eye, float farthest) : ClipVolume(view_proj) {
  eye_ = eye;
  farthest_ = farthest;
}

ClipVolume::ClipVolume(const glm::mat4& view_proj) : farthest_(INFINITY) {
  // A point p is inside when -w <= x, y, z <= w for (x, y, z, w) = M p: each of the six inequalities is a
  // plane, the matrix's last row plus or minus one of the others (glm stores columns: row i is m[.][i]).
  const auto row = [&](int i) { return glm::vec4(view_proj[0][i], view_proj[1][i], view_proj[2][i], view_proj[3][i]); };
  const glm::vec4 w = row(3);
  for (int axis = 0; axis < 3; ++axis) {
    planes_[2 * axis] = w + row(axis);
    planes_[2 * axis + 1] = w - row(axis);
  }
  for (glm::vec4& p : planes_) {
    const float length = glm::length(glm::vec3(p));
    if (length > 0.0f) p /= length;
  }
}

bool ClipVolume::excludes(const glm::vec3& centre, float radius) const {
  const float grown = radius * (1.0f + kSlack) + kSlack;
  for (const glm::vec4& p : planes_) {
    if (glm::dot(glm::vec3(p), centre) + p.w < -grown) return true;
  }
  return glm::length(centre - eye_) - grown > farthest_;
}

BoundingSphere bounding_sphere(const CapsuleInstance& capsule) {
  const glm::vec3 a(capsule.a_radius), b(capsule.b_glow);
  return {0.5f * (a + b), 0.5f * glm::length(b - a) + capsule.a_radius.w};
}

BoundingSphere bounding_sphere(const BoxInstance& box) {
  // The corners are the centre plus half of (+-c0 +- c1 +- c2); opposite corners are as far, so four do.
  const glm::vec3 c0(box.model[0]), c1(box.model[1]), c2(box.model[2]);
  float farthest = 0.0f;
  for (const float s1 : {-1.0f, 1.0f})
    for (const float s2 : {-1.0f, 1.0f}) farthest = std::max(farthest, glm::length(c0 + s1 * c1 + s2 * c2));
  return {glm::vec3(box.model[3]), 0.5f * farthest};
}

namespace {
template <class Instance>
void keep_visible_of(const std::vector<Instance>& in, const ClipVolume& volume, std::vector<Instance>& out) {
  out.clear();
  for (const Instance& instance : in) {
    const BoundingSphere s = bounding_sphere(instance);
    if (!volume.excludes(s.centre, s.radius)) out.push_back(instance);
  }
}
}  // namespace

void keep_visible(const std::vector<CapsuleInstance>& in, const ClipVolume& volume, std::vector<CapsuleInstance>& out) {
  keep_visible_of(in, volume, out);
}
void keep_visible(const std::vector<BoxInstance>& in, const ClipVolume& volume, std::vector<BoxInstance>& out) {
  keep_visible_of(in, volume, out);
}

void keep_visible(const std::vector<CapsuleInstance>& in, const ClipVolume& volume, const glm::vec3& eye, float distant_from,
                  std::vector<CapsuleInstance>& near, std::vector<CapsuleInstance>& distant) {
  near.clear();
  distant.clear();
  for (const CapsuleInstance& capsule : in) {
    const BoundingSphere s = bounding_sphere(capsule);
    if (volume.excludes(s.centre, s.radius)) continue;
    (glm::length(s.centre - eye) - s.radius > distant_from ? distant : near).push_back(capsule);
  }
}

}  // namespace prep::render
