// Leaving out, before a pass is drawn, the instances it could not show: on llvmpipe every instance sent
// is shaded vertex by vertex on one thread before the clipper throws it away, and a crowd seen from one
// end, or a shadow map covering a few metres of a stadium, throws most of them away.
//
// A bounding sphere is tested against the six planes of a view-projection's clip volume: an instance is
// left out only when its sphere lies wholly outside one plane, where the clipper would have removed every
// one of its triangles. In the main pass an instance wholly beyond the distance where the fog is full is
// left out too: there it, and the floor behind it, would be the sky's colour.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <vector>

#include "app/render/instances.h"

namespace prep::render {

// The clip volume of a view-projection matrix as six planes (a, b, c, d) with a x + b y + c z + d >= 0
// inside, normalized so that the left side is a distance in world units.
class ClipVolume {
 public:
  explicit ClipVolume(const glm::mat4& view_proj);
  // Also excluding what lies wholly farther than `farthest` from `eye`.
  ClipVolume(const glm::mat4& view_proj, const glm::vec3& eye, float farthest);
  // True when the sphere lies wholly outside one of the planes (so nothing of it can be seen).
  bool excludes(const glm::vec3& centre, float radius) const;

 private:
  glm::vec4 planes_[6];
  glm::vec3 eye_{0.0f};
  float farthest_;
};

// The spheres holding an instance's whole shape.
struct BoundingSphere {
  glm::vec3 centre;
  float radius;
};
BoundingSphere bounding_sphere(const CapsuleInstance& capsule);
BoundingSphere bounding_sphere(const BoxInstance& box);  // the unit cube's corners after the model matrix

// `out` = the instances of `in` that the clip volume does not exclude, in their order.
void keep_visible(const std::vector<CapsuleInstance>& in, const ClipVolume& volume, std::vector<CapsuleInstance>& out);
// The same, the capsules kept split by their distance from `eye`: those wholly farther than `distant_from`
// into `distant`, the others into `near`.
void keep_visible(const std::vector<CapsuleInstance>& in, const ClipVolume& volume, const glm::vec3& eye, float distant_from,
                  std::vector<CapsuleInstance>& near, std::vector<CapsuleInstance>& distant);
void keep_visible(const std::vector<BoxInstance>& in, const ClipVolume& volume, std::vector<BoxInstance>& out);

}  // namespace prep::render
