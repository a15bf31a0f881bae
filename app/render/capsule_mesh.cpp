#include "app/render/capsule_mesh.h"

#include <cmath>

namespace prep::render {

void capsule_mesh(int slices, int half_rings, std::vector<float>& vertices, std::vector<unsigned>& indices) {
  constexpr float kPi = 3.14159265358979f;
  const int rows = 2 * (half_rings + 1);
  for (int row = 0; row < rows; ++row) {
    const bool end_b = row > half_rings;
    const int k = end_b ? row - half_rings - 1 : row;
    const float latitude = end_b ? 0.5f * kPi * k / half_rings : -0.5f * kPi + 0.5f * kPi * k / half_rings;
    for (int s = 0; s <= slices; ++s) {
      const float longitude = 2.0f * kPi * s / slices;
      vertices.insert(vertices.end(), {std::cos(latitude) * std::cos(longitude), std::sin(latitude),
                                       std::cos(latitude) * std::sin(longitude), end_b ? 1.0f : 0.0f});
    }
  }
  for (int row = 0; row + 1 < rows; ++row)
    for (int s = 0; s < slices; ++s) {
      const unsigned a = row * (slices + 1) + s, b = a + slices + 1;
      indices.insert(indices.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
}

}  // namespace prep::render
