#include "app/render/meshes.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace prep::render {

namespace {
constexpr float kPi = 3.14159265358979f;
}  // namespace

// A's pole, then rings of `slices` vertices from A's cap up to B's, then B's pole; the band between A's
// equator and B's equator is the cylinder. Each pole is one vertex and each ring closes on its first
// vertex: no seam copies and no zero-area triangles at the poles, which a software rasterizer would still
// transform and set up.
void capsule_mesh(int slices, int half_rings, std::vector<float>& vertices, std::vector<unsigned>& indices) {
  const int rings = 2 * half_rings;  // A's rings from just above its pole to its equator, then B's
  vertices.insert(vertices.end(), {0.0f, -1.0f, 0.0f, 0.0f});  // A's pole
  for (int ring = 0; ring < rings; ++ring) {
    const bool end_b = ring >= half_rings;
    const int k = end_b ? ring - half_rings : ring + 1;
    const float latitude = end_b ? 0.5f * kPi * k / half_rings : -0.5f * kPi + 0.5f * kPi * k / half_rings;
    for (int s = 0; s < slices; ++s) {
      const float longitude = 2.0f * kPi * s / slices;
      vertices.insert(vertices.end(), {std::cos(latitude) * std::cos(longitude), std::sin(latitude),
                                       std::cos(latitude) * std::sin(longitude), end_b ? 1.0f : 0.0f});
    }
  }
  vertices.insert(vertices.end(), {0.0f, 1.0f, 0.0f, 1.0f});  // B's pole
  const auto at = [slices](int ring, int s) { return static_cast<unsigned>(1 + ring * slices + s % slices); };
  const unsigned pole_b = static_cast<unsigned>(1 + rings * slices);
  for (int s = 0; s < slices; ++s) {
    indices.insert(indices.end(), {0u, at(0, s), at(0, s + 1)});
    for (int ring = 0; ring + 1 < rings; ++ring) {
      const unsigned a = at(ring, s), a1 = at(ring, s + 1), b = at(ring + 1, s), b1 = at(ring + 1, s + 1);
      indices.insert(indices.end(), {a, b, a1, a1, b, b1});
    }
    indices.insert(indices.end(), {at(rings - 1, s), pole_b, at(rings - 1, s + 1)});
  }
}

void cube_mesh(std::vector<float>& vertices, std::vector<unsigned>& indices) {
  const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const glm::vec3& n : normals) {
    const glm::vec3 u = std::fabs(n.y) > 0.5f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    const glm::vec3 v = glm::cross(n, u);
    const unsigned base = static_cast<unsigned>(vertices.size() / 6);
    for (int corner = 0; corner < 4; ++corner) {
      const float su = (corner == 1 || corner == 2) ? 0.5f : -0.5f, sv = corner >= 2 ? 0.5f : -0.5f;
      const glm::vec3 p = 0.5f * n + su * u + sv * v;
      vertices.insert(vertices.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
    }
    indices.insert(indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  }
}

}  // namespace prep::render
